//! The answer to one request: the page and its assets (its modules under `/js/`), `/info.json`,
//! the ray debugger's page (`/ray`) and its trace routes (`/trace.json`, `.svg`, `.png`:
//! [`super::trace_route`]), `/healthz` (the same answer as the metrics listener's, so a balancer
//! in front of the browser port checks the world it sends players to), and the WebSocket upgrade
//! at `/ws`, checked for its `Origin`, then admitted within the server's limits and played.

use std::net::SocketAddr;
use std::sync::Arc;

use tokio::io::AsyncWriteExt;
use tokio::net::TcpStream;
use tokio::sync::Mutex;
use tokio_tungstenite::tungstenite::handshake::derive_accept_key;
use tokio_tungstenite::tungstenite::protocol::frame::coding::CloseCode;
use tokio_tungstenite::tungstenite::protocol::{Role, WebSocketConfig};
use tokio_tungstenite::WebSocketStream;

use super::edge::WebEdge;
use super::page;
use super::request::Request;
use super::session;
use crate::serve::edge::admission;
use crate::serve::edge::arrival::Who;
use crate::serve::edge::name::{display_name, shown_name};
use crate::serve::edge::Via;
use crate::serve::ops::metrics::{self, Reason};
use crate::trace_query::address::percent_decoded;

/// The largest message a page may send (its messages are a few dozen bytes).
pub const MAX_MESSAGE: usize = 4096;
/// Frames the server may have queued unwritten for one page before its writes wait.
const MAX_WRITE_BUFFER: usize = 4 * 1024 * 1024;
/// The grid a page gets when its request names none.
const DEFAULT_SIZE: (u32, u32) = (80, 24);

/// Answers a request that could not be read.
pub async fn bad_request(socket: TcpStream) {
    reply(socket, 400, "text/plain", b"bad request\n").await;
}

/// Answers `req` from `peer`.
pub async fn answer(socket: TcpStream, req: Request, peer: SocketAddr, edge: Arc<WebEdge>) {
    if req.method != "GET" && req.method != "HEAD" {
        return reply(socket, 405, "text/plain", b"only GET\n").await;
    }
    let text = "text/plain";
    let (health, info, traced);
    let (status, kind, body): (u16, &str, &[u8]) = match req.path.as_str() {
        "/" => (200, "text/html; charset=utf-8", page::HTML.as_bytes()),
        "/halfcast.css" => (200, "text/css", page::CSS.as_bytes()),
        "/info.json" => {
            info = super::info::json(&edge.shared);
            (200, "application/json", info.as_bytes())
        }
        js if js.starts_with("/js/") => match page::module(&js[4..]) {
            Some(m) => (200, "text/javascript", m.as_bytes()),
            None => (404, text, b"not found\n"),
        },
        // Browsers ask for an icon; there is none, and no error need show for it.
        "/favicon.ico" => (204, text, b""),
        "/healthz" => {
            let h = edge.ready.health();
            metrics::health_check(h.word());
            health = format!("{}\n", h.word());
            (h.status(), text, health.as_bytes())
        }
        "/ws" => return upgrade(socket, req, peer, edge).await,
        // The ray debugger: its page and the trace's data and figure (its modules are under /js/).
        "/ray" => (200, "text/html; charset=utf-8", page::RAY_HTML.as_bytes()),
        "/ray.css" => (200, "text/css", page::RAY_CSS.as_bytes()),
        "/trace.json" | "/trace.svg" | "/trace.png" => {
            traced = super::trace_route::answer(&req.path, &req.query, &edge).await;
            (traced.status, traced.kind, traced.body.as_slice())
        }
        _ => (404, text, b"not found\n"),
    };
    if req.method == "HEAD" {
        head_reply(socket, status, kind, body.len()).await;
    } else {
        reply(socket, status, kind, body).await;
    }
}

/// The head of an answer to `HEAD`: the length the body would have, no body.
async fn head_reply(mut socket: TcpStream, status: u16, kind: &str, len: usize) {
    let head = head(status, kind, len);
    let _ = tokio::time::timeout(super::request::HEAD_WAIT, async {
        let _ = socket.write_all(head.as_bytes()).await;
        let _ = socket.shutdown().await;
    })
    .await;
}

/// One whole HTTP answer, then the connection closed.
async fn reply(mut socket: TcpStream, status: u16, kind: &str, body: &[u8]) {
    let head = head(status, kind, body.len());
    let _ = tokio::time::timeout(super::request::HEAD_WAIT, async {
        let _ = socket.write_all(head.as_bytes()).await;
        let _ = socket.write_all(body).await;
        let _ = socket.shutdown().await;
    })
    .await;
}

/// A response's status line and headers.
fn head(status: u16, kind: &str, len: usize) -> String {
    let word = match status {
        200 => "OK",
        204 => "No Content",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        426 => "Upgrade Required",
        _ => "Service Unavailable",
    };
    format!(
        "HTTP/1.1 {status} {word}\r\nContent-Type: {kind}\r\nContent-Length: {len}\r\n\
         Cache-Control: no-cache\r\nX-Content-Type-Options: nosniff\r\n\
         Content-Security-Policy: default-src 'self'; connect-src 'self'; frame-ancestors 'none'\r\n\
         Connection: close\r\n\r\n"
    )
}

/// The WebSocket handshake (RFC 6455 §4.2), the `Origin` check first; then the session.
async fn upgrade(mut socket: TcpStream, req: Request, peer: SocketAddr, edge: Arc<WebEdge>) {
    let key = req.header("sec-websocket-key").map(str::trim);
    let ok = req.has_token("connection", "upgrade")
        && req.has_token("upgrade", "websocket")
        && req.header("sec-websocket-version").map(str::trim) == Some("13");
    let Some(key) = key.filter(|_| ok) else {
        return reply(
            socket,
            426,
            "text/plain",
            b"a WebSocket upgrade is expected here\n",
        )
        .await;
    };
    let origin = req.header("origin");
    if !super::origin::allowed(origin, req.header("host"), &edge.options.origins) {
        let why = format!("a page from {:?} may not play here", origin.unwrap_or(""));
        admission::refuse(&edge.shared, None, peer, Reason::Origin, why);
        return reply(
            socket,
            403,
            "text/plain",
            b"this page's origin may not play here\n",
        )
        .await;
    }
    let accept = derive_accept_key(key.as_bytes());
    let head = format!(
        "HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\
         Sec-WebSocket-Accept: {accept}\r\n\r\n"
    );
    if socket.write_all(head.as_bytes()).await.is_err() {
        return;
    }
    let config = WebSocketConfig::default()
        .max_message_size(Some(MAX_MESSAGE))
        .max_frame_size(Some(MAX_MESSAGE))
        .max_write_buffer_size(MAX_WRITE_BUFFER);
    let ws = WebSocketStream::from_raw_socket(socket, Role::Server, Some(config)).await;
    play(ws, &req, peer, edge).await;
}

/// Admits the page's player within the limits and runs the session, or closes saying why not.
async fn play(ws: WebSocketStream<TcpStream>, req: &Request, peer: SocketAddr, edge: Arc<WebEdge>) {
    let shared = &edge.shared;
    let place = admission::admit(shared, peer)
        .and_then(|pending| admission::take_place(shared, (None, peer), &pending));
    let place = match place {
        Ok(place) => place,
        Err(why) => {
            let (writer, _reader) = futures_util::StreamExt::split(ws);
            let text = why.to_string();
            session::close(&Mutex::new(writer), CloseCode::Again, &text).await;
            return;
        }
    };
    let id = admission::connected(shared, peer);
    let q = Query::read(&req.query);
    let who = Who {
        id,
        peer,
        name: display_name(q.name.as_deref().unwrap_or(""), id),
        spectator: q.spectate,
        via: Via::Web,
    };
    session::run(ws, edge, (who, place, q.size.unwrap_or(DEFAULT_SIZE))).await;
}

/// What the upgrade's query says: `name=`, `spectate`, `cols=` and `rows=`.
#[derive(Debug, Default, PartialEq, Eq)]
struct Query {
    name: Option<String>,
    spectate: bool,
    size: Option<(u32, u32)>,
}

impl Query {
    fn read(query: &str) -> Self {
        let mut q = Self::default();
        let (mut cols, mut rows) = (None, None);
        for pair in query.split('&') {
            let (k, v) = pair.split_once('=').unwrap_or((pair, ""));
            match k {
                "name" => q.name = shown_name(&percent_decoded(v)),
                "spectate" => q.spectate = true,
                "cols" => cols = v.parse::<u32>().ok(),
                "rows" => rows = v.parse::<u32>().ok(),
                _ => {}
            }
        }
        q.size = cols.zip(rows).filter(|&(c, r)| c >= 1 && r >= 1);
        q
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_upgrade_query_names_the_player_and_sizes_the_grid() {
        let q = Query::read("name=Ann%20B%1b%5B31m&cols=120&rows=40");
        assert_eq!(q.name.as_deref(), Some("AnnB[31m"));
        assert_eq!(q.size, Some((120, 40)));
        assert!(!q.spectate);
        let q = Query::read("spectate&cols=0&rows=9");
        assert!(q.spectate);
        assert_eq!((q.name, q.size), (None, None));
        assert_eq!(Query::read("name=%20%20").name, None);
        assert_eq!(percent_decoded("a%2"), "a%2");
        assert_eq!(percent_decoded("%41+b"), "A b");
    }
}
