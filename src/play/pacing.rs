//! When a play session may send its next frame, and which colour level its link carries: pure
//! arithmetic over [`LinkSample`]s and frame sizes, the caller owns the clock.
//!
//! A frame goes only once the last one has nearly arrived (bytes not yet acknowledged below about
//! what the path itself holds), as mosh sends a new state only as the last is acknowledged. So
//! nothing queues behind the player's keys: on a slow link they get fewer frames, each drawn from
//! the newest state. When the link carries fewer than [`MIN_FPS`] frames a second at the
//! session's colour level, the level steps down (truecolor → 256 → 16), and back up when the link
//! would carry the richer level with room to spare.
//!
//! Frame sizes are kept as the encoder's bytes, and the wire's share of them (a browser's
//! compression makes it about a quarter) is the last moving frame's: so a level seen once raw is
//! judged at the size compression gives it, and a transport that could shrink its frames is asked
//! to ([`Step::Shrink`]) before the level drops.

use std::time::{Duration, Instant};

use super::link::LinkSample;
use crate::encode::ColorLevel;

/// Frames per second a moving view should get; below it the level steps down.
pub const MIN_FPS: f64 = 15.0;
/// How much more than [`MIN_FPS`] the richer level must be predicted to carry before stepping up.
const UP_MARGIN: f64 = 1.5;
/// The least a session keeps in flight beyond what it waits on: about three full TCP segments,
/// so the next frame starts while the last one's tail is still on the way.
const MIN_ALLOWANCE: u64 = 4_096;
/// Frames the kernel found all but delivered at the first look, in a row, before the link is
/// asked only every [`ASK_EVERY`] frames.
const KEPT_UP_STREAK: u32 = 30;
/// How often a link that keeps up is asked.
const ASK_EVERY: u32 = 4;
/// Frames closer together than this many frame periods count as one moving stretch.
const STRETCH: f64 = 2.5;
/// Moving frames seen at a level before it may step down.
const SETTLE_FRAMES: u32 = 4;
/// The least time between a step and a step up.
const UP_HOLD: Duration = Duration::from_secs(5);
/// Large moving frames (about two seconds of movement) that must all find the link empty before
/// a richer level is tried without a measured speed that allows it.
const QUIET_FRAMES: u32 = 60;
/// A frame that took this long to arrive was held up by the link (checks come every few ms).
const HELD_UP: Duration = Duration::from_millis(15);
/// The longest wait before a step up, however often steps up failed.
const MAX_UP_HOLD: Duration = Duration::from_secs(60);
/// How long the link's measured speed is trusted once no frame is held up any more.
const GOODPUT_MEMORY: Duration = Duration::from_secs(5);
/// Held-up frames in one stretch before their speed may step the level down: one frame late
/// is a hiccup (a browser page busy for 80 ms once, measured on loopback), a slow link holds
/// up every frame.
const HELD_SAMPLES: u32 = 3;
/// The least encoder bytes of a frame whose wire size says how frames go on the wire (a status
/// line's few dozen bytes compress far worse than any view does).
const RATIO_FROM: u64 = 1_000;
/// How long a delivery-rate peak is trusted.
const RATE_MEMORY: Duration = Duration::from_secs(2);
/// Weight of the newest moving frame in a level's mean size.
const SMOOTHING: f64 = 0.25;
/// Size of a moving frame at the next level up, as a multiple of this level's, until one
/// was seen: each level's turning frames are about four times the next lower one's at every
/// size measured (truecolor 940, 256 colours 230, 16 colours 53 kB/s at 80×24; docs/serving.md,
/// "A slow link").
const SIZE_RATIO_UP: f64 = 4.0;

/// What a session's link pacing decided about the colour level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step {
    Down(ColorLevel),
    Up(ColorLevel),
    /// The same level in smaller frames: the transport said it could shrink them, and at that
    /// size the link carries the level.
    Shrink,
}

/// One frame handed to the SSH layer and not yet known to have arrived.
#[derive(Debug, Clone, Copy)]
struct InFlight {
    at: Instant,
    /// Whether it came in a moving stretch (its arrival time then measures the link).
    moving: bool,
    /// Socket bytes written before the frame was handed over.
    wire_before: u64,
}

/// The link figures an operator and the status line show.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LinkFigures {
    /// Smoothed round trip.
    pub rtt: Duration,
    /// Bytes per second the kernel saw the link deliver lately (`None` before a sample).
    pub rate: Option<f64>,
    /// Whether the link held frames up lately (it then limits what the player sees).
    pub limiting: bool,
    /// Bytes written and not yet acknowledged, at the last sample.
    pub queued: u64,
    /// The most that was ever queued.
    pub max_queued: u64,
    pub steps_down: u32,
    pub steps_up: u32,
}

/// One session's pacing state.
#[derive(Debug, Clone)]
pub struct LinkPacer {
    period: Duration,
    in_flight: Option<InFlight>,
    /// Mean encoder bytes of a moving frame, per level (truecolor, 256, 16, mono).
    sizes: [Option<f64>; 4],
    /// The encoder's bytes in the last frame.
    last_bytes: u64,
    /// Wire bytes per encoder byte of the last moving frame (below 1 while compressed).
    wire_ratio: f64,
    last_sent: Option<Instant>,
    /// Wire bytes written when the last frame was handed over.
    last_wire: u64,
    /// Moving frames since the level last changed.
    settled: u32,
    last_step: Option<Instant>,
    /// The highest delivery rate the kernel reported lately, and when.
    peak: Option<(f64, Instant)>,
    /// Mean bytes per second of moving frames the link held up, and when the last was seen.
    goodput: Option<(f64, Instant)>,
    /// Held-up frames measured since the speed was last forgotten.
    held_samples: u32,
    /// Whether a frame was wanted while the last one was still on its way.
    held_up: bool,
    /// The level of the last frame sent.
    last_level: Option<ColorLevel>,
    /// How long the last frame waited for the link, until taken.
    waited: Option<Duration>,
    /// Since when a frame has been wanted while the last one was still on its way.
    blocked_since: Option<Instant>,
    /// When the kernel was last sampled.
    seen: Option<Instant>,
    /// How long after a step the next step up may come; doubles each time a step up is
    /// followed by a step down (no flapping on a link at the edge).
    up_hold: Duration,
    /// Frames in a row the kernel found delivered at the first look.
    kept_up: u32,
    /// Frames let go without asking the kernel since it was last asked.
    unasked: u32,
    /// Since when every large moving frame found the link empty as it went.
    quiet_since: Option<Instant>,
    /// Large moving frames in that quiet.
    quiet_frames: u32,
    /// Bytes unacknowledged at the last sample.
    outstanding: u64,
    /// The last step up: to which level, and when.
    last_up: Option<(ColorLevel, Instant)>,
    /// The level the session started at: steps up never go above it.
    ceiling: ColorLevel,
    figures: LinkFigures,
}

fn index(level: ColorLevel) -> usize {
    match level {
        ColorLevel::TrueColor => 0,
        ColorLevel::Ansi256 => 1,
        ColorLevel::Ansi16 => 2,
        ColorLevel::Mono => 3,
    }
}

impl LinkPacer {
    /// A pacer for a session drawing at most one frame per `period`, starting at `level` (which
    /// is also the highest it steps back up to).
    #[must_use]
    pub fn new(period: Duration, level: ColorLevel) -> Self {
        Self {
            period,
            in_flight: None,
            sizes: [None; 4],
            last_bytes: 0,
            wire_ratio: 1.0,
            last_sent: None,
            last_wire: 0,
            settled: 0,
            last_step: None,
            peak: None,
            goodput: None,
            held_samples: 0,
            seen: None,
            waited: None,
            blocked_since: None,
            held_up: false,
            last_level: None,
            up_hold: UP_HOLD,
            last_up: None,
            kept_up: 0,
            unasked: 0,
            quiet_since: None,
            quiet_frames: 0,
            outstanding: 0,
            ceiling: level,
            figures: LinkFigures::default(),
        }
    }

    /// Whether the next frame may go now: the last one has been written to the socket (`wire`
    /// bytes so far), per the kernel's `sample` nearly all of it acknowledged, and the client
    /// itself has answered for enough of the frames before it (`answered`, from
    /// [`super::acks`]). Without a sample the kernel's part is skipped.
    pub fn clear(
        &mut self,
        wire: u64,
        sample: Option<&LinkSample>,
        answered: bool,
        now: Instant,
    ) -> bool {
        if let Some(s) = sample {
            self.observe(s, now);
        }
        let Some(f) = self.in_flight else {
            return true;
        };
        let done = wire > f.wire_before
            && answered
            && sample.is_none_or(|s| s.outstanding <= self.allowance(s));
        if sample.is_some() {
            self.unasked = 0;
        } else if done {
            self.unasked = self.unasked.saturating_add(1);
        }
        if !done {
            self.kept_up = 0;
            self.held_up = true;
            self.blocked_since.get_or_insert(now);
            self.quiet_since = None;
            self.quiet_frames = 0;
            return false;
        }
        self.in_flight = None;
        let blocked = self.blocked_since.take();
        if blocked.is_none() && sample.is_some() {
            self.kept_up = self.kept_up.saturating_add(1);
        }
        self.waited = Some(blocked.map_or(Duration::ZERO, |b| now.duration_since(b)));
        // Only a frame whose arrival was watched for (the session wanted the next one and
        // looked every few ms) says how fast the link is, and only if the link held it up.
        let took = now.duration_since(f.at);
        if let (Some(s), true, Some(_)) = (sample, f.moving, blocked) {
            if took >= HELD_UP && wire - f.wire_before > 2 * MIN_ALLOWANCE {
                let arrived = (wire - f.wire_before).saturating_sub(s.outstanding);
                let r = arrived as f64 / took.as_secs_f64();
                let fresh = self.held_rate().is_some();
                let mean = self.goodput.map_or(r, |(g, _)| g + SMOOTHING * (r - g));
                self.goodput = Some((mean, now));
                self.held_samples = if fresh { self.held_samples + 1 } else { 1 };
            }
        }
        true
    }

    /// Whether [`LinkPacer::clear`] needs the kernel's figures now: a frame is in flight and
    /// already written (`wire` bytes so far), so only its acknowledgement is in question.
    #[must_use]
    pub fn needs_sample(&self, wire: u64) -> bool {
        // A link that has kept up with every frame lately is asked every few frames only (the
        // question costs the server a netlink round trip); one frame's hold-up is enough to go
        // back to asking every time.
        let due = self.kept_up < KEPT_UP_STREAK || self.unasked + 1 >= ASK_EVERY;
        due && self.in_flight.is_some_and(|f| wire > f.wire_before)
    }

    /// What may stay unacknowledged when the next frame goes: what the path holds by itself
    /// (delivery rate × least round trip), at least [`MIN_ALLOWANCE`].
    fn allowance(&self, s: &LinkSample) -> u64 {
        // The link's measured speed where frames were held up (the kernel's peak on a shaped
        // link can be a burst through the shaper's bucket, far above what it sustains).
        let rate = self.measured().or(self.peak.map(|(r, _)| r)).unwrap_or(0.0);
        let bdp = rate * s.min_rtt.as_secs_f64();
        (bdp as u64).max(MIN_ALLOWANCE)
    }

    fn observe(&mut self, s: &LinkSample, now: Instant) {
        self.seen = Some(now);
        self.figures.rtt = s.rtt;
        self.figures.queued = s.outstanding;
        self.outstanding = s.outstanding;
        self.figures.max_queued = self.figures.max_queued.max(s.outstanding);
        if s.delivery_rate > 0 {
            // The kernel's samples while the session waits between frames are app-limited:
            // "at least this much". A peak is kept a while, then any newer sample replaces it.
            let r = s.delivery_rate as f64;
            if self
                .peak
                .is_none_or(|(p, at)| r >= p || now.duration_since(at) > RATE_MEMORY)
            {
                self.peak = Some((r, now));
            }
        }
        self.figures.rate = self.measured().or(self.peak.map(|(r, _)| r));
        self.figures.limiting = self.slow_rate().is_some();
    }

    /// Bytes per second the link delivered when it last held moving frames up, however long
    /// ago (`None` if it never did).
    fn measured(&self) -> Option<f64> {
        self.goodput.map(|(g, _)| g)
    }

    /// [`Self::held_rate`] once enough frames were held up to say the link, not one hiccup,
    /// is slow.
    fn slow_rate(&self) -> Option<f64> {
        self.held_rate()
            .filter(|_| self.held_samples >= HELD_SAMPLES)
    }

    /// Bytes per second measured from frames the link held up lately: the one figure that says
    /// the link is too slow (the kernel's own samples between frames are only lower bounds).
    fn held_rate(&self) -> Option<f64> {
        match (self.goodput, self.seen) {
            (Some((g, at)), Some(seen)) if seen.duration_since(at) <= GOODPUT_MEMORY => Some(g),
            _ => None,
        }
    }

    /// Records a frame of `bytes` from the encoder handed to the transport at `now`, `wire` bytes
    /// having gone on the wire before it, drawn at `level`.
    pub fn sent(&mut self, wire: u64, bytes: u64, level: ColorLevel, now: Instant) {
        // A frame that waited on the link, or came soon after the last, is part of a moving
        // stretch: the previous frame's size counts for its level, and its wire size (all
        // written by now) says how frames go on the wire.
        let moving = self.held_up
            || self.last_sent.is_some_and(|t| {
                now.duration_since(t).as_secs_f64() < self.period.as_secs_f64() * STRETCH
            });
        if let (true, Some(prev)) = (moving && wire > self.last_wire, self.last_level) {
            let prev_bytes = self.last_bytes.max(1) as f64;
            if self.last_bytes >= RATIO_FROM {
                self.wire_ratio = (wire - self.last_wire) as f64 / prev_bytes;
            }
            // A frame of at least half the level's usual moving size that found the link
            // empty when it went (the last one all acknowledged) keeps the link's quiet going;
            // one that found it busy ends it.
            let large = self.sizes[index(prev)].is_none_or(|m| prev_bytes >= m / 2.0);
            if large && prev == level {
                if self.outstanding > 0 {
                    self.quiet_since = None;
                    self.quiet_frames = 0;
                } else {
                    self.quiet_since.get_or_insert(now);
                    self.quiet_frames = self.quiet_frames.saturating_add(1);
                }
            }
            let slot = &mut self.sizes[index(prev)];
            *slot = Some(slot.map_or(prev_bytes, |m| m + SMOOTHING * (prev_bytes - m)));
            if prev == level {
                self.settled = self.settled.saturating_add(1);
            }
        }
        self.held_up = false;
        self.last_sent = Some(now);
        self.last_wire = wire;
        self.last_bytes = bytes;
        self.last_level = Some(level);
        self.in_flight = Some(InFlight {
            at: now,
            wire_before: wire,
            moving,
        });
    }

    /// How long the frame that may go now waited for the link (zero when it did not), once:
    /// the lag the link added, for the histogram.
    pub fn take_waited(&mut self) -> Option<Duration> {
        self.waited.take()
    }

    /// How long the frame in flight has been on its way.
    #[must_use]
    pub fn waiting(&self, now: Instant) -> Option<Duration> {
        self.in_flight.map(|f| now.duration_since(f.at))
    }

    /// Frames per second the link carries at `level`, by its delivery rate and that level's
    /// frame size (measured, or guessed from the level below) on the wire as frames go now.
    fn fps_at(&self, level: ColorLevel, rate: Option<f64>) -> Option<f64> {
        self.fps_shrunk(level, rate, self.wire_ratio)
    }

    /// [`Self::fps_at`] with frames `ratio` of the encoder's bytes on the wire.
    fn fps_shrunk(&self, level: ColorLevel, rate: Option<f64>, ratio: f64) -> Option<f64> {
        let size = match self.sizes[index(level)] {
            Some(s) => s,
            None => {
                let below = level.lower()?;
                self.sizes[index(below)]? * SIZE_RATIO_UP
            }
        };
        Some(rate? / (size * ratio).max(1.0))
    }

    /// The level step the link calls for now at `level`, if any (the caller applies it unless the
    /// player chose the level). `shrink` is the wire's share of the encoder's bytes the
    /// transport could bring its frames to, if it can make them smaller than they go now.
    pub fn step(&mut self, level: ColorLevel, now: Instant, shrink: Option<f64>) -> Option<Step> {
        let since_step = self
            .last_step
            .map_or(Duration::MAX, |t| now.duration_since(t));
        if self.settled >= SETTLE_FRAMES
            && matches!(level, ColorLevel::TrueColor | ColorLevel::Ansi256)
            && self
                .fps_at(level, self.slow_rate())
                .is_some_and(|f| f < MIN_FPS)
        {
            if shrink.is_some_and(|r| {
                r < self.wire_ratio
                    && self
                        .fps_shrunk(level, self.slow_rate(), r)
                        .is_some_and(|f| f >= MIN_FPS)
            }) {
                // Smaller frames keep the level: judge them afresh once a few went.
                self.settled = 0;
                self.wire_ratio = shrink.unwrap_or(self.wire_ratio);
                return Some(Step::Shrink);
            }
            let down = level.lower()?;
            if self.last_up.is_some_and(|(to, _)| to == level) {
                // The last step up did not hold: wait longer before the next one.
                self.up_hold = (self.up_hold * 2).min(MAX_UP_HOLD);
            }
            self.last_up = None;
            self.stepped(now);
            self.figures.steps_down += 1;
            return Some(Step::Down(down));
        }
        if level != self.ceiling && since_step >= self.up_hold {
            let up = up_from(level)?;
            // Up when the link's measured speed carries the richer level with room to spare,
            // or, to find out, when every moving frame of the whole hold found the link empty
            // (a failed try doubles the next hold).
            let roomy = self
                .fps_at(up, self.measured())
                .is_some_and(|f| f >= MIN_FPS * UP_MARGIN);
            let idle_link = self.quiet_frames >= QUIET_FRAMES
                && self
                    .quiet_since
                    .is_some_and(|t| now.duration_since(t) >= self.up_hold);
            if roomy || idle_link {
                self.stepped(now);
                self.last_up = Some((up, now));
                self.figures.steps_up += 1;
                return Some(Step::Up(up));
            }
        }
        None
    }

    fn stepped(&mut self, now: Instant) {
        self.last_step = Some(now);
        self.settled = 0;
        self.quiet_since = None;
        self.quiet_frames = 0;
    }

    /// Whether `level` is below the level this session started at (where the link's steps stop
    /// going up).
    #[must_use]
    pub fn below_ceiling(&self, level: ColorLevel) -> bool {
        level != self.ceiling
    }

    /// The figures for the status line, metrics and the log.
    #[must_use]
    pub fn figures(&self) -> LinkFigures {
        self.figures
    }
}

/// The next level up the ladder (the inverse of [`ColorLevel::lower`]).
fn up_from(level: ColorLevel) -> Option<ColorLevel> {
    match level {
        ColorLevel::TrueColor => None,
        ColorLevel::Ansi256 => Some(ColorLevel::TrueColor),
        ColorLevel::Ansi16 => Some(ColorLevel::Ansi256),
        ColorLevel::Mono => Some(ColorLevel::Ansi16),
    }
}

#[cfg(test)]
#[path = "pacing_tests.rs"]
mod tests;
