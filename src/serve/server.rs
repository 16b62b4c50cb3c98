//! The accept loop: admits connections within the limits, runs each in its own task (so no
//! session's panic or error reaches the loop), logs connect and disconnect with the duration.

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

use super::avatars::with_avatar_sheet;
use super::config::ServeConfig;
use super::handler::{ConnHandler, Shared};
use super::hostkey;
use super::limits::Limiter;
use super::log::Log;
use super::stats::{ServeStats, StatsSnapshot};
use super::world_task::spawn_world;
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
    let (key, notes) = hostkey::load_or_generate(&config.host_key)?;
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
        auth_rejection_time: Duration::from_millis(300),
        auth_rejection_time_initial: Some(Duration::ZERO),
        // Before a shell starts, a silent connection is dropped after the idle timeout too.
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
    let (world, avatar_sheet) = with_avatar_sheet(world);
    let world = Arc::new(world);
    let (shutdown_tx, shutdown_rx) = watch::channel(false);
    let stats = Arc::new(ServeStats::default());
    let shared = Arc::new(Shared {
        world: spawn_world(Arc::clone(&world), config.tick_hz),
        world_data: world,
        avatar_sheet,
        stats: Arc::clone(&stats),
        log,
        shutdown: shutdown_rx.clone(),
        config,
    });
    log.server(format_args!("listening on {addr}"));
    let accept = tokio::spawn(accept_loop(listener, ssh, shared, shutdown_rx));
    Ok(RunningServer {
        addr,
        stats,
        shutdown: shutdown_tx,
        accept,
    })
}

async fn accept_loop(
    listener: TcpListener,
    ssh: Arc<Config>,
    shared: Arc<Shared>,
    mut shutdown: watch::Receiver<bool>,
) {
    let limiter = Limiter::new(shared.config.max_sessions, shared.config.max_per_ip);
    let next_id = AtomicU64::new(1);
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
        let slot = match limiter.admit(peer.ip()) {
            Ok(s) => s,
            Err(why) => {
                ServeStats::add(&shared.stats.refused, 1);
                shared.log.server(format_args!(
                    "refused {peer}: {why:?} ({} live)",
                    limiter.live()
                ));
                drop(socket);
                continue;
            }
        };
        ServeStats::add(&shared.stats.connections, 1);
        let id = next_id.fetch_add(1, Ordering::Relaxed);
        let ssh = Arc::clone(&ssh);
        let shared = Arc::clone(&shared);
        tokio::spawn(async move {
            let started = Instant::now();
            shared.log.session(id, peer, "connected");
            let handler = ConnHandler::new(id, peer, Arc::clone(&shared));
            let result = serve_connection(ssh, socket, handler, shared.shutdown.clone()).await;
            let secs = started.elapsed().as_secs_f64();
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
            drop(slot);
        });
    }
}

async fn serve_connection(
    ssh: Arc<Config>,
    socket: tokio::net::TcpStream,
    handler: ConnHandler,
    mut shutdown: watch::Receiver<bool>,
) -> Result<(), russh::Error> {
    let running = russh::server::run_stream(ssh, socket, handler).await?;
    let handle = running.handle();
    tokio::select! {
        r = running => r,
        _ = shutdown.changed() => {
            // Give sessions a moment to restore the client's terminal, then hang up.
            tokio::time::sleep(Duration::from_millis(300)).await;
            let _ = handle
                .disconnect(russh::Disconnect::ByApplication, "server shutting down".into(), String::new())
                .await;
            Ok(())
        }
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
