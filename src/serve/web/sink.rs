//! A play session's frames over a WebSocket: each frame one binary message of the same bytes an
//! SSH player's terminal gets; their arrival known from the page's acknowledgements
//! ([`super::acked`]), which also gate the next frame ([`crate::play::acks`]).

use std::sync::Arc;
use std::time::{Duration, Instant};

use futures_util::stream::SplitSink;
use futures_util::SinkExt;
use tokio::net::TcpStream;
use tokio::sync::Mutex;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::WebSocketStream;

use super::acked::AckBook;
use crate::play::acks::{EchoGate, Echoes};
use crate::play::link::LinkSample;
use crate::play::sink::{FrameSink, Gone};

/// The WebSocket's sending half, shared by the session's frames and the reader's close.
pub type Writer = SplitSink<WebSocketStream<TcpStream>, Message>;

/// One page's WebSocket as a session's frame sink.
pub struct WebSink {
    writer: Arc<Mutex<Writer>>,
    book: AckBook,
    gate: EchoGate,
    written: u64,
}

impl WebSink {
    /// A sink writing to `writer`, its acknowledgements recorded in `book`.
    #[must_use]
    pub fn new(writer: Arc<Mutex<Writer>>, book: AckBook) -> Self {
        Self {
            writer,
            book,
            gate: EchoGate::new(),
            written: 0,
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
        let len = frame.len() as u64;
        let now = crate::play::session::now();
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
        self.gate.clear(period, now)
    }

    fn acked_rtt(&self) -> Option<Duration> {
        self.gate.least_rtt()
    }

    fn measures(&self) -> bool {
        true
    }
}
