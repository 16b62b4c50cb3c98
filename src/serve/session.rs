//! One connected terminal: reads its keys, follows the world's snapshots, and sends it frames at
//! its own size and pace.
//!
//! Keys go through the local TUI's key map (`tui::keys::Controls`) into the same `game::Input`
//! the local game steps with; the world task applies it. Frames are the TUI's panes
//! ([`super::screen`]).
//!
//! Output is bounded: the task renders only when it is ready to send, and waits for each frame to
//! be taken by the SSH layer (which itself stops taking when the client's window is full). While
//! it waits, frame ticks pass and are skipped, so a slow client gets fewer, newer frames — the
//! latest frame wins — and nothing queues without bound.

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::{Duration, Instant};

use russh::server::Handle;
use russh::ChannelId;
use tokio::sync::{mpsc, watch};
use tokio::time::MissedTickBehavior;

use super::ask_colour::{ask_truecolor, SSH_QUERY_PATIENCE};
use super::config::clamp_size;
use super::handler::BoardLine;
use super::header::{self, Piece};
use super::leaderboard::{board_key, shown_name, Boards};
use super::log::Log;
use super::metrics::{self, FrameMetrics, Reason};
use super::screen::{panes_for, view_rect, SessionScreen};
use super::stats::ServeStats;
use super::world_task::{WorldHandle, WorldMsg};
use crate::encode::{ColorLevel, ColourChoice, ColourReason};
use crate::game::multi::players::{PlayerId, Snapshot};
use crate::game::Held;
use crate::render::glyphs::Glyphs;
use crate::ui::glyph_cycle::GlyphCycle;
use crate::ui::key_bytes::{InputEvent, InputParser};
use crate::ui::key_route::{route, Routed};
use crate::ui::keys::{Controls, InputMode, UiCommand};
use crate::ui::layout::Toggles;
use crate::ui::octant_support::{octant_dropper, TermEnv};
use crate::ui::results::Board;
use crate::world::World;

/// Alternate screen, hidden cursor, cleared; kitty keyboard flags pushed (disambiguate, event
/// types, all keys as escapes) and queried, so release events arrive where supported.
const ENTER: &[u8] = b"\x1b[?1049h\x1b[?25l\x1b[0m\x1b[2J\x1b[>11u\x1b[?u";
/// Everything [`ENTER`] changed, undone.
pub const LEAVE: &[u8] = b"\x1b[<u\x1b[0m\x1b[?25h\x1b[?1049l";
/// How long an unfinished escape sequence may wait before a lone ESC counts as the Esc key.
const ESC_WAIT: Duration = Duration::from_millis(50);
/// How long a note shows over the status line.
const NOTICE_FOR: Duration = Duration::from_secs(4);
/// How an SSH player asks for octants where the glyph key skips them.
pub const FORCE_OCTANTS: &str = "ssh -o SetEnv=HALFCAST_GLYPHS=octant forces";

/// What the session needs from the server; built by the connection handler at `shell`.
pub struct SessionParams {
    pub id: u64,
    pub peer: SocketAddr,
    pub name: String,
    /// Watches a player's view instead of playing.
    pub spectator: bool,
    pub term: String,
    pub colorterm: Option<String>,
    /// `TMUX`, when the client sent it (an env request): tmux drops octants.
    pub tmux: Option<String>,
    /// `HALFCAST_GLYPHS`, when the client sent it: the block characters to start with (octant
    /// there forces octants into the glyph key's cycle).
    pub glyphs: Option<Glyphs>,
    pub handle: Handle,
    pub channel: ChannelId,
    pub world: WorldHandle,
    /// The lasting leaderboard, when the server keeps one.
    pub boards: Option<BoardLine>,
    /// The served world (with the avatar sheet at `avatar_sheet`).
    pub world_data: Arc<World>,
    pub avatar_sheet: usize,
    pub fps: u32,
    /// Players with no keystroke for this long are closed; spectators never are.
    pub idle_timeout: Duration,
    /// A client that takes no frame for this long is dropped (its link is dead or it never
    /// reads); the connection is then closed too.
    pub stall_timeout: Duration,
    pub stats: Arc<ServeStats>,
    pub log: Log,
    pub shutdown: watch::Receiver<bool>,
    /// The last line a player sees when the server stops (see [`super::drain`]).
    pub farewell: watch::Receiver<&'static str>,
}

/// What the connection handler feeds the session: raw key bytes, and the latest pty size.
pub struct SessionInputs {
    pub data: mpsc::Receiver<Vec<u8>>,
    pub size: watch::Receiver<(u32, u32)>,
}

/// Why a session ended (for the log, and for how the connection is closed).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum End {
    Quit,
    ClientGone,
    Idle,
    Stalled,
    Shutdown,
}

/// Counters for one session's log line.
#[derive(Debug, Default)]
struct Tally {
    frames: u64,
    bytes: u64,
    dropped: u64,
}

/// Runs a session until the client quits or leaves, stops reading, the idle timeout, or server
/// shutdown; says which.
pub async fn run(p: SessionParams, mut inputs: SessionInputs) -> End {
    let mut s = State::new(&p, *inputs.size.borrow());
    let mut shutdown = p.shutdown.clone();
    let frame_metrics = FrameMetrics::new();
    metrics::session(p.spectator, true);
    let boards = p.boards.as_ref().map(|b| b.board.boards());
    // (map index, name) whose own best was last asked for.
    let mut asked: Option<(usize, String)> = None;
    if !p.spectator {
        p.world
            .send(WorldMsg::Join {
                id: p.id,
                name: p.name.clone(),
            })
            .await;
    }
    // Before the first frame: a TERM guess is checked with the client's terminal itself.
    let mut early_end = None;
    let mut entered = false;
    if s.screen.colour().worth_asking() {
        // On the alternate screen, so a terminal that shows a query as text shows it there only.
        entered = true;
        let (answer, typed) = ask_truecolor(
            &p.handle,
            p.channel,
            ENTER,
            &mut inputs.data,
            SSH_QUERY_PATIENCE,
        )
        .await;
        s.screen.set_colour(s.screen.colour().with_answer(answer));
        if !typed.is_empty() {
            early_end = keys_early(&mut s, &typed);
        }
    }
    let mut snaps = p.world.snapshots();
    let fps = p.fps.clamp(1, 240);
    let period = Duration::from_secs_f64(1.0 / f64::from(fps));
    let mut tick = tokio::time::interval(period);
    tick.set_missed_tick_behavior(MissedTickBehavior::Skip);
    let mut last_tick: Option<tokio::time::Instant> = None;
    let mut tally = Tally::default();
    let mut out = if entered { Vec::new() } else { ENTER.to_vec() };
    let mut keys = Vec::new();
    // Whether the world's (unique) name for us has been seen; spectators have none.
    let mut named = p.spectator;
    let end = loop {
        tokio::select! {
            biased;
            Some(end) = std::future::ready(early_end), if early_end.is_some() => break end,
            _ = shutdown.changed() => break End::Shutdown,
            data = inputs.data.recv() => {
                let Some(bytes) = data else { break End::ClientGone };
                s.last_input = Instant::now();
                keys.clear();
                s.parser.feed(&bytes, &mut keys);
                if s.parser.has_pending() {
                    s.pending_since.get_or_insert(s.last_input);
                } else {
                    s.pending_since = None;
                }
                if let Some(end) = s.on_keys(&keys, &snaps.borrow()) {
                    break end;
                }
            }
            changed = inputs.size.changed() => {
                if changed.is_err() { break End::ClientGone }
                let (c, r) = *inputs.size.borrow_and_update();
                s.resize(c, r);
            }
            at = tick.tick() => {
                if let Some(prev) = last_tick {
                    let gap = at.duration_since(prev).as_secs_f64() / period.as_secs_f64();
                    let skipped = (gap.round() as u64).saturating_sub(1);
                    tally.dropped += skipped;
                    frame_metrics.skipped(skipped);
                }
                last_tick = Some(at);
                let now = Instant::now();
                if s.pending_since.is_some_and(|t| now.duration_since(t) >= ESC_WAIT) {
                    keys.clear();
                    s.parser.flush(&mut keys);
                    s.pending_since = None;
                    if let Some(end) = s.on_keys(&keys, &snaps.borrow()) {
                        break end;
                    }
                }
                if !p.spectator && now.duration_since(s.last_input) >= p.idle_timeout {
                    break End::Idle;
                }
                if !p.spectator {
                    if let Some(msg) = s.world_input(p.id, now) {
                        p.world.send(msg).await;
                    }
                }
                let snap = snaps.borrow_and_update().clone();
                if !named {
                    if let Some(me) = snap.player(p.id) {
                        named = true;
                        if me.name != p.name {
                            // The log line at login named what was asked for.
                            p.log.session(
                                p.id,
                                p.peer,
                                format_args!("{:?} was taken: plays as {:?}", p.name, me.name),
                            );
                        }
                    }
                }
                if let (Some(line), Some(me)) = (&p.boards, snap.player(p.id)) {
                    // Ask for our own best on each map as we come to it.
                    let here = (snap.map, me.name.clone());
                    if asked.as_ref() != Some(&here) {
                        if let Some(hash) = line.hashes.get(snap.map) {
                            line.board.lookup(hash, line.mode, &here.1);
                        }
                        asked = Some(here);
                    }
                }
                // Only while shown: a frame of play builds no board.
                s.leaders = match (&p.boards, &boards) {
                    (Some(line), Some(rx)) if snap.ended.is_some() || s.show_leaders => {
                        leaders(line, &rx.borrow(), &snap, p.id)
                    }
                    _ => None,
                };
                s.compose(&snap, &mut out);
                if out.is_empty() {
                    continue;
                }
                let (render, encode) = s.screen.last_times();
                frame_metrics.timed(render, encode);
                let n = out.len() as u64;
                let bytes = std::mem::take(&mut out);
                match tokio::time::timeout(p.stall_timeout, p.handle.data(p.channel, bytes)).await {
                    Err(_) => break End::Stalled,
                    Ok(Err(_)) => break End::ClientGone,
                    Ok(Ok(())) => {
                        tally.frames += 1;
                        tally.bytes += n;
                        frame_metrics.sent(n as usize);
                    }
                }
            }
        }
    };
    if !p.spectator {
        p.world.send(WorldMsg::Leave { id: p.id }).await;
    }
    if !matches!(end, End::ClientGone | End::Stalled) {
        let mut bye = LEAVE.to_vec();
        let farewell = super::drain::farewell_line(*p.farewell.borrow());
        bye.extend_from_slice(match end {
            End::Idle => b"halfcast: closed after being idle too long.\r\n".as_slice(),
            End::Shutdown => &farewell,
            _ => b"",
        });
        // Best effort: the client may already be gone; don't wait on a dead link.
        let h = &p.handle;
        let _ = tokio::time::timeout(Duration::from_secs(2), async {
            let _ = h.data(p.channel, bye).await;
            let _ = h.exit_status_request(p.channel, 0).await;
            let _ = h.eof(p.channel).await;
            let _ = h.close(p.channel).await;
        })
        .await;
    }
    metrics::session(p.spectator, false);
    if end == End::Stalled {
        metrics::refused(Reason::Stall);
    }
    ServeStats::add(&p.stats.frames_sent, tally.frames);
    ServeStats::add(&p.stats.bytes_sent, tally.bytes);
    ServeStats::add(&p.stats.frames_dropped, tally.dropped);
    p.log.session(
        p.id,
        p.peer,
        format_args!(
            "session ended ({end:?}): {} frames, {} bytes, {} frame ticks skipped",
            tally.frames, tally.bytes, tally.dropped
        ),
    );
    end
}

/// Keys the player typed while the colour query ran: parsed now, acted on with the first
/// snapshot's input (an unfinished escape waits for the usual flush). Returns an end if one
/// of them quits.
fn keys_early(s: &mut State, bytes: &[u8]) -> Option<End> {
    let mut keys = Vec::new();
    s.parser.feed(bytes, &mut keys);
    if s.parser.has_pending() {
        s.pending_since = Some(Instant::now());
    }
    s.on_keys(&keys, &Snapshot::default())
}

/// (snapshot version, size, colour level, block characters, note shown, eye, panes,
/// leaderboard shown): everything a frame is drawn from.
type Shown = (
    u64,
    (u16, u16),
    ColourChoice,
    (Glyphs, bool),
    Option<PlayerId>,
    Toggles,
    Option<(Board, bool)>,
);

/// The leaderboard a session shows for the map of `snap` (the finished round's map while the
/// results show): top entries with escaped names, and `me`'s own best.
fn leaders(line: &BoardLine, boards: &Boards, snap: &Snapshot, me: PlayerId) -> Option<Board> {
    let map = snap.ended.as_ref().map_or(snap.map, |e| e.map);
    let hash = line.hashes.get(map)?;
    let board = boards.maps.get(&board_key(hash, line.mode));
    let top = board.map(|b| b.top.as_slice()).unwrap_or_default();
    let rows = top
        .iter()
        .enumerate()
        .map(|(i, e)| {
            (
                format!("{:>2}. {}", i + 1, shown_name(&e.name)),
                e.figure(line.mode),
            )
        })
        .collect();
    let own = snap
        .player(me)
        .and_then(|p| board?.bests.get(&p.name))
        .map(|e| e.figure(line.mode));
    Some(Board {
        title: format!("All-time top {} on this map", super::leaderboard::TOP),
        rows,
        own,
    })
}

/// What is on the client's screen and what it asked for; everything the frame depends on.
struct State {
    spectator: bool,
    me: PlayerId,
    size: (u16, u16),
    /// Whether the client claimed a bigger terminal than we draw (the header says so).
    clamped: bool,
    following: Option<PlayerId>,
    parser: InputParser,
    pending_since: Option<Instant>,
    controls: Controls,
    /// What the world was last told: held keys and view width.
    sent: (Held, usize),
    last_input: Instant,
    screen: SessionScreen,
    /// What the frame on screen was drawn from, to skip identical frames.
    shown: Option<Shown>,
    /// The leaderboard to show (on the results, and over the game while `L` is on).
    leaders: Option<Board>,
    /// Whether `L` put the leaderboard over the game.
    show_leaders: bool,
    /// The glyph key's cycle for this client (without octant behind tmux, unless asked for).
    glyph_cycle: GlyphCycle,
    /// The last header and what it was made from: it changes only when someone joins, leaves
    /// or scores, so most frames reuse it.
    header: Option<(HeaderFrom, String)>,
}

/// Everything [`State::header`] reads: names here, the eye's name, the scoreboard, the colour
/// level, the size and whether it was clamped.
#[derive(Debug, Clone, PartialEq)]
struct HeaderFrom {
    names: Vec<String>,
    eye: Option<String>,
    scoreboard: crate::game::multi::round::Scoreboard,
    colour: ColourChoice,
    size: (u16, u16),
    clamped: bool,
    /// Whether the map has a game (its scoreboard replaces the list of who is here).
    game: bool,
}

impl HeaderFrom {
    /// Whether a header made from `self` is the one `snap` through `eye` would make.
    fn same(&self, snap: &Snapshot, eye: Option<&str>, now: &HeaderFrom) -> bool {
        self.size == now.size
            && self.clamped == now.clamped
            && self.game == now.game
            && self.colour == now.colour
            && self.eye.as_deref() == eye
            && self.scoreboard == snap.scoreboard
            && self.names.len() == snap.players.len()
            && self
                .names
                .iter()
                .zip(&snap.players)
                .all(|(n, p)| *n == p.name)
    }
}

impl State {
    fn new(p: &SessionParams, size: (u32, u32)) -> Self {
        let colour = level_for_term(&p.term, p.colorterm.as_deref());
        let glyphs = p.glyphs.unwrap_or_default();
        let dropper = octant_dropper(TermEnv {
            term: Some(&p.term),
            tmux: p.tmux.as_deref(),
        });
        Self {
            spectator: p.spectator,
            me: p.id,
            size: clamp_size(size.0, size.1),
            clamped: is_clamped(size),
            following: None,
            parser: InputParser::new(),
            pending_since: None,
            controls: Controls::new(InputMode::Emulated),
            sent: (Held::default(), usize::MAX),
            last_input: Instant::now(),
            screen: {
                let mut screen = SessionScreen::new(&p.world_data, p.avatar_sheet, colour.level);
                screen.set_colour(colour);
                screen.set_glyphs(glyphs);
                screen
            },
            shown: None,
            leaders: None,
            show_leaders: false,
            glyph_cycle: GlyphCycle::new(dropper, glyphs, FORCE_OCTANTS),
            header: None,
        }
    }

    /// Follows the client's claimed terminal size, within the bounds.
    fn resize(&mut self, cols: u32, rows: u32) {
        self.size = clamp_size(cols, rows);
        self.clamped = is_clamped((cols, rows));
    }

    /// Acts on parsed keys; returns an end if one of them quits.
    fn on_keys(&mut self, events: &[InputEvent], snap: &Snapshot) -> Option<End> {
        let now = Instant::now();
        if let Some(p) = snap.player(self.me) {
            // Paused, the turn keys move the debugged column instead of turning.
            self.controls.set_paused(p.state.debugger.paused);
        }
        for ev in events {
            match *ev {
                InputEvent::KittyFlags(_) => {
                    if self.controls.mode() != InputMode::Kitty {
                        self.controls = Controls::new(InputMode::Kitty);
                    }
                }
                InputEvent::Key(k) => match route(k) {
                    Routed::NextTarget => self.following = cycle(snap, self.following, true),
                    Routed::PrevTarget => self.following = cycle(snap, self.following, false),
                    Routed::Leaderboard => self.show_leaders = !self.show_leaders,
                    Routed::Tui(ev) => self.controls.handle(&ev, now),
                    Routed::Nothing => {}
                },
            }
        }
        let mut uis = self.controls.take_ui();
        if let Some(note) = self.glyph_cycle.resolve(&mut uis, self.screen.glyphs()) {
            self.screen.set_notice(note, now + NOTICE_FOR);
        }
        for ui in uis {
            let toggles = &mut self.screen.toggles;
            match ui {
                UiCommand::Quit => return Some(End::Quit),
                UiCommand::Back if toggles.help => toggles.help = false,
                UiCommand::Back => return Some(End::Quit),
                UiCommand::ToggleMinimap => toggles.minimap = !toggles.minimap,
                UiCommand::ToggleDebug => toggles.debug = !toggles.debug,
                UiCommand::ToggleHelp => toggles.help = !toggles.help,
                UiCommand::CycleColours => self.screen.set_colour(self.screen.colour().cycled()),
                UiCommand::SetGlyphs(g) => self.screen.set_glyphs(g),
                // Resolved into `SetGlyphs` by the glyph cycle above.
                UiCommand::CycleGlyphs => self.screen.set_glyphs(self.screen.glyphs().cycled()),
                // Over SSH the figure key is off: it would write on the server's disk.
                UiCommand::SaveFigure => {}
            }
        }
        None
    }

    /// The message for the world at `now`, when the player's input changed since the last one.
    fn world_input(&mut self, id: PlayerId, now: Instant) -> Option<WorldMsg> {
        let input = self.controls.take_input(now);
        let width = usize::from(view_rect(&panes_for(self.size, self.screen.toggles)).width);
        if input.commands.is_empty() && (input.held, width) == self.sent {
            return None;
        }
        self.sent = (input.held, width);
        Some(WorldMsg::Input {
            id,
            input,
            view_width: width,
        })
    }

    /// Whose eyes this session looks through now.
    fn eye(&mut self, snap: &Snapshot) -> Option<PlayerId> {
        if !self.spectator {
            return Some(self.me);
        }
        if self.following.is_none_or(|id| snap.player(id).is_none()) {
            self.following = snap.players.first().map(|p| p.id);
        }
        self.following
    }

    /// The header: who you are or whom you watch, who is here, the colour level, server keys.
    /// ASCII only, so it reads the same at every colour level (mono turns other glyphs to `#`).
    fn header(&self, snap: &Snapshot, eye: Option<PlayerId>) -> String {
        let names: Vec<&str> = snap.players.iter().map(|p| p.name.as_str()).collect();
        let who = match (eye.and_then(|e| snap.player(e)), self.spectator) {
            (Some(p), true) => format!("watching {} (Tab: next)", p.name),
            (None, true) => "waiting for players (Tab: next)".to_string(),
            // The world's name for us: unique among those here (`ada-2`).
            (Some(p), false) => format!("you are {}", p.name),
            (None, false) => "joining...".to_string(),
        };
        // On maps with something to play for, the game's scoreboard (which names everyone)
        // takes the place of the list of who is here; spectators see it too. When the line is
        // too narrow the key hint, the name and the colour level go before the scoreboard's
        // tail (or the list of who is here) shortens to ", +N more".
        let game = self.screen.map().has_game() && !snap.scoreboard.is_empty();
        let mut pieces = vec![Piece::text(1, "halfcast"), Piece::text(8, who)];
        if !game {
            pieces.push(Piece::List {
                keep: 5,
                prefix: format!("{} here: ", names.len()),
                items: names.iter().map(|n| (*n).to_owned()).collect(),
            });
        }
        pieces.push(Piece::text(3, self.screen.colour().to_string()));
        if game {
            pieces.push(Piece::text(6, snap.scoreboard.summary.clone()));
            pieces.push(Piece::List {
                keep: 5,
                prefix: String::new(),
                items: snap.scoreboard.rows.clone(),
            });
        }
        // O is the key map's default colour key (sessions use the default keys).
        pieces.push(Piece::text(0, "O colours"));
        if self.clamped {
            pieces.push(Piece::text(
                4,
                format!("clamped to {}x{}", self.size.0, self.size.1),
            ));
        }
        header::fit(&pieces, usize::from(self.size.0))
    }

    /// Appends the bytes of the next frame to `out` (nothing if the screen would not change).
    fn compose(&mut self, snap: &Snapshot, out: &mut Vec<u8>) {
        let eye = self.eye(snap);
        let key = (
            snap.version,
            self.size,
            self.screen.colour(),
            (
                self.screen.glyphs(),
                self.screen.notice_showing(Instant::now()),
            ),
            eye,
            self.screen.toggles,
            self.leaders.clone().map(|b| (b, self.show_leaders)),
        );
        if self.shown.as_ref() == Some(&key) {
            return;
        }
        self.shown = Some(key);
        self.screen
            .set_leaders(self.leaders.clone(), self.show_leaders);
        let eye_name = eye.and_then(|e| snap.player(e)).map(|p| p.name.as_str());
        // The parts of the key that cost nothing to build; the names and board are compared
        // in place.
        let mut now = HeaderFrom {
            names: Vec::new(),
            eye: None,
            scoreboard: Default::default(),
            colour: self.screen.colour(),
            size: self.size,
            clamped: self.clamped,
            game: self.screen.map().has_game(),
        };
        let fresh = self
            .header
            .as_ref()
            .is_some_and(|(from, _)| from.same(snap, eye_name, &now));
        if !fresh {
            now.names = snap.players.iter().map(|p| p.name.clone()).collect();
            now.eye = eye_name.map(str::to_owned);
            now.scoreboard = snap.scoreboard.clone();
            let text = self.header(snap, eye);
            self.header = Some((now, text));
        }
        let header = self.header.as_ref().map_or("", |(_, h)| h.as_str());
        let mode = self.controls.mode();
        out.extend_from_slice(self.screen.frame(snap, eye, header, self.size, mode));
    }
}

/// Whether a claimed size is outside what we draw (beyond the bounds, or zero).
fn is_clamped((cols, rows): (u32, u32)) -> bool {
    let (c, r) = clamp_size(cols, rows);
    (u32::from(c), u32::from(r)) != (cols, rows)
}

/// The colour level for a client's `TERM` (and `COLORTERM`, when its client sends it as an env
/// request): the encoder's own rule, plus terminals known to show 24-bit colour whatever their
/// `TERM` says.
fn level_for_term(term: &str, colorterm: Option<&str>) -> ColourChoice {
    const TRUECOLOR_TERMS: [&str; 9] = [
        "truecolor",
        "24bit",
        "kitty",
        "alacritty",
        "wezterm",
        "foot",
        "ghostty",
        "iterm",
        "contour",
    ];
    let lower = term.to_ascii_lowercase();
    let env = ColourChoice::from_env(colorterm, Some(term), None);
    if env.reason == ColourReason::Colorterm {
        return env;
    }
    if TRUECOLOR_TERMS.iter().any(|t| lower.contains(t)) {
        return ColourChoice {
            level: ColorLevel::TrueColor,
            reason: ColourReason::Term,
        };
    }
    let term = if term.is_empty() { "dumb" } else { term };
    ColourChoice::from_env(colorterm, Some(term), None)
}

/// The next (or previous) player after `current` in join order, wrapping; `None` if nobody.
fn cycle(snap: &Snapshot, current: Option<PlayerId>, forward: bool) -> Option<PlayerId> {
    let ids: Vec<PlayerId> = snap.players.iter().map(|p| p.id).collect();
    if ids.is_empty() {
        return None;
    }
    let at = current.and_then(|c| ids.iter().position(|&i| i == c));
    let n = ids.len();
    let next = match (at, forward) {
        (None, _) => 0,
        (Some(i), true) => (i + 1) % n,
        (Some(i), false) => (i + n - 1) % n,
    };
    Some(ids[next])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::multi::players::Players;

    #[test]
    fn tab_cycles_through_players_both_ways() {
        let mut ps = Players::new(Arc::new(World::default_world()));
        for (id, n) in [(5, "a"), (7, "b"), (9, "c")] {
            ps.join(id, n);
        }
        let snap = ps.snapshot();
        assert_eq!(cycle(&snap, None, true), Some(5));
        assert_eq!(cycle(&snap, Some(5), true), Some(7));
        assert_eq!(cycle(&snap, Some(9), true), Some(5));
        assert_eq!(cycle(&snap, Some(5), false), Some(9));
        assert_eq!(cycle(&Snapshot::default(), Some(5), true), None);
    }

    #[test]
    fn the_header_is_made_again_when_someone_joins_or_the_size_changes() {
        let mut ps = Players::new(Arc::new(World::default_world()));
        ps.join(5, "a");
        let snap = ps.snapshot();
        let from = HeaderFrom {
            names: vec!["a".into()],
            eye: Some("a".into()),
            scoreboard: snap.scoreboard.clone(),
            colour: level_for_term("xterm-256color", None),
            size: (80, 24),
            clamped: false,
            game: false,
        };
        assert!(from.same(&snap, Some("a"), &from.clone()));
        let mut wider = from.clone();
        wider.size = (81, 24);
        assert!(!from.same(&snap, Some("a"), &wider));
        ps.join(7, "b");
        assert!(!from.same(&ps.snapshot(), Some("a"), &from.clone()));
    }

    #[test]
    fn term_names_map_to_levels() {
        assert_eq!(
            level_for_term("xterm-kitty", None).level,
            ColorLevel::TrueColor
        );
        assert_eq!(
            level_for_term("xterm-direct", None).level,
            ColorLevel::TrueColor
        );
        assert_eq!(
            level_for_term("xterm-256color", None).level,
            ColorLevel::Ansi256
        );
        assert_eq!(
            level_for_term("xterm-256color", Some("truecolor")).level,
            ColorLevel::TrueColor
        );
        assert_eq!(level_for_term("xterm", None).level, ColorLevel::Ansi16);
        assert_eq!(level_for_term("", None).level, ColorLevel::Mono);
        assert_eq!(level_for_term("dumb", None).level, ColorLevel::Mono);
    }
}
