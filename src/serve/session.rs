//! One connected terminal: reads its keys, follows the world's snapshots, and sends it frames at
//! its own size and pace.
//!
//! Keys go through the local TUI's key map (`tui::keys::Controls`) into the same `game::Input`
//! the local game steps with; the world task applies it. Frames are the TUI's panes
//! ([`super::screen`]).
//!
//! Output follows the link ([`super::link_pacer`]): a frame is drawn only once the last one has
//! nearly arrived (the kernel's count of unacknowledged bytes, [`super::link_probe`]), from the
//! newest snapshot. So a slow client gets fewer, newer frames and nothing queues behind the
//! player's keys; when the link carries fewer than 15 frames a second the colour level steps
//! down (`256 (link)`), and back up when it allows. Keys reach the world at once, and a changed
//! snapshot is drawn at once when the link is free, so a tap from idle shows without waiting
//! for a frame tick.

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::{Duration, Instant};

use russh::server::Handle;
use russh::ChannelId;
use tokio::sync::{mpsc, watch};
use tokio::time::MissedTickBehavior;

use super::ask_colour::{ask_colour, SSH_QUERY_PATIENCE};
use super::config::clamp_size;
use super::handler::BoardLine;
use super::header::{self, Piece};
use super::leaderboard::{board_key, shown_name, Boards};
use super::lifecycle::Lifeline;
use super::link_echo::EchoGate;
use super::link_pacer::{LinkFigures, LinkPacer, Step};
use super::link_probe::LinkProbe;
use super::log::Log;
use super::metrics::{self, FrameMetrics, Reason};
use super::screen::{panes_for, view_rect, SessionScreen};
use super::stats::ServeStats;
use super::world_task::{WorldHandle, WorldMsg};
use crate::encode::{ColourChoice, ColourReason};
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
/// How soon to look at the link again while a frame waits for it.
const LINK_RECHECK: Duration = Duration::from_millis(3);
/// How long a task waits for the client's answer to a frame's echo.
const ECHO_WAIT: Duration = Duration::from_secs(60);
/// How often the link figures on the header may change.
const LINK_SHOWN_EVERY: Duration = Duration::from_secs(1);
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
    /// The connection's socket: bytes written so far, its TCP addresses, and where the link
    /// figures go when the session ends.
    pub life: Arc<Lifeline>,
    /// Whether frames are acknowledged end to end ([`super::link_echo`]): behind a load balancer
    /// (`--proxy-protocol`), where the kernel sees only the hop to the balancer. A direct client's
    /// path is the socket's own, which the kernel's figures cover at no cost.
    pub echo: bool,
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
    let mut farewell = p.farewell.clone();
    let mut farewell_alive = true;
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
        let (colour, typed) = ask_colour(
            &p.handle,
            p.channel,
            ENTER,
            &mut inputs.data,
            SSH_QUERY_PATIENCE,
            s.screen.colour(),
        )
        .await;
        s.screen.set_colour(colour);
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
    let mut pacer = LinkPacer::new(period, s.screen.colour().level);
    let mut probe = p
        .life
        .tcp()
        .and_then(|(local, peer)| LinkProbe::open(local, peer));
    let mut echo = if p.echo {
        EchoGate::new()
    } else {
        EchoGate::off()
    };
    s.link_known = probe.is_some();
    // Whether the screen may have changed since the last frame; when the next look is due
    // (the frame-rate cap, or the link still carrying the last frame).
    let mut want = true;
    let mut again: Option<tokio::time::Instant> = None;
    // When the next frame is due on the `--fps` grid.
    let mut next_slot: Option<tokio::time::Instant> = None;
    let mut world_alive = true;
    let end = loop {
        tokio::select! {
            biased;
            Some(end) = std::future::ready(early_end), if early_end.is_some() => break end,
            _ = shutdown.changed() => break End::Shutdown,
            changed = farewell.changed(), if farewell_alive => {
                // Err: the server is gone; its shutdown signal ends the session.
                farewell_alive = changed.is_ok();
                if farewell_alive && *farewell.borrow_and_update() == super::drain::RESTARTING {
                    // Draining: the player hears it now, not only when the world stops.
                    s.screen.set_notice(
                        super::drain::DRAINING_NOTICE.to_owned(),
                        Instant::now() + Duration::from_secs(3600),
                    );
                    want = true;
                }
            }
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
                // At once, not at the next frame tick: the world applies it on its next tick.
                if !p.spectator {
                    if let Some(msg) = s.world_input(p.id, s.last_input) {
                        p.world.send(msg).await;
                    }
                }
                want = true;
            }
            changed = inputs.size.changed() => {
                if changed.is_err() { break End::ClientGone }
                let (c, r) = *inputs.size.borrow_and_update();
                s.resize(c, r);
                want = true;
            }
            changed = snaps.changed(), if world_alive => {
                world_alive = changed.is_ok();
                want = true;
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
                    want = true;
                }
                if !p.spectator && now.duration_since(s.last_input) >= p.idle_timeout {
                    break End::Idle;
                }
                // A held key's end is inferred from time, so the world hears it from here too.
                if !p.spectator {
                    if let Some(msg) = s.world_input(p.id, now) {
                        p.world.send(msg).await;
                    }
                }
                // A frame the client has not taken for the stall timeout: its link is dead or
                // it stopped reading.
                if pacer.waiting(now).is_some_and(|w| w >= p.stall_timeout) {
                    let sample = probe.as_mut().and_then(LinkProbe::sample);
                    let answered = echo.clear(period, now);
                    if !pacer.clear(p.life.written(), sample.as_ref(), answered, now) {
                        break End::Stalled;
                    }
                }
                if want {
                    // Wanted at a tick and still not drawn: the link held it back.
                    tally.dropped += u64::from(again.is_some());
                }
                // The world's snapshots bring its changes; the tick brings only what time
                // changes by itself: a note over the status line running out.
                want |= s.screen.notice_showing(now) != s.notice_shown;
            }
            () = sleep_until_some(again), if again.is_some() => {
                again = None;
            }
        }
        if !want {
            continue;
        }
        let now = tokio::time::Instant::now();
        // `--fps` frames a second at most, on a grid a period apart; a frame may come a quarter
        // period early, so the world's snapshots (a period apart, with some jitter) are each
        // drawn as they come. The first change after a pause goes at once.
        if let Some(next) = next_slot.map(|t| t - period / 4).filter(|&t| t > now) {
            again = Some(next);
            continue;
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
        if s.unchanged(&snap) {
            want = false;
            continue;
        }
        let wire = p.life.written();
        let sample = match probe.as_mut() {
            // Nothing in flight, or not yet written: no need to ask the kernel.
            Some(pr) if pacer.needs_sample(wire) => {
                let sample = pr.sample();
                if sample.is_none() {
                    // The kernel no longer knows the socket: pace on writes alone from now.
                    probe = None;
                }
                sample
            }
            _ => None,
        };
        let std_now = now.into_std();
        let answered = echo.clear(period, std_now);
        if !pacer.clear(wire, sample.as_ref(), answered, std_now) {
            again = Some(now + LINK_RECHECK);
            continue;
        }
        if let Some(d) = pacer.take_waited() {
            frame_metrics.link_wait(d);
        }
        again = None;
        want = false;
        if s.screen.colour().reason != ColourReason::Key {
            if let Some(step) = pacer.step(s.screen.colour().level, std_now) {
                let (level, down) = match step {
                    Step::Down(l) => (l, true),
                    Step::Up(l) => (l, false),
                };
                frame_metrics.level_step(down);
                s.screen.set_colour(ColourChoice {
                    level,
                    reason: ColourReason::Link,
                });
            }
        }
        s.show_link(link_figures(&pacer, &echo), std_now);
        s.compose(&snap, &mut out);
        if out.is_empty() {
            continue;
        }
        let (render, encode) = s.screen.last_times();
        frame_metrics.timed(render, encode);
        let n = out.len() as u64;
        let bytes = std::mem::take(&mut out);
        let wire_before = p.life.written();
        match tokio::time::timeout(p.stall_timeout, p.handle.data(p.channel, bytes)).await {
            Err(_) => break End::Stalled,
            Ok(Err(_)) => break End::ClientGone,
            Ok(Ok(())) => {
                pacer.sent(wire_before, s.screen.colour().level, std_now);
                if echo.on() {
                    send_echo(&p.handle, &mut echo, std_now);
                }
                next_slot = Some(next_slot.map_or(now, |t| t.max(now - period / 4)) + period);
                tally.frames += 1;
                tally.bytes += n;
                frame_metrics.sent(n as usize);
            }
        }
    };
    p.life.set_link(link_figures(&pacer, &echo));
    if !p.spectator {
        p.world.send(WorldMsg::Leave { id: p.id }).await;
    }
    if !matches!(end, End::ClientGone | End::Stalled) {
        let mut bye = LEAVE.to_vec();
        let farewell = super::drain::farewell_line_for(*p.farewell.borrow(), p.id);
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
            "session ended ({end:?}): {} frames, {} bytes, {} frame ticks skipped{}",
            tally.frames,
            tally.bytes,
            tally.dropped,
            link_summary(&link_figures(&pacer, &echo)),
        ),
    );
    end
}

/// The link's figures, with the round trip the client's own answers took where it gives them
/// (behind a load balancer the kernel sees only the hop to the balancer).
fn link_figures(pacer: &LinkPacer, echo: &EchoGate) -> LinkFigures {
    let mut f = pacer.figures();
    if let Some(rtt) = echo.least_rtt() {
        f.rtt = rtt;
    }
    f
}

/// After a frame: asks the client for an answer that comes only once it has read the frame
/// ([`super::link_echo`]); a task waits for it.
fn send_echo(handle: &Handle, echo: &mut EchoGate, now: Instant) {
    let (n, answers) = echo.sent(now);
    let handle = handle.clone();
    tokio::spawn(async move {
        let asked = Instant::now();
        // Success or failure alike: the client has read everything before it. No answer in
        // time (the connection is gone) leaves the frame unanswered.
        let answer =
            tokio::time::timeout(ECHO_WAIT, handle.cancel_forward_tcpip(String::new(), 0)).await;
        if answer.is_ok() {
            answers.answered(n, asked.elapsed());
        }
    });
}

/// Sleeps until `at` (never called with `None`: the select arm is disabled then).
async fn sleep_until_some(at: Option<tokio::time::Instant>) {
    if let Some(at) = at {
        tokio::time::sleep_until(at).await;
    }
}

/// The link part of the session's last log line: `; link 512 kbit/s, round trip 40 ms, …`.
fn link_summary(f: &LinkFigures) -> String {
    let Some(rate) = f.rate else {
        return String::new();
    };
    format!(
        "; link {}, round trip {}, most queued {} bytes, level steps {} down {} up",
        rate_text(rate),
        rtt_text(f.rtt),
        f.max_queued,
        f.steps_down,
        f.steps_up
    )
}

/// A round trip for people: `0.4 ms`, `35 ms`.
fn rtt_text(rtt: Duration) -> String {
    let ms = rtt.as_secs_f64() * 1000.0;
    if ms < 10.0 {
        format!("{ms:.1} ms")
    } else {
        format!("{ms:.0} ms")
    }
}

/// A link rate for people: `512 kbit/s`, `4.2 Mbit/s` (two significant figures at most).
fn rate_text(bytes_per_sec: f64) -> String {
    let kbit = bytes_per_sec * 8.0 / 1000.0;
    if kbit < 1000.0 {
        format!("{} kbit/s", round2(kbit))
    } else if kbit < 1_000_000.0 {
        format!("{} Mbit/s", round2(kbit / 1000.0))
    } else {
        format!("{} Gbit/s", round2(kbit / 1_000_000.0))
    }
}

/// `x` to two significant figures, without a trailing `.0`.
fn round2(x: f64) -> String {
    if x >= 100.0 {
        format!("{:.0}", (x / 10.0).round() * 10.0)
    } else if x >= 10.0 {
        format!("{:.0}", x.round())
    } else {
        let r = (x * 10.0).round() / 10.0;
        if r.fract() == 0.0 {
            format!("{r:.0}")
        } else {
            format!("{r:.1}")
        }
    }
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
    /// Whether a note was over the status line in the frame on screen.
    notice_shown: bool,
    /// Whether the kernel's figures for this link can be read (then the header shows them).
    link_known: bool,
    /// The link figures the header shows, and when they last changed.
    link: Option<(String, Instant)>,
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
    /// The link figures shown.
    link: Option<String>,
}

impl HeaderFrom {
    /// Whether a header made from `self` is the one `snap` through `eye` would make.
    fn same(&self, snap: &Snapshot, eye: Option<&str>, now: &HeaderFrom) -> bool {
        self.size == now.size
            && self.clamped == now.clamped
            && self.game == now.game
            && self.colour == now.colour
            && self.link == now.link
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
            notice_shown: false,
            link_known: false,
            link: None,
        }
    }

    /// Takes new link figures for the header, at most once per [`LINK_SHOWN_EVERY`] (so the
    /// header, and the frame, change rarely for them). They show while the link limits the
    /// frames or set the colour level; a link that keeps up leaves the header as it was.
    fn show_link(&mut self, f: LinkFigures, now: Instant) {
        if !self.link_known
            || self
                .link
                .as_ref()
                .is_some_and(|(_, at)| now.duration_since(*at) < LINK_SHOWN_EVERY)
        {
            return;
        }
        let shown = f.limiting || self.screen.colour().reason == ColourReason::Link;
        let text = match (shown, f.rate) {
            (true, Some(rate)) => Some(format!("link {} {}", rate_text(rate), rtt_text(f.rtt))),
            _ => None,
        };
        if self.link.as_ref().map(|(t, _)| t) != text.as_ref() {
            self.link = text.map(|t| (t, now));
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
        if let Some((link, _)) = &self.link {
            pieces.push(Piece::text(2, link.clone()));
        }
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

    /// Whether the frame drawn from `snap` now would be the one on screen (nothing to send).
    fn unchanged(&mut self, snap: &Snapshot) -> bool {
        let key = self.key(snap);
        self.shown.as_ref() == Some(&key)
    }

    /// Everything the frame drawn from `snap` depends on.
    fn key(&mut self, snap: &Snapshot) -> Shown {
        let eye = self.eye(snap);
        (
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
        )
    }

    /// Appends the bytes of the next frame to `out` (nothing if the screen would not change).
    fn compose(&mut self, snap: &Snapshot, out: &mut Vec<u8>) {
        let key = self.key(snap);
        let eye = key.4;
        if self.shown.as_ref() == Some(&key) {
            return;
        }
        self.notice_shown = key.3 .1;
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
            link: self.link.as_ref().map(|(t, _)| t.clone()),
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
/// request): the same rule as the local game's ([`crate::ui::colour_query::rules::guess`]).
fn level_for_term(term: &str, colorterm: Option<&str>) -> ColourChoice {
    crate::ui::colour_query::rules::guess(colorterm, Some(term), None)
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
    use crate::encode::ColorLevel;
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
            link: None,
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
        assert_eq!(level_for_term("xterm", None).level, ColorLevel::Ansi256);
        assert_eq!(level_for_term("", None).level, ColorLevel::Mono);
        assert_eq!(level_for_term("dumb", None).level, ColorLevel::Mono);
    }
}
