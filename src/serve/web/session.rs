//! The browser edge of a play session: the page's messages read into input, sizes and
//! acknowledgements ([`super::messages`]), a [`WebSink`] for its frames, and a goodbye as the
//! WebSocket's close code and reason, which the page shows. The session's run and its end are the
//! one way in's ([`crate::serve::edge::run`]).

use std::sync::Arc;
use std::time::Duration;

use futures_util::stream::SplitStream;
use futures_util::{SinkExt, StreamExt};
use tokio::net::TcpStream;
use tokio::sync::{mpsc, watch, Mutex};
use tokio::task::JoinHandle;
use tokio::time::Instant;
use tokio_tungstenite::tungstenite::protocol::frame::coding::CloseCode;
use tokio_tungstenite::tungstenite::protocol::CloseFrame;
use tokio_tungstenite::tungstenite::{Error as WsError, Message};
use tokio_tungstenite::WebSocketStream;

use super::acked::AckBook;
use super::edge::WebEdge;
use super::messages::{self, PageMessage};
use super::sink::{WebSink, Writer};
use crate::play::acks::Echoes;
use crate::play::input::Input;
use crate::play::session::{self, End};
use crate::serve::edge::arrival::{arrive, Who};
use crate::serve::edge::run::{Facts, Goodbye, Outcome, Transport};
use crate::serve::limits::Playing;
use crate::serve::ops::drain::{self, RESTARTING};

type Reader = SplitStream<WebSocketStream<TcpStream>>;

/// Input messages a session may have waiting; beyond, the page is sending faster than any
/// player types and is closed.
const INPUT_QUEUE: usize = 256;
/// Messages a page may send per second on average (acks at the frame rate, keys, sizes).
const RATE: f64 = 200.0;
/// Messages a page may send in a burst.
const BURST: f64 = 400.0;
/// How long a goodbye may take to go out.
const BYE_WAIT: Duration = Duration::from_secs(2);

/// Runs one let-in page's session until it ends, then closes the WebSocket with the reason.
pub async fn run(
    ws: WebSocketStream<TcpStream>,
    edge: Arc<WebEdge>,
    (who, place, size): (Who, Playing, (u32, u32)),
) {
    let (writer, reader) = ws.split();
    let writer = Arc::new(Mutex::new(writer));
    let book = AckBook::default();
    let maps: Arc<[String]> = edge
        .shared
        .maps
        .iter()
        .map(|w| w.map.name.clone())
        .collect();
    let compress = edge.options.compress;
    let sink = WebSink::new(Arc::clone(&writer), book.clone(), (compress, maps));
    let (input_tx, input_rx) = mpsc::channel(INPUT_QUEUE);
    let (size_tx, size_rx) = watch::channel(size);
    let page = Page {
        input: input_tx,
        size: size_tx,
        book,
        echoes: sink.echoes(),
        writer: Arc::clone(&writer),
    };
    let log = edge.shared.log;
    let (id, peer) = (who.id, who.peer);
    let reading = tokio::spawn(async move {
        if let Err(why) = page.read(reader).await {
            log.session(id, peer, format_args!("closed: {}", why.1));
            close(&page.writer, why.0, why.1).await;
        }
    });
    let arrival = arrive(&edge.shared, who, place).await;
    let transport = Transport {
        facts: Facts::browser(),
        input: input_rx,
        size: size_rx,
        sink,
    };
    let bye = WebGoodbye {
        writer,
        reading,
        id,
        farewell: edge.shared.farewell.clone(),
    };
    arrival.play(transport, bye).await;
}

/// How a page is left: its reader stopped, and a close frame whose code says whether to come
/// back (1012: the world restarts, with the wait in the reason; 1001: the server stopped) and
/// whose reason the page shows.
struct WebGoodbye {
    writer: Arc<Mutex<Writer>>,
    reading: JoinHandle<()>,
    id: u64,
    farewell: watch::Receiver<&'static str>,
}

impl Goodbye for WebGoodbye {
    async fn goodbye(self, outcome: &Outcome) {
        self.reading.abort();
        let farewell = *self.farewell.borrow();
        let (code, text) = match *outcome {
            Outcome::Ended(End::Shutdown, _) if farewell == RESTARTING => {
                (CloseCode::Restart, drain::farewell_for(farewell, self.id))
            }
            Outcome::Ended(End::Shutdown, _) => (CloseCode::Away, farewell.to_owned()),
            Outcome::Ended(End::Idle, _) => {
                (CloseCode::Normal, "closed after being idle too long".into())
            }
            Outcome::Ended(End::Stalled, _) => (
                CloseCode::Normal,
                "the page took no frame for too long".into(),
            ),
            Outcome::Ended(End::Quit | End::ClientGone, _) => (CloseCode::Normal, "bye".into()),
            Outcome::Failed => (CloseCode::Error, "the server failed this session".into()),
        };
        close(&self.writer, code, &text).await;
    }
}

/// Sends a close frame saying why, if the page still takes one soon.
pub async fn close(writer: &Mutex<Writer>, code: CloseCode, reason: &str) {
    // A close reason is at most 123 bytes; ours are ASCII.
    let reason: String = reason.chars().take(120).collect();
    let frame = CloseFrame {
        code,
        reason: reason.into(),
    };
    let _ = tokio::time::timeout(BYE_WAIT, async {
        let mut w = writer.lock().await;
        let _ = w.send(Message::Close(Some(frame))).await;
    })
    .await;
}

/// Where the page's messages go.
struct Page {
    input: mpsc::Sender<Input>,
    size: watch::Sender<(u32, u32)>,
    book: AckBook,
    echoes: Arc<Echoes>,
    writer: Arc<Mutex<Writer>>,
}

impl Page {
    /// Reads the page until it closes (`Ok`) or breaks a rule (the close code and reason).
    async fn read(&self, mut reader: Reader) -> Result<(), (CloseCode, &'static str)> {
        let mut tokens = BURST;
        let mut last = Instant::now();
        while let Some(msg) = reader.next().await {
            let msg = match msg {
                Ok(m) => m,
                Err(WsError::Capacity(_)) => return Err((CloseCode::Size, "message too big")),
                Err(WsError::Protocol(_) | WsError::Utf8(_)) => {
                    return Err((CloseCode::Protocol, "not a WebSocket message"))
                }
                Err(_) => return Ok(()),
            };
            let now = Instant::now();
            tokens = (tokens + now.duration_since(last).as_secs_f64() * RATE).min(BURST);
            last = now;
            tokens -= 1.0;
            if tokens < 0.0 {
                return Err((CloseCode::Policy, "too many messages"));
            }
            match msg {
                Message::Text(text) => self.take(text.as_str())?,
                Message::Binary(_) => {
                    return Err((CloseCode::Unsupported, "binary messages are not read"))
                }
                Message::Close(_) => return Ok(()),
                Message::Ping(_) | Message::Pong(_) | Message::Frame(_) => {}
            }
        }
        Ok(())
    }

    fn take(&self, text: &str) -> Result<(), (CloseCode, &'static str)> {
        let bad = |why| (CloseCode::Policy, why);
        match messages::parse(text).map_err(bad)? {
            PageMessage::Ack(n) => self
                .book
                .acked(n, session::now(), &self.echoes)
                .map_err(|_| bad("acknowledged a frame never sent")),
            PageMessage::Size(c, r) => {
                self.size.send_replace((c, r));
                Ok(())
            }
            PageMessage::Key(ev) => self
                .input
                .try_send(Input::Keys(vec![ev]))
                .map_err(|_| bad("keys faster than the game reads them")),
            PageMessage::Ray(column) => self
                .input
                .try_send(Input::Ray(column))
                .map_err(|_| bad("keys faster than the game reads them")),
        }
    }
}
