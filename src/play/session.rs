//! One client's play session, whatever carries it: reads its input, follows the world's
//! snapshots, and sends it frames at its own size and pace through a [`FrameSink`].
//!
//! Keys go through the local game's key map into the same `game::Input` the local game steps
//! with; the world task applies it. Frames are the game's panes under a header
//! (`super::screen`).
//!
//! Output follows the link ([`super::pacing`]): a frame is drawn only once the last one has
//! nearly arrived (what the sink knows of its link, and the client's own acknowledgements), from
//! the newest snapshot. So a slow client gets fewer, newer frames and nothing queues behind the
//! player's keys; when the link carries fewer than 15 frames a second the colour level steps
//! down (`256 (link)`), and back up when it allows. Keys reach the world at once, and a changed
//! snapshot is drawn at once when the link is free, so a tap from idle shows without waiting
//! for a frame tick.
//!
//! Time is tokio's clock throughout, so a test can run a session on a paused clock.

use std::sync::Arc;
use std::time::{Duration, Instant};

use tokio::sync::watch;
use tokio::time::MissedTickBehavior;

pub use super::end::{End, Tally};
use super::hooks::Hooks;
use super::input::{Input, InputSource};
use super::pacing::{LinkFigures, LinkPacer, Step};
use super::player::Player;
pub use super::setup::{Client, Facts, Feeds, Rules, Setup};
use super::sink::FrameSink;
use super::world_port::{WorldHandle, WorldMsg};
use crate::encode::{ColourChoice, ColourReason};
use crate::game::multi::players::{PlayerId, Snapshot};
use crate::ui::frame_grid::FrameGrid;

/// How long an unfinished escape sequence may wait before a lone ESC counts as the Esc key.
const ESC_WAIT: Duration = Duration::from_millis(50);
/// How soon to look at the link again while a frame waits for it.
const LINK_RECHECK: Duration = Duration::from_millis(3);
/// How long a note from the server (a world draining) stays: until the session ends.
const STANDING_NOTE: Duration = Duration::from_secs(3600);

/// The clock a session runs on: tokio's, so a paused test clock drives it.
#[must_use]
pub fn now() -> Instant {
    tokio::time::Instant::now().into_std()
}

/// Proof that a session's player is in the world ([`join`]): a session runs only with one.
#[derive(Debug)]
pub struct Joined {
    _in_world: (),
}

/// Puts the player in the world (a spectator only watches): the first thing a transport does
/// once it admits a player, before anything else it asks its client (a terminal's colour query),
/// so the world counts them from then on (a draining world waits for the round of everyone
/// admitted, not only of those whose first frame was drawn).
pub async fn join(world: &WorldHandle, id: PlayerId, name: &str, spectator: bool) -> Joined {
    if !spectator {
        let msg = WorldMsg::Join {
            id,
            name: name.to_owned(),
        };
        world.send(msg).await;
    }
    Joined { _in_world: () }
}

/// Runs a session until the client quits or leaves, stops reading, the idle timeout, or server
/// shutdown; says which, with the session's figures. The player left the world when it returns;
/// the transport says goodbye afterwards.
pub async fn run<I: InputSource, S: FrameSink, H: Hooks>(
    _joined: Joined,
    setup: Setup,
    mut feeds: Feeds<I>,
    sink: S,
    hooks: H,
) -> (End, Tally) {
    let size = *feeds.size.borrow();
    let early = Input::Bytes(setup.client.facts.early.clone());
    let mut lp = Loop::new(setup, size, sink, hooks);
    let mut early_end = lp.p.take(early, &Snapshot::default(), now());
    let period = lp.grid.period();
    let mut tick = tokio::time::interval(period);
    tick.set_missed_tick_behavior(MissedTickBehavior::Skip);
    let (mut world_alive, mut announce_alive) = (true, true);
    let end = loop {
        let step = tokio::select! {
            biased;
            Some(end) = std::future::ready(early_end.take()), if early_end.is_some() => Err(end),
            _ = feeds.shutdown.changed() => Err(End::Shutdown),
            changed = feeds.announce.changed(), if announce_alive => {
                // Err: the server is gone; its shutdown signal ends the session.
                announce_alive = changed.is_ok();
                if announce_alive {
                    lp.announce(feeds.announce.borrow_and_update().clone());
                }
                Ok(())
            }
            input = feeds.input.recv() => lp.on_input(input).await,
            changed = feeds.size.changed() => match changed {
                Err(_) => Err(End::ClientGone),
                Ok(()) => {
                    let (c, r) = *feeds.size.borrow_and_update();
                    lp.p.resize(c, r);
                    lp.want = true;
                    Ok(())
                }
            },
            changed = lp.snaps.changed(), if world_alive => {
                world_alive = changed.is_ok();
                lp.want = true;
                Ok(())
            }
            at = tick.tick() => lp.on_tick(at).await,
            () = sleep_until_some(lp.again), if lp.again.is_some() => {
                lp.again = None;
                Ok(())
            }
        };
        if let Err(end) = step {
            break end;
        }
        if lp.want {
            if let Err(end) = lp.frame().await {
                break end;
            }
        }
    };
    let client = &lp.setup.client;
    if !client.spectator {
        let leave = WorldMsg::Leave { id: client.id };
        lp.setup.rules.world.send(leave).await;
    }
    lp.tally.link = lp.figures();
    (end, lp.tally)
}

/// A session's state between the events of its loop.
struct Loop<S, H> {
    setup: Setup,
    p: Player,
    sink: S,
    hooks: H,
    snaps: watch::Receiver<Arc<Snapshot>>,
    pacer: LinkPacer,
    grid: FrameGrid,
    tally: Tally,
    /// Frame bytes, reused.
    out: Vec<u8>,
    /// Whether the screen may have changed since the last frame.
    want: bool,
    /// When to look again at a wanted frame (the frame-rate cap, or the link still carrying the
    /// last frame).
    again: Option<tokio::time::Instant>,
    last_tick: Option<tokio::time::Instant>,
    /// Whether the world's (unique) name for us has been seen; spectators have none.
    named: bool,
    /// (map index, name) whose own best was last asked for.
    asked: Option<(usize, String)>,
}

impl<S: FrameSink, H: Hooks> Loop<S, H> {
    fn new(setup: Setup, size: (u32, u32), sink: S, hooks: H) -> Self {
        let grid = FrameGrid::new(setup.rules.fps);
        let p = Player::new(&setup, size, sink.measures(), now());
        Self {
            pacer: LinkPacer::new(grid.period(), p.colour().level),
            p,
            sink,
            hooks,
            snaps: setup.rules.world.snapshots(),
            grid,
            tally: Tally::default(),
            out: Vec::new(),
            want: true,
            again: None,
            last_tick: None,
            named: setup.client.spectator,
            asked: None,
            setup,
        }
    }

    /// Input arrived (or the client closed its side: `None`).
    async fn on_input(&mut self, input: Option<Input>) -> Result<(), End> {
        let input = input.ok_or(End::ClientGone)?;
        let snap = Arc::clone(&self.snaps.borrow());
        if let Some(end) = self.p.take(input, &snap, now()) {
            return Err(end);
        }
        // At once, not at the next frame tick: the world applies it on its next tick.
        self.tell_world().await;
        self.want = true;
        Ok(())
    }

    /// The player's input, when it changed, to the world.
    async fn tell_world(&mut self) {
        if !self.setup.client.spectator {
            for msg in self.p.world_messages(now()) {
                self.setup.rules.world.send(msg).await;
            }
        }
    }

    /// A note from the server for the rest of the session.
    fn announce(&mut self, note: Option<String>) {
        if let Some(note) = note {
            let now = now();
            self.p.note_until(note, now + STANDING_NOTE);
            self.want = true;
        }
    }

    /// A frame tick: what time changes by itself (a lone Esc, idleness, a held key's inferred
    /// end, a stalled link, a note running out).
    async fn on_tick(&mut self, at: tokio::time::Instant) -> Result<(), End> {
        let period = self.grid.period();
        if let Some(prev) = self.last_tick {
            let gap = at.duration_since(prev).as_secs_f64() / period.as_secs_f64();
            let skipped = (gap.round() as u64).saturating_sub(1);
            self.tally.dropped += skipped;
            self.hooks.ticks_skipped(skipped);
        }
        self.last_tick = Some(at);
        let now = now();
        if self.p.escape_due(now, ESC_WAIT) {
            let snap = Arc::clone(&self.snaps.borrow());
            if let Some(end) = self.p.flush_escape(&snap, now) {
                return Err(end);
            }
            self.want = true;
        }
        let rules = &self.setup.rules;
        if !self.setup.client.spectator && self.p.idle_for(now) >= rules.idle_timeout {
            return Err(End::Idle);
        }
        // A held key's end is inferred from time, so the world hears it from here too.
        self.tell_world().await;
        // A frame the client has not taken for the stall timeout: its link is dead or it
        // stopped reading.
        if self
            .pacer
            .waiting(now)
            .is_some_and(|w| w >= self.setup.rules.stall_timeout)
        {
            let sample = self.sink.sample();
            let answered = self.sink.answered(period, now);
            if !self
                .pacer
                .clear(self.sink.written(), sample.as_ref(), answered, now)
            {
                return Err(End::Stalled);
            }
        }
        if self.want {
            // Wanted at a tick and still not drawn: the link held it back.
            self.tally.dropped += u64::from(self.again.is_some());
        }
        // The world's snapshots bring its changes; the tick brings only what time changes by
        // itself: a note over the status line running out.
        self.want |= self.p.note_changed(now);
        Ok(())
    }

    /// Draws and sends a frame if the cap, the link and the screen allow; otherwise notes when
    /// to look again.
    async fn frame(&mut self) -> Result<(), End> {
        let now = now();
        if let Some(at) = self.grid.wait_until(now) {
            self.again = Some(tokio::time::Instant::from_std(at));
            return Ok(());
        }
        let snap = Arc::clone(&self.snaps.borrow_and_update());
        self.follow(&snap);
        for note in self.p.notes(&snap) {
            self.sink.note(note).await.map_err(|_| End::ClientGone)?;
        }
        if self.p.unchanged(&snap, now) {
            self.want = false;
            return Ok(());
        }
        if !self.link_clear(now) {
            self.again = Some(tokio::time::Instant::from_std(now) + LINK_RECHECK);
            return Ok(());
        }
        self.again = None;
        self.want = false;
        self.step_level(now);
        self.p.show_link(self.figures(), now);
        self.p.compose(&snap, now, &mut self.out);
        if self.out.is_empty() {
            return Ok(());
        }
        let (render, encode) = self.p.frame_times();
        self.hooks.frame_timed(render, encode);
        let n = self.out.len();
        let bytes = std::mem::take(&mut self.out);
        let wire_before = self.sink.written();
        let colour = self.p.colour();
        let held = colour.reason == ColourReason::Link && self.pacer.below_ceiling(colour.level);
        self.sink.level_held_down(held);
        let stall = self.setup.rules.stall_timeout;
        match tokio::time::timeout(stall, self.sink.send(bytes)).await {
            Err(_) => Err(End::Stalled),
            Ok(Err(_)) => Err(End::ClientGone),
            Ok(Ok(())) => {
                self.pacer
                    .sent(wire_before, n as u64, self.p.colour().level, now);
                self.grid.drawn(now);
                self.tally.frames += 1;
                self.tally.bytes += n as u64;
                self.hooks.frame_sent(n);
                Ok(())
            }
        }
    }

    /// What the frame from `snap` shows besides the world: the name the world gave us, our best
    /// asked for on each map, the leaderboard while it shows.
    fn follow(&mut self, snap: &Snapshot) {
        let client = &self.setup.client;
        let me = snap.player(client.id);
        if let (false, Some(me)) = (self.named, me) {
            self.named = true;
            if me.name != client.name {
                self.hooks.renamed(&client.name, &me.name);
            }
        }
        if let Some(me) = me {
            let here = (snap.map, me.name.clone());
            if self.asked.as_ref() != Some(&here) {
                self.hooks.best_wanted(here.0, &here.1);
                self.asked = Some(here);
            }
        }
        // Only while shown: a frame of play builds no board.
        let board = if self.p.wants_board(snap) {
            self.hooks.board(snap, client.id)
        } else {
            None
        };
        self.p.set_leaders(board);
    }

    /// Whether the link lets the next frame go now (the last one has nearly arrived).
    fn link_clear(&mut self, now: Instant) -> bool {
        let wire = self.sink.written();
        // Nothing in flight, or not yet written: no need to ask the transport.
        let sample = if self.pacer.needs_sample(wire) {
            self.sink.sample()
        } else {
            None
        };
        let answered = self.sink.answered(self.grid.period(), now);
        if !self.pacer.clear(wire, sample.as_ref(), answered, now) {
            return false;
        }
        if let Some(d) = self.pacer.take_waited() {
            self.hooks.link_waited(d);
        }
        true
    }

    /// Steps the colour level as the link asks, unless the player chose it.
    fn step_level(&mut self, now: Instant) {
        if self.p.colour().reason == ColourReason::Key {
            return;
        }
        let shrink = self.sink.could_shrink();
        if let Some(step) = self.pacer.step(self.p.colour().level, now, shrink) {
            let (level, down) = match step {
                Step::Down(l) => (l, true),
                Step::Up(l) => (l, false),
                Step::Shrink => {
                    self.sink.shrink();
                    return;
                }
            };
            self.hooks.level_stepped(down);
            self.p.set_colour(ColourChoice {
                level,
                reason: ColourReason::Link,
            });
        }
    }

    /// The link's figures, with the round trip of the client's own answers where it gives them
    /// (behind a load balancer the kernel sees only the hop to the balancer).
    fn figures(&self) -> LinkFigures {
        let mut f = self.pacer.figures();
        if let Some(rtt) = self.sink.acked_rtt() {
            f.rtt = rtt;
        }
        f
    }
}

/// Sleeps until `at` (never called with `None`: the select arm is disabled then).
async fn sleep_until_some(at: Option<tokio::time::Instant>) {
    if let Some(at) = at {
        tokio::time::sleep_until(at).await;
    }
}
