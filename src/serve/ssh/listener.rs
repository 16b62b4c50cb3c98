//! The SSH edge's accept loop: admits connections within the limits, runs each in its own task (so no
//! session's panic or error reaches the loop) under the login grace deadline, logs connect and
//! disconnect with the duration.
//!
//! A connection turned away at accept (per-address or start-up limit, server full) is told why
//! without any key exchange: one text line before the SSH version line (RFC 4253 §4.2 allows
//! such lines, but OpenSSH's `ssh` shows them only with `-v`), the version line, then an
//! unencrypted SSH_MSG_DISCONNECT carrying the reason, which plain `ssh` prints as
//! "Received disconnect from HOST port PORT:12: REASON". One refused later (server full at
//! login, login grace over) gets the disconnect message inside the encrypted session.

use std::net::SocketAddr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use russh::keys::PrivateKey;
use russh::server::Config;
use russh::{compression, Preferred};
use tokio::net::TcpListener;
use tokio::sync::watch;

use super::auth::Backoff;
use super::handler::ConnHandler;
use super::lifeline::Lifeline;
use crate::serve::config::ServeConfig;
use crate::serve::edge::admission;
use crate::serve::limits::Refusal;
use crate::serve::ops::metrics::Reason;
use crate::serve::proxy_header::{read_header, Inbound, Source, HEADER_WAIT};
use crate::serve::shared::Shared;

/// Compression offered to clients, most preferred first: the delayed `zlib@openssh.com`
/// (what OpenSSH's `ssh -C` asks for), plain `zlib`, or none.
const COMPRESSION: &[compression::Name] = &[
    compression::ZLIB_LEGACY,
    compression::ZLIB,
    compression::NONE,
];

/// russh's settings for the SSH edge: auth methods, the host key, timeouts, compression.
pub(crate) fn russh_config(config: &ServeConfig, key: PrivateKey) -> Config {
    Config {
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
    }
}

/// Refused sockets at most lingering at once to deliver their reason (beyond, just closed).
const MAX_LINGERING: usize = 64;
/// How long a refused socket lingers so its reason line arrives before the close.
const LINGER: Duration = Duration::from_millis(500);
/// Connections at most waiting at once for their PROXY header (beyond, closed at accept).
const MAX_HEADER_WAITS: u64 = 256;

/// What the accept loop hands each connection.
struct Door {
    ssh: Arc<Config>,
    shared: Arc<Shared>,
    /// Failed password logins per source address.
    backoff: Arc<Backoff>,
    lingering: Arc<AtomicU64>,
    /// Shared with [`RunningServer`]: a draining world waits for these too.
    header_waits: Arc<AtomicU64>,
}

/// Accepts connections until told to stop, then takes in what the port's queue still holds and
/// says the port is closed.
pub(crate) async fn accept_loop(
    listener: TcpListener,
    ssh: Arc<Config>,
    shared: Arc<Shared>,
    (mut stop, closed, header_waits): (watch::Receiver<bool>, watch::Sender<bool>, Arc<AtomicU64>),
) {
    let door = Arc::new(Door {
        ssh,
        shared,
        backoff: Arc::default(),
        lingering: Arc::new(AtomicU64::new(0)),
        header_waits,
    });
    loop {
        let (socket, tcp_peer) = tokio::select! {
            _ = stop.changed() => break,
            r = listener.accept() => match r {
                Ok(x) => x,
                Err(e) => {
                    // E.g. out of file descriptors: back off instead of spinning.
                    door.shared.log.server(format_args!("accept failed: {e}"));
                    tokio::time::sleep(Duration::from_millis(100)).await;
                    continue;
                }
            },
        };
        enter(&door, socket, tcp_peer);
    }
    // Connections the kernel already completed are taken in (a balancer counts them as
    // delivered); closing the port with them queued would reset them.
    while let Ok(Ok((socket, tcp_peer))) =
        tokio::time::timeout(Duration::ZERO, listener.accept()).await
    {
        enter(&door, socket, tcp_peer);
    }
    drop(listener);
    closed.send_replace(true);
}

/// Takes in one accepted connection: admitted at once, or after its PROXY header.
fn enter(door: &Arc<Door>, socket: tokio::net::TcpStream, tcp_peer: SocketAddr) {
    let accepted = Instant::now();
    if !door.shared.config.proxy_protocol {
        admit(door, socket, tcp_peer, Inbound::refusing_headers, accepted);
        return;
    }
    // Behind a balancer: the header names the client; every limit applies to it.
    if door.header_waits.load(Ordering::Relaxed) >= MAX_HEADER_WAITS {
        return;
    }
    door.header_waits.fetch_add(1, Ordering::Relaxed);
    let door = Arc::clone(door);
    tokio::spawn(async move {
        let mut socket = socket;
        let got = tokio::time::timeout(HEADER_WAIT, read_header(&mut socket)).await;
        match got {
            Ok(Ok((source, head))) => {
                let peer = match source {
                    Source::Client(peer) => peer,
                    Source::Local => tcp_peer,
                };
                let inbound = move |s| Inbound::after_header(s, head);
                admit(&door, socket, peer, inbound, accepted);
            }
            Ok(Err(e)) => bad_header(&door, socket, tcp_peer, &e),
            Err(_) => bad_header(&door, socket, tcp_peer, "no PROXY header in time"),
        }
        // Only now: admitted, the limits count it (a draining world never sees it in neither).
        door.header_waits.fetch_sub(1, Ordering::Relaxed);
    });
}

/// Closes a connection whose PROXY header is missing or malformed.
fn bad_header(door: &Door, socket: tokio::net::TcpStream, tcp_peer: SocketAddr, why: &str) {
    admission::refuse(&door.shared, None, tcp_peer, Reason::Proxy, why);
    let _ = socket.try_write(format!("halfcast: {why}\r\n").as_bytes());
}

/// Admits a connection from `peer` within the limits and runs it in a task of its own, or
/// tells it why not.
fn admit(
    door: &Door,
    socket: tokio::net::TcpStream,
    peer: SocketAddr,
    inbound: impl FnOnce(tokio::net::TcpStream) -> Inbound<tokio::net::TcpStream>,
    accepted: Instant,
) {
    let shared = &door.shared;
    let pending = match admission::admit(shared, peer) {
        Ok(s) => s,
        Err(why) => {
            refuse(socket, why, &door.lingering);
            return;
        }
    };
    let id = admission::connected(shared, peer);
    let ssh = Arc::clone(&door.ssh);
    let shared = Arc::clone(shared);
    let backoff = Arc::clone(&door.backoff);
    let tcp = socket.local_addr().ok().zip(socket.peer_addr().ok());
    let stream = inbound(socket);
    tokio::spawn(async move {
        let life = Arc::new(Lifeline::default());
        if let Some((local, remote)) = tcp {
            life.set_tcp(local, remote);
        }
        let handler = ConnHandler::new(
            id,
            peer,
            (Arc::clone(&shared), backoff),
            pending,
            Arc::clone(&life),
        );
        let deadline = accepted + shared.config.login_grace;
        let result = serve_connection(
            ssh,
            stream,
            handler,
            &life,
            deadline,
            (shared.shutdown.clone(), shared.farewell.clone()),
        )
        .await;
        let secs = accepted.elapsed().as_secs_f64();
        let err = result.err();
        if err
            .as_deref()
            .is_some_and(|e| e.starts_with("login grace time over"))
        {
            crate::serve::ops::metrics::refused(Reason::Grace);
        }
        shared.log.disconnect(
            id,
            peer,
            secs,
            life.wire_bytes(),
            life.link(),
            err.as_deref(),
        );
    });
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
    socket: Inbound<tokio::net::TcpStream>,
    handler: ConnHandler,
    life: &Lifeline,
    deadline: Instant,
    (mut shutdown, farewell): (watch::Receiver<bool>, watch::Receiver<&'static str>),
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
                let why = *farewell.borrow();
                goodbye(&handle, russh::Disconnect::ByApplication, why).await;
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
