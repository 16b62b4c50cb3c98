//! A WebSocket client that plays as the browser page does (frames read into a vt100 screen,
//! each acknowledged once read, keys as press and release messages), for the `--web` tests.

use std::net::SocketAddr;
use std::time::Duration;

use futures_util::{SinkExt, StreamExt};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::client::IntoClientRequest;
use tokio_tungstenite::tungstenite::handshake::client::Request;
use tokio_tungstenite::tungstenite::http::HeaderValue;
use tokio_tungstenite::tungstenite::protocol::frame::coding::CloseCode;
use tokio_tungstenite::tungstenite::{Error, Message};
use tokio_tungstenite::WebSocketStream;

use super::PATIENCE;

/// One page's connection.
pub struct WebClient {
    pub ws: WebSocketStream<TcpStream>,
    pub screen: vt100::Parser,
    /// Frames read so far.
    pub frames: u64,
    /// Their messages' bytes (compressed ones as they came).
    pub wire: u64,
    /// Whether each frame is acknowledged as it is read (a page always does).
    pub acking: bool,
    /// The server's text messages (JSON notes: where the view is, a debugged ray), in order.
    pub notes: Vec<String>,
}

/// How a connection ended: the close frame's code and reason.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Closed {
    pub code: Option<CloseCode>,
    pub reason: String,
}

/// Opens `/ws?query` on `addr` with `origin` (as a browser would send it), or the HTTP status the
/// upgrade was refused with.
pub async fn open(addr: SocketAddr, query: &str, origin: Option<&str>) -> Result<WebClient, u16> {
    let mut req = format!("ws://{addr}/ws?{query}")
        .into_client_request()
        .expect("a request");
    if let Some(o) = origin {
        req.headers_mut()
            .insert("Origin", HeaderValue::from_str(o).expect("header"));
    }
    let tcp = TcpStream::connect(addr)
        .await
        .expect("the web port answers");
    upgrade(req, tcp).await
}

/// Upgrades `req` over `tcp`, a connection made as the test needs it (from a chosen source
/// address, through a proxy), to a page playing at the grid the request's query asks for; or
/// the HTTP status the upgrade was refused with.
pub async fn upgrade(req: Request, tcp: TcpStream) -> Result<WebClient, u16> {
    // As a browser's socket is: an ack never waits on the last one's TCP acknowledgement.
    tcp.set_nodelay(true).expect("nodelay");
    let (cols, rows) = size_in(req.uri().query().unwrap_or_default());
    match tokio_tungstenite::client_async(req, tcp).await {
        Ok((ws, _)) => Ok(WebClient {
            ws,
            screen: vt100::Parser::new(rows, cols, 0),
            frames: 0,
            wire: 0,
            acking: true,
            notes: Vec::new(),
        }),
        Err(Error::Http(resp)) => Err(resp.status().as_u16()),
        Err(e) => panic!("upgrade failed: {e}"),
    }
}

/// The grid a query asks for (the server's default when it names none).
fn size_in(query: &str) -> (u16, u16) {
    let get = |k: &str| {
        query
            .split('&')
            .find_map(|p| p.strip_prefix(k)?.parse::<u16>().ok())
    };
    (get("cols=").unwrap_or(80), get("rows=").unwrap_or(24))
}

impl WebClient {
    /// The next frame's bytes (drawn into the screen, acknowledged when `acking`), or how the
    /// connection closed; `Ok(None)` when nothing came within `wait`.
    pub async fn frame(&mut self, wait: Duration) -> Result<Option<Vec<u8>>, Closed> {
        loop {
            let msg = match tokio::time::timeout(wait, self.ws.next()).await {
                Err(_) => return Ok(None),
                Ok(None) | Ok(Some(Err(_))) => {
                    return Err(Closed {
                        code: None,
                        reason: String::new(),
                    })
                }
                Ok(Some(Ok(m))) => m,
            };
            match msg {
                Message::Binary(b) => {
                    self.frames += 1;
                    self.wire += b.len() as u64;
                    let frame = frame_bytes(&b);
                    self.screen.process(&frame);
                    if self.acking {
                        self.send(&format!("{{\"ack\":{}}}", self.frames)).await;
                    }
                    return Ok(Some(frame));
                }
                Message::Text(t) => self.notes.push(t.to_string()),
                Message::Close(c) => {
                    return Err(Closed {
                        code: c.as_ref().map(|c| c.code),
                        reason: c.map(|c| c.reason.to_string()).unwrap_or_default(),
                    })
                }
                _ => {}
            }
        }
    }

    /// Reads frames until a note whose JSON has `key` at its top comes (returned), or
    /// [`PATIENCE`] passes.
    pub async fn note(&mut self, key: &str) -> Option<serde_json::Value> {
        let deadline = tokio::time::Instant::now() + PATIENCE;
        loop {
            let found = self.notes.iter().find_map(|n| {
                let v: serde_json::Value = serde_json::from_str(n).expect("a note is JSON");
                v.get(key).cloned()
            });
            if found.is_some() {
                self.notes.retain(|n| !n.contains(&format!("\"{key}\"")));
                return found;
            }
            if tokio::time::Instant::now() >= deadline
                || self.frame(Duration::from_millis(200)).await.is_err()
            {
                return None;
            }
        }
    }

    /// Reads frames until `done` holds for the screen; false if it never did within
    /// [`PATIENCE`].
    pub async fn until(&mut self, mut done: impl FnMut(&vt100::Screen) -> bool) -> bool {
        let deadline = tokio::time::Instant::now() + PATIENCE;
        while tokio::time::Instant::now() < deadline {
            if done(self.screen.screen()) {
                return true;
            }
            if self.frame(Duration::from_millis(200)).await.is_err() {
                return false;
            }
        }
        done(self.screen.screen())
    }

    /// Reads (and acks) whatever frames come for `d`.
    pub async fn drain_for(&mut self, d: Duration) {
        let deadline = tokio::time::Instant::now() + d;
        while tokio::time::Instant::now() < deadline {
            let left = deadline - tokio::time::Instant::now();
            if self.frame(left).await.is_err() {
                return;
            }
        }
    }

    /// Reads until the server closes, returning its close frame.
    pub async fn closed(&mut self) -> Closed {
        let deadline = tokio::time::Instant::now() + PATIENCE;
        while tokio::time::Instant::now() < deadline {
            if let Err(c) = self.frame(Duration::from_millis(500)).await {
                return c;
            }
        }
        panic!("the server did not close the connection");
    }

    /// Sends one text message.
    pub async fn send(&mut self, text: &str) {
        let _ = self.ws.send(Message::Text(text.into())).await;
    }

    /// A key's press (`down`) or release, named as the browser names it.
    pub async fn key(&mut self, key: &str, down: bool) {
        self.send(&format!("{{\"key\":\"{key}\",\"down\":{down}}}"))
            .await;
    }
}

/// A frame message's bytes as the page reads them: a message starting 0x00 is the raw DEFLATE
/// of the frame after that byte, any other the frame itself.
#[must_use]
pub fn frame_bytes(message: &[u8]) -> Vec<u8> {
    match message.split_first() {
        Some((0, deflated)) => {
            let mut out = Vec::new();
            std::io::Read::read_to_end(&mut flate2::read::DeflateDecoder::new(deflated), &mut out)
                .expect("a compressed frame inflates");
            out
        }
        _ => message.to_vec(),
    }
}
