//! One connected terminal: reads its keys, follows the world's snapshots, and sends it frames at
//! its own size and pace.
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

use super::color_level::{self, ColorLevel};
use super::config::clamp_size;
use super::controls::{Action, HeldKeys};
use super::frame::FrameEncoder;
use super::input::{InputEvent, InputParser};
use super::log::Log;
use super::player::Held;
use super::players::{PlayerId, Snapshot};
use super::stats::ServeStats;
use super::view::{render_view, status_line};
use super::world_task::{WorldHandle, WorldMsg};
use crate::framebuffer::Framebuffer;
use crate::world::World;

/// Alternate screen, hidden cursor, cleared; kitty keyboard flags pushed (disambiguate, event
/// types, all keys as escapes) and queried, so release events arrive where supported.
const ENTER: &[u8] = b"\x1b[?1049h\x1b[?25l\x1b[0m\x1b[2J\x1b[>11u\x1b[?u";
/// Everything [`ENTER`] changed, undone.
pub const LEAVE: &[u8] = b"\x1b[<u\x1b[0m\x1b[?25h\x1b[?1049l";
/// How long an unfinished escape sequence may wait before a lone ESC counts as the Esc key.
const ESC_WAIT: Duration = Duration::from_millis(50);
/// A client that takes no frame for this long is dropped (its link is dead or it never reads).
const WRITE_STALL: Duration = Duration::from_secs(30);

/// What the session needs from the server; built by the connection handler at `shell`.
pub struct SessionParams {
    pub id: u64,
    pub peer: SocketAddr,
    pub name: String,
    /// Watches a player's view instead of playing.
    pub spectator: bool,
    pub term: String,
    pub colorterm: Option<String>,
    pub handle: Handle,
    pub channel: ChannelId,
    pub world: WorldHandle,
    pub world_data: Arc<World>,
    pub fps: u32,
    pub idle_timeout: Duration,
    pub stats: Arc<ServeStats>,
    pub log: Log,
    pub shutdown: watch::Receiver<bool>,
}

/// What the connection handler feeds the session: raw key bytes, and the latest pty size.
pub struct SessionInputs {
    pub data: mpsc::Receiver<Vec<u8>>,
    pub size: watch::Receiver<(u32, u32)>,
}

/// Why a session ended (for the log).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum End {
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

/// Runs a session until the client quits or leaves, the idle timeout, or server shutdown.
pub async fn run(p: SessionParams, mut inputs: SessionInputs) {
    let mut s = State::new(&p, *inputs.size.borrow());
    let mut shutdown = p.shutdown.clone();
    if !p.spectator {
        p.world
            .send(WorldMsg::Join {
                id: p.id,
                name: p.name.clone(),
            })
            .await;
    }
    let mut snaps = p.world.snapshots();
    let fps = p.fps.clamp(1, 240);
    let period = Duration::from_secs_f64(1.0 / f64::from(fps));
    let mut tick = tokio::time::interval(period);
    tick.set_missed_tick_behavior(MissedTickBehavior::Skip);
    let mut last_tick: Option<tokio::time::Instant> = None;
    let mut tally = Tally::default();
    let mut out = ENTER.to_vec();
    let mut keys = Vec::new();
    let end = loop {
        tokio::select! {
            biased;
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
                s.resize(clamp_size(c, r));
            }
            at = tick.tick() => {
                if let Some(prev) = last_tick {
                    let gap = at.duration_since(prev).as_secs_f64() / period.as_secs_f64();
                    tally.dropped += (gap.round() as u64).saturating_sub(1);
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
                if now.duration_since(s.last_input) >= p.idle_timeout {
                    break End::Idle;
                }
                if !p.spectator {
                    let held = s.held.held(now);
                    if held != s.sent_held {
                        s.sent_held = held;
                        p.world.send(WorldMsg::Held { id: p.id, held }).await;
                    }
                }
                let snap = snaps.borrow_and_update().clone();
                s.compose(&snap, &mut out);
                if out.is_empty() {
                    continue;
                }
                let n = out.len() as u64;
                let bytes = std::mem::take(&mut out);
                match tokio::time::timeout(WRITE_STALL, p.handle.data(p.channel, bytes)).await {
                    Err(_) => break End::Stalled,
                    Ok(Err(_)) => break End::ClientGone,
                    Ok(Ok(())) => {
                        tally.frames += 1;
                        tally.bytes += n;
                    }
                }
            }
        }
    };
    if !p.spectator {
        p.world.send(WorldMsg::Leave { id: p.id }).await;
    }
    if end != End::ClientGone {
        let mut bye = LEAVE.to_vec();
        bye.extend_from_slice(match end {
            End::Idle => b"halfcast: closed after being idle too long.\r\n".as_slice(),
            End::Shutdown => b"halfcast: the server is shutting down.\r\n",
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
}

/// (snapshot version, size, colour level, eye): everything a frame is drawn from.
type Shown = (u64, (u16, u16), ColorLevel, Option<PlayerId>);

/// What is on the client's screen and what it asked for; everything the frame depends on.
struct State {
    world: Arc<World>,
    spectator: bool,
    me: PlayerId,
    size: (u16, u16),
    level: ColorLevel,
    following: Option<PlayerId>,
    parser: InputParser,
    pending_since: Option<Instant>,
    held: HeldKeys,
    sent_held: Held,
    last_input: Instant,
    encoder: FrameEncoder,
    fb: Framebuffer,
    /// What the frame on screen was drawn from, to skip identical frames.
    shown: Option<Shown>,
    status: String,
    clear: bool,
}

impl State {
    fn new(p: &SessionParams, size: (u32, u32)) -> Self {
        let level = color_level::from_term(&p.term, p.colorterm.as_deref());
        Self {
            world: Arc::clone(&p.world_data),
            spectator: p.spectator,
            me: p.id,
            size: clamp_size(size.0, size.1),
            level,
            following: None,
            parser: InputParser::new(),
            pending_since: None,
            held: HeldKeys::default(),
            sent_held: Held::default(),
            last_input: Instant::now(),
            encoder: FrameEncoder::new(level),
            fb: Framebuffer::new(0, 0),
            shown: None,
            status: String::new(),
            clear: false,
        }
    }

    fn resize(&mut self, size: (u16, u16)) {
        if size != self.size {
            self.size = size;
            self.clear = true;
        }
    }

    /// Acts on parsed keys; returns an end if one of them quits.
    fn on_keys(&mut self, events: &[InputEvent], snap: &Snapshot) -> Option<End> {
        let now = Instant::now();
        for ev in events {
            match *ev {
                InputEvent::KittyFlags(_) => self.held.releases = true,
                InputEvent::Key(k) => match self.held.on_event(k, now) {
                    Action::Quit => return Some(End::Quit),
                    Action::CycleColour => {
                        self.level = self.level.next();
                        self.clear = true;
                    }
                    Action::NextTarget => self.following = cycle(snap, self.following, true),
                    Action::PrevTarget => self.following = cycle(snap, self.following, false),
                    Action::Move(_) | Action::Nothing => {}
                },
            }
        }
        None
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

    /// Appends the bytes of the next frame to `out` (nothing if the screen would not change).
    fn compose(&mut self, snap: &Snapshot, out: &mut Vec<u8>) {
        let eye = self.eye(snap);
        let key = (snap.version, self.size, self.level, eye);
        if self.shown == Some(key) && !self.clear {
            return;
        }
        self.shown = Some(key);
        let (cols, rows) = self.size;
        let view_rows = if rows >= 2 { rows - 1 } else { rows };
        if self.clear {
            out.extend_from_slice(b"\x1b[0m\x1b[2J");
            self.encoder.invalidate(self.level);
            self.status.clear();
            self.clear = false;
        }
        self.fb
            .resize(usize::from(cols), usize::from(view_rows) * 2);
        let drawn = eye.is_some_and(|e| render_view(&self.world, snap, e, &mut self.fb));
        if !drawn {
            for y in 0..self.fb.height() {
                self.fb.row_mut(y).fill(crate::color::Rgb::default());
            }
        }
        self.encoder.encode(&self.fb, (0, 0), out);
        if rows >= 2 {
            let line = status_line(snap, eye, self.spectator, self.level.name(), cols);
            if line != self.status {
                let pad = usize::from(cols).saturating_sub(line.chars().count());
                out.extend_from_slice(
                    format!("\x1b[{rows};1H\x1b[0;7m{line}{:pad$}\x1b[0m", "").as_bytes(),
                );
                self.status = line;
            }
        }
    }
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
    use crate::serve::players::Players;

    #[test]
    fn tab_cycles_through_players_both_ways() {
        let world = World::default_world();
        let mut ps = Players::new();
        for (id, n) in [(5, "a"), (7, "b"), (9, "c")] {
            ps.join(&world.map, id, n);
        }
        let snap = ps.snapshot();
        assert_eq!(cycle(&snap, None, true), Some(5));
        assert_eq!(cycle(&snap, Some(5), true), Some(7));
        assert_eq!(cycle(&snap, Some(9), true), Some(5));
        assert_eq!(cycle(&snap, Some(5), false), Some(9));
        assert_eq!(cycle(&Snapshot::default(), Some(5), true), None);
    }
}
