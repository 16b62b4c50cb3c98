//! The browser listener: takes connections in (a bounded number reading their request at once,
//! each within [`super::request::HEAD_WAIT`]), finds the player's address (behind a trusted
//! proxy, its headers), and answers each request ([`super::routes`]). It closes with the SSH
//! port when the world drains or stops.

use std::net::SocketAddr;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::Duration;

use tokio::net::{TcpListener, TcpStream};
use tokio::sync::watch;
use tokio::task::JoinHandle;

use super::edge::WebEdge;
use super::forwarded::client_addr;
use super::request::{read_head, HEAD_WAIT};
use super::routes;

/// Connections at most reading their request at once (beyond, closed at accept).
const MAX_READING: usize = 256;

/// Binds the browser listener and serves until `stop` turns true.
///
/// # Errors
/// A message when the address cannot be bound.
pub async fn start(
    edge: WebEdge,
    stop: watch::Receiver<bool>,
) -> Result<(SocketAddr, JoinHandle<()>), String> {
    let addr = edge.options.listen;
    let listener = TcpListener::bind(addr)
        .await
        .map_err(|e| format!("cannot serve the web page on {addr}: {e}"))?;
    let bound = listener.local_addr().map_err(|e| e.to_string())?;
    edge.shared
        .log
        .server(format_args!("players in a browser: http://{bound}/"));
    Ok((
        bound,
        tokio::spawn(accept_loop(listener, Arc::new(edge), stop)),
    ))
}

async fn accept_loop(listener: TcpListener, edge: Arc<WebEdge>, mut stop: watch::Receiver<bool>) {
    let reading = Arc::new(AtomicUsize::new(0));
    loop {
        let (socket, peer) = tokio::select! {
            _ = stop.changed() => break,
            r = listener.accept() => match r {
                Ok(x) => x,
                Err(e) => {
                    edge.shared.log.server(format_args!("web accept failed: {e}"));
                    tokio::time::sleep(Duration::from_millis(100)).await;
                    continue;
                }
            },
        };
        if reading.load(Ordering::Relaxed) >= MAX_READING {
            continue;
        }
        let _ = socket.set_nodelay(true);
        reading.fetch_add(1, Ordering::Relaxed);
        let (edge, reading) = (Arc::clone(&edge), Arc::clone(&reading));
        tokio::spawn(visit(socket, peer, edge, reading));
    }
}

/// One connection: its request read (counted in `reading` meanwhile), then answered.
async fn visit(
    mut socket: TcpStream,
    tcp_peer: SocketAddr,
    edge: Arc<WebEdge>,
    reading: Arc<AtomicUsize>,
) {
    let head = tokio::time::timeout(HEAD_WAIT, read_head(&mut socket)).await;
    reading.fetch_sub(1, Ordering::Relaxed);
    let Ok(Ok(req)) = head else {
        routes::bad_request(socket).await;
        return;
    };
    let (trusted, header) = (&edge.options.trusted_proxies, edge.options.forwarded_header);
    let peer = client_addr(tcp_peer, &req, trusted, header);
    routes::answer(socket, req, peer, edge).await;
}
