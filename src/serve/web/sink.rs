//! A play session's frames over a WebSocket: each frame one binary message of the same bytes an
//! SSH player's terminal gets, compressed while the link needs it ([`super::deflate`]); their
//! arrival known from the page's acknowledgements ([`super::acked`]), which also gate the next
//! frame ([`crate::play::acks`]). Pacing and colour levels see the bytes on the wire.

use std::sync::Arc;
use std::time::{Duration, Instant};

use futures_util::stream::SplitSink;
use futures_util::SinkExt;
use tokio::net::TcpStream;
use tokio::sync::Mutex;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::WebSocketStream;

use super::acked::AckBook;
use super::deflate::{self, Policy};
use super::options::Compress;
use crate::play::acks::{EchoGate, Echoes};
use crate::play::link::LinkSample;
use crate::play::sink::{FrameSink, Gone, Note};

/// The WebSocket's sending half, shared by the session's frames and the reader's close.
pub type Writer = SplitSink<WebSocketStream<TcpStream>, Message>;

/// One page's WebSocket as a session's frame sink.
pub struct WebSink {
    writer: Arc<Mutex<Writer>>,
    book: AckBook,
    gate: EchoGate,
    written: u64,
    deflate: Policy,
    /// The served maps' names, in the rotation's order, for a ray's `map`.
    maps: Arc<[String]>,
    /// The time between frames the session last asked about.
    period: Duration,
}

impl WebSink {
    /// A sink writing to `writer`, its acknowledgements recorded in `book`.
    #[must_use]
    pub fn new(
        writer: Arc<Mutex<Writer>>,
        book: AckBook,
        (compress, maps): (Compress, Arc<[String]>),
    ) -> Self {
        Self {
            writer,
            book,
            gate: EchoGate::new(),
            written: 0,
            deflate: Policy::new(compress, crate::play::session::now()),
            maps,
            period: Duration::from_millis(33),
        }
    }

    /// Where the reader tells acknowledgements for this sink's gate.
    #[must_use]
    pub fn echoes(&self) -> Arc<Echoes> {
        self.gate.shared()
    }
}

impl FrameSink for WebSink {
    async fn send(&mut self, frame: Vec<u8>) -> Result<(), Gone> {
        let now = crate::play::session::now();
        let rate = self.book.sample().delivery_rate as f64;
        self.deflate.frame(frame.len(), (rate, self.period), now);
        let raw = frame.len();
        let frame = if self.deflate.compress(now) {
            deflate::compressed(&frame)
        } else {
            frame
        };
        self.deflate.sent(raw, frame.len());
        let len = frame.len() as u64;
        let (n, _) = self.gate.sent(now);
        self.book.sent(n, len, now);
        let mut w = self.writer.lock().await;
        w.send(Message::Binary(frame.into()))
            .await
            .map_err(|_| Gone)?;
        self.written += len;
        Ok(())
    }

    fn written(&self) -> u64 {
        self.written
    }

    fn sample(&mut self) -> Option<LinkSample> {
        Some(self.book.sample())
    }

    fn answered(&mut self, period: Duration, now: Instant) -> bool {
        self.period = period;
        let open = self.gate.clear(period, now);
        self.deflate.gate(open, now);
        open
    }

    fn acked_rtt(&self) -> Option<Duration> {
        self.gate.least_rtt()
    }

    fn measures(&self) -> bool {
        true
    }

    fn level_held_down(&mut self, by_link: bool) {
        self.deflate.level_held_down(by_link);
    }

    fn could_shrink(&self) -> Option<f64> {
        self.deflate.could_shrink()
    }

    fn shrink(&mut self) {
        self.deflate.shrink(crate::play::session::now());
    }

    async fn note(&mut self, note: Note) -> Result<(), Gone> {
        let text = note_json(&note, &self.maps);
        let mut w = self.writer.lock().await;
        w.send(Message::Text(text.into())).await.map_err(|_| Gone)
    }
}

/// A note as the page reads it: one JSON object whose single key names it (`view`, `ray`). A
/// ray names its map only where the server has several.
fn note_json(note: &Note, maps: &[String]) -> String {
    let value = match note {
        Note::View { x, y, cols, rows } => {
            serde_json::json!({ "view": { "x": x, "y": y, "cols": cols, "rows": rows } })
        }
        Note::Ray(r) => {
            let mut ray = serde_json::json!({
                "pos": [r.pos.0, r.pos.1],
                "angle": r.angle,
                "column": r.column,
                "size": [r.size.0, r.size.1],
                "fov": r.fov,
            });
            if let (true, Some(name)) = (maps.len() > 1, maps.get(r.map)) {
                ray["map"] = name.as_str().into();
            }
            serde_json::json!({ "ray": ray })
        }
    };
    value.to_string()
}
