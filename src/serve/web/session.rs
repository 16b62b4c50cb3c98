//! The browser edge of a play session: the page's messages read into input, sizes and
//! acknowledgements ([`super::messages`]), the session run with a [`WebSink`], and a goodbye as
//! the WebSocket's close reason, which the page shows.

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;

use futures_util::stream::SplitStream;
use futures_util::{SinkExt, StreamExt};
use tokio::net::TcpStream;
use tokio::sync::{mpsc, watch, Mutex};
use tokio::time::Instant;
use tokio_tungstenite::tungstenite::protocol::frame::coding::CloseCode;
use tokio_tungstenite::tungstenite::protocol::CloseFrame;
use tokio_tungstenite::tungstenite::{Error as WsError, Message};
use tokio_tungstenite::WebSocketStream;

use super::acked::AckBook;
use super::edge::WebEdge;
use super::messages::{self, PageMessage};
use super::sink::{WebSink, Writer};
use crate::encode::{ColorLevel, ColourChoice, ColourReason};
use crate::play::acks::Echoes;
use crate::play::input::Input;
use crate::play::session::{self, End, Feeds, Setup};
use crate::serve::limits::Playing;
use crate::serve::ops::stats::ServeStats;
use crate::serve::session_hooks::{draining_notes, session_ended, session_started, ServerHooks};
use crate::ui::keys::InputMode;

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

/// Who a WebSocket plays as, from its upgrade request.
pub struct WebPlayer {
    pub id: u64,
    pub peer: SocketAddr,
    pub name: String,
    pub spectator: bool,
    pub size: (u32, u32),
    /// The session's place within `--max-sessions`, held until it ends.
    pub place: Playing,
}

/// Runs one page's session until it ends, then closes the WebSocket with the reason and logs it.
pub async fn run(ws: WebSocketStream<TcpStream>, edge: Arc<WebEdge>, p: WebPlayer) {
    let (writer, reader) = ws.split();
    let writer = Arc::new(Mutex::new(writer));
    let book = AckBook::default();
    let sink = WebSink::new(Arc::clone(&writer), book.clone());
    let (input_tx, input_rx) = mpsc::channel(INPUT_QUEUE);
    let (size_tx, size_rx) = watch::channel(p.size);
    let page = Page {
        input: input_tx,
        size: size_tx,
        book,
        echoes: sink.echoes(),
        writer: Arc::clone(&writer),
    };
    let log = edge.shared.log;
    let (id, peer) = (p.id, p.peer);
    let reading = tokio::spawn(async move {
        if let Err(why) = page.read(reader).await {
            log.session(id, peer, format_args!("closed: {}", why.1));
            close(&page.writer, why.0, why.1).await;
        }
    });
    session_started(p.spectator, "web");
    let joined = session::join(&edge.shared.world, p.id, &p.name, p.spectator).await;
    ServeStats::add(&edge.shared.stats.sessions_live, 1);
    edge.shared.log.login_web(id, peer, &p.name, p.spectator);
    let setup = setup(&edge, &p);
    let feeds = Feeds {
        input: input_rx,
        size: size_rx,
        shutdown: edge.shared.shutdown.clone(),
        announce: draining_notes(edge.shared.farewell.clone()),
    };
    let hooks = ServerHooks::new(id, peer, edge.shared.log, edge.shared.boards.clone());
    let (end, tally) = session::run(joined, setup, feeds, sink, hooks).await;
    reading.abort();
    let bye = farewell(end, *edge.shared.farewell.borrow());
    close(&writer, CloseCode::Normal, &bye).await;
    session_ended(
        (&edge.shared.stats, edge.shared.log),
        (p.id, p.peer),
        (p.spectator, "web"),
        end,
        &tally,
    );
    edge.shared
        .stats
        .sessions_live
        .fetch_sub(1, std::sync::atomic::Ordering::Relaxed);
    drop(p.place);
}

/// A browser's session start: true colour (the page draws every colour), key releases as they
/// happen, the server's frame rate and timeouts.
fn setup(edge: &WebEdge, p: &WebPlayer) -> Setup {
    let c = &edge.shared.config;
    Setup {
        id: p.id,
        name: p.name.clone(),
        spectator: p.spectator,
        colour: ColourChoice {
            level: ColorLevel::TrueColor,
            reason: ColourReason::Browser,
        },
        glyphs: crate::render::glyphs::Glyphs::default(),
        octant_dropper: None,
        force_octants: "",
        input_mode: InputMode::Released,
        early: Vec::new(),
        world: edge.shared.world.clone(),
        world_data: Arc::clone(&edge.shared.world_data),
        avatar_sheet: edge.shared.avatar_sheet,
        fps: c.fps,
        idle_timeout: c.idle_timeout,
        stall_timeout: c.stall_timeout,
    }
}

/// What the page reads as the session's last words.
fn farewell(end: End, farewell: &'static str) -> String {
    match end {
        End::Idle => "closed after being idle too long".to_owned(),
        End::Shutdown => farewell.to_owned(),
        End::Stalled => "the page took no frame for too long".to_owned(),
        End::Quit | End::ClientGone => "bye".to_owned(),
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
        }
    }
}
