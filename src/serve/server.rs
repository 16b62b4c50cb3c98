//! The accept loop: admits connections within the limits, runs each in its own task (so no
//! session's panic or error reaches the loop) under the login grace deadline, logs connect and
//! disconnect with the duration.
//!
//! A connection turned away at accept (per-address or start-up limit, server full) is told why
//! without any key exchange: one text line before the SSH version line (RFC 4253 §4.2 allows
//! such lines, but OpenSSH's `ssh` shows them only with `-v`), the version line, then an
//! unencrypted SSH_MSG_DISCONNECT carrying the reason, which plain `ssh` prints as
//! "Received disconnect from HOST port PORT:12: REASON". One refused later (server full at
//! login, login grace over) gets the disconnect message inside the encrypted session.

use std::io;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use russh::server::Config;
use russh::{compression, Preferred};
use tokio::net::TcpListener;
use tokio::sync::watch;
use tokio::task::JoinHandle;

use super::auth::Backoff;
use super::avatars::with_avatar_sheet;
use super::config::ServeConfig;
use super::handler::{ConnHandler, Shared};
use super::hostkey;
use super::lifecycle::Lifeline;
use super::limits::{Caps, Limiter, Refusal};
use super::log::Log;
use super::stats::{ServeStats, StatsSnapshot};
use super::world_task::spawn_game;
use crate::world::World;

/// Compression offered to clients, most preferred first: the delayed `zlib@openssh.com`
/// (what OpenSSH's `ssh -C` asks for), plain `zlib`, or none.
const COMPRESSION: &[compression::Name] = &[
    compression::ZLIB_LEGACY,
    compression::ZLIB,
    compression::NONE,
];

/// A server started by [`start`]; stop it with [`RunningServer::shutdown`].
pub struct RunningServer {
    addr: SocketAddr,
    stats: Arc<ServeStats>,
    limiter: Limiter,
    shutdown: watch::Sender<bool>,
    accept: JoinHandle<()>,
}

impl RunningServer {
    /// The address actually bound (useful with port 0).
    #[must_use]
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// Totals so far.
    #[must_use]
    pub fn stats(&self) -> StatsSnapshot {
        self.stats.snapshot()
    }

    /// Connections (logging in, playing or watching) the limits count right now, so callers can
    /// wait for the server to have noticed an arrival or a departure instead of guessing a delay.
    #[must_use]
    pub fn live(&self) -> (usize, usize) {
        self.limiter.live()
    }

    /// Stops accepting, tells every session to end, and waits (up to a few seconds) for them;
    /// returns the totals after that, so sessions that were still running count too.
    pub async fn shutdown(self) -> StatsSnapshot {
        let _ = self.shutdown.send(true);
        let _ = self.accept.await;
        for _ in 0..50 {
            if self.stats.snapshot().sessions_live == 0 {
                break;
            }
            tokio::time::sleep(Duration::from_millis(40)).await;
        }
        self.stats.snapshot()
    }
}

/// Binds, loads or creates the host key, starts the world and the accept loop.
///
/// # Errors
/// A message when the address cannot be bound or the host key cannot be read or created.
pub async fn start(config: ServeConfig, world: World) -> Result<RunningServer, String> {
    let log = Log::new(config.quiet);
    let (key, notes) = hostkey::load_or_generate(&config.host_key, config.insecure_host_key)?;
    for n in notes {
        log.server(n);
    }
    let listener = TcpListener::bind(config.listen)
        .await
        .map_err(|e| format!("cannot listen on {}: {e}", config.listen))?;
    let addr = listener.local_addr().map_err(|e| e.to_string())?;
    let ssh = Arc::new(Config {
        methods: config.auth.methods(),
        keys: vec![key],
        // The least a rejection waits; the handler adds a delay growing per source address.
        auth_rejection_time: Duration::from_millis(300),
        auth_rejection_time_initial: Some(Duration::ZERO),
        // russh counts every rejected request, the `none` probe included.
        max_auth_attempts: config.max_auth_tries,
        // Before a shell starts the login grace time applies (enforced by serve_connection).
        inactivity_timeout: Some(config.idle_timeout),
        keepalive_interval: Some(Duration::from_secs(30)),
        keepalive_max: 3,
        // Few internal messages per connection: frames wait here at most this many deep.
        event_buffer_size: 4,
        nodelay: true,
        preferred: Preferred {
            compression: std::borrow::Cow::Borrowed(COMPRESSION),
            ..Preferred::default()
        },
        ..Config::default()
    });
    let limiter = Limiter::new(
        Caps {
            max_sessions: config.max_sessions,
            max_per_ip: config.max_per_ip,
            startups: config.max_startups,
            startups_per_ip: config.max_startups_per_ip,
        },
        config.seed,
    );
    let (world, avatar_sheet) = with_avatar_sheet(world);
    let world = Arc::new(world);
    let (shutdown_tx, shutdown_rx) = watch::channel(false);
    let stats = Arc::new(ServeStats::default());
    let shared = Arc::new(Shared {
        world: spawn_game(Arc::clone(&world), config.tick_hz, config.mode, config.seed),
        world_data: world,
        avatar_sheet,
        stats: Arc::clone(&stats),
        log,
        shutdown: shutdown_rx.clone(),
        limiter: limiter.clone(),
        backoff: Backoff::default(),
        config,
    });
    log.server(format_args!("listening on {addr}"));
    let accept = tokio::spawn(accept_loop(listener, ssh, shared, shutdown_rx));
    Ok(RunningServer {
        addr,
        stats,
        limiter,
        shutdown: shutdown_tx,
        accept,
    })
}

/// Refused sockets at most lingering at once to deliver their reason (beyond, just closed).
const MAX_LINGERING: usize = 64;
/// How long a refused socket lingers so its reason line arrives before the close.
const LINGER: Duration = Duration::from_millis(500);

async fn accept_loop(
    listener: TcpListener,
    ssh: Arc<Config>,
    shared: Arc<Shared>,
    mut shutdown: watch::Receiver<bool>,
) {
    let next_id = AtomicU64::new(1);
    let lingering = Arc::new(AtomicU64::new(0));
    loop {
        let (socket, peer) = tokio::select! {
            _ = shutdown.changed() => return,
            r = listener.accept() => match r {
                Ok(x) => x,
                Err(e) => {
                    // E.g. out of file descriptors: back off instead of spinning.
                    shared.log.server(format_args!("accept failed: {e}"));
                    tokio::time::sleep(Duration::from_millis(100)).await;
                    continue;
                }
            },
        };
        let accepted = Instant::now();
        let pending = match shared.limiter.admit(peer.ip()) {
            Ok(s) => s,
            Err(why) => {
                ServeStats::add(&shared.stats.refused, 1);
                let (logging_in, playing) = shared.limiter.live();
                shared.log.server(format_args!(
                    "refused {peer}: {why} ({logging_in} logging in, {playing} playing)"
                ));
                refuse(socket, why, &lingering);
                continue;
            }
        };
        ServeStats::add(&shared.stats.connections, 1);
        let id = next_id.fetch_add(1, Ordering::Relaxed);
        let ssh = Arc::clone(&ssh);
        let shared = Arc::clone(&shared);
        tokio::spawn(async move {
            shared.log.session(id, peer, "connected");
            let life = Arc::new(Lifeline::default());
            let handler =
                ConnHandler::new(id, peer, Arc::clone(&shared), pending, Arc::clone(&life));
            let deadline = accepted + shared.config.login_grace;
            let result = serve_connection(
                ssh,
                socket,
                handler,
                &life,
                deadline,
                shared.shutdown.clone(),
            )
            .await;
            let secs = accepted.elapsed().as_secs_f64();
            match result {
                Ok(()) => {
                    shared
                        .log
                        .session(id, peer, format_args!("disconnected after {secs:.1} s"))
                }
                Err(e) => shared.log.session(
                    id,
                    peer,
                    format_args!("disconnected after {secs:.1} s: {e}"),
                ),
            }
        });
    }
}

/// SSH_DISCONNECT_TOO_MANY_CONNECTIONS (RFC 4250 §4.2.2).
const TOO_MANY_CONNECTIONS: u32 = 12;

/// What a refused client is sent, all before any key exchange: the reason as a text line
/// (shown by `ssh -v`, netcat, paramiko's log), our version line, and the reason again as an
/// SSH_MSG_DISCONNECT in the binary packet format with no encryption and no MAC (RFC 4253 §6),
/// which is what every SSH client reads next and what plain `ssh` prints.
#[must_use]
pub fn refusal_bytes(why: &Refusal) -> Vec<u8> {
    let reason = format!("halfcast: {why}");
    let mut out = format!("{reason}\r\nSSH-2.0-halfcast\r\n").into_bytes();
    let mut payload = vec![1u8]; // SSH_MSG_DISCONNECT
    payload.extend_from_slice(&TOO_MANY_CONNECTIONS.to_be_bytes());
    for s in [reason.as_str(), ""] {
        payload.extend_from_slice(&(s.len() as u32).to_be_bytes());
        payload.extend_from_slice(s.as_bytes());
    }
    // Length field, padding-length byte, payload and padding make a multiple of 8, with at
    // least 4 bytes of padding.
    let mut padding = 8 - (4 + 1 + payload.len()) % 8;
    if padding < 4 {
        padding += 8;
    }
    let packet_len = (1 + payload.len() + padding) as u32;
    out.extend_from_slice(&packet_len.to_be_bytes());
    out.push(padding as u8);
    out.extend_from_slice(&payload);
    out.extend(std::iter::repeat_n(0u8, padding));
    out
}

/// Tells a refused client why (see [`refusal_bytes`]), then closes; the socket lingers briefly
/// (a bounded number at once) so the reason is not lost to a reset.
fn refuse(socket: tokio::net::TcpStream, why: Refusal, lingering: &Arc<AtomicU64>) {
    // A fresh socket's send buffer is empty: this never blocks, and a short write is dropped.
    let _ = socket.try_write(&refusal_bytes(&why));
    if lingering.load(Ordering::Relaxed) >= MAX_LINGERING as u64 {
        return;
    }
    lingering.fetch_add(1, Ordering::Relaxed);
    let lingering = Arc::clone(lingering);
    tokio::spawn(async move {
        use tokio::io::{AsyncReadExt, AsyncWriteExt};
        let mut socket = socket;
        let _ = tokio::time::timeout(LINGER, async {
            let _ = socket.shutdown().await;
            // Read (and discard) what the client still sends until it closes too.
            let mut buf = [0u8; 512];
            while matches!(socket.read(&mut buf).await, Ok(n) if n > 0) {}
        })
        .await;
        lingering.fetch_sub(1, Ordering::Relaxed);
    });
}

/// Runs one connection until it ends, killing it when the login grace time passes before it
/// plays, or when the server shuts down.
async fn serve_connection(
    ssh: Arc<Config>,
    socket: tokio::net::TcpStream,
    handler: ConnHandler,
    life: &Lifeline,
    deadline: Instant,
    mut shutdown: watch::Receiver<bool>,
) -> Result<(), String> {
    let deadline = tokio::time::Instant::from_std(deadline);
    let stream = life.wrap(socket);
    // russh reads the client's version line before handing the connection to its own task.
    let running =
        match tokio::time::timeout_at(deadline, russh::server::run_stream(ssh, stream, handler))
            .await
        {
            Err(_) => return Err("login grace time over before the version line".into()),
            Ok(Err(e)) => return Err(e.to_string()),
            Ok(Ok(r)) => r,
        };
    let handle = running.handle();
    tokio::pin!(running);
    let mut playing = life.playing();
    let mut grace_over = false;
    let mut stopping = false;
    loop {
        let waiting = !*playing.borrow() && !grace_over;
        tokio::select! {
            r = &mut running => {
                return match r {
                    Ok(()) if grace_over => Err("login grace time over".into()),
                    Ok(()) => Ok(()),
                    Err(_) if grace_over => Err("login grace time over".into()),
                    Err(_) if life.killed() => Err("closed by the server".into()),
                    Err(e) => Err(e.to_string()),
                }
            }
            _ = playing.changed(), if waiting => {}
            () = tokio::time::sleep_until(deadline), if waiting => {
                grace_over = true;
                goodbye(&handle, russh::Disconnect::ByApplication, "login grace time over").await;
                life.kill();
            }
            _ = shutdown.changed(), if !stopping => {
                stopping = true;
                // Give sessions a moment to restore the client's terminal, then hang up.
                tokio::time::sleep(Duration::from_millis(300)).await;
                goodbye(&handle, russh::Disconnect::ByApplication, "server shutting down").await;
                life.kill();
            }
        }
    }
}

/// Sends a disconnect message if the connection takes it soon, and leaves it a moment to go out.
async fn goodbye(handle: &russh::server::Handle, reason: russh::Disconnect, why: &str) {
    let sent = tokio::time::timeout(
        Duration::from_millis(200),
        handle.disconnect(reason, why.into(), String::new()),
    )
    .await;
    if matches!(sent, Ok(Ok(()))) {
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
}

/// Runs a server until Ctrl-C or SIGTERM (the `halfcast serve` command).
///
/// # Errors
/// A message when the runtime, the address or the host key fail.
pub fn run_until_signal(config: ServeConfig, world: World) -> Result<(), String> {
    let rt = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| format!("cannot start the async runtime: {e}"))?;
    rt.block_on(async move {
        let log = Log::new(config.quiet);
        let server = start(config, world).await?;
        wait_for_signal().await.map_err(|e| e.to_string())?;
        log.server("shutting down");
        let stats = server.shutdown().await;
        log.server(format_args!(
            "served {} connections ({} refused), {} frames, {} bytes",
            stats.connections, stats.refused, stats.frames_sent, stats.bytes_sent
        ));
        Ok(())
    })
}

async fn wait_for_signal() -> io::Result<()> {
    #[cfg(unix)]
    {
        use tokio::signal::unix::{signal, SignalKind};
        let mut term = signal(SignalKind::terminate())?;
        tokio::select! {
            r = tokio::signal::ctrl_c() => r,
            _ = term.recv() => Ok(()),
        }
    }
    #[cfg(not(unix))]
    {
        tokio::signal::ctrl_c().await
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_refusal_is_a_line_a_version_and_a_well_formed_disconnect_packet() {
        let bytes = refusal_bytes(&Refusal::TooManyFromAddress);
        let text = "halfcast: too many connections from your address";
        let head = format!("{text}\r\nSSH-2.0-halfcast\r\n");
        assert!(bytes.starts_with(head.as_bytes()));
        let packet = &bytes[head.len()..];
        let len = u32::from_be_bytes(packet[..4].try_into().unwrap()) as usize;
        assert_eq!(packet.len(), 4 + len);
        assert_eq!(packet.len() % 8, 0);
        let padding = usize::from(packet[4]);
        assert!(padding >= 4);
        let payload = &packet[5..4 + len - padding];
        assert_eq!(payload[0], 1, "SSH_MSG_DISCONNECT");
        assert_eq!(u32::from_be_bytes(payload[1..5].try_into().unwrap()), 12);
        let n = u32::from_be_bytes(payload[5..9].try_into().unwrap()) as usize;
        assert_eq!(&payload[9..9 + n], text.as_bytes());
        assert_eq!(&payload[9 + n..], &[0, 0, 0, 0], "an empty language tag");
    }
}
