//! Frames compressed only when the link needs it. A browser's frames are the encoder's bytes,
//! which raw DEFLATE shrinks about four times (measured at 80×24 to 240×68, truecolor and 256
//! colours), at a cost of a few hundred microseconds of one core a frame. So they are compressed
//! while the link holds frames back (the page's acknowledgements gate the next frame, and the
//! gate stays shut for much of a second), and sent as they are once the link has room: a probe
//! sends raw frames after a calm spell, when the best delivery rate the acknowledgements showed
//! lately carries them at the full frame rate, and goes back at the first sign of holding, each
//! failed probe waiting twice as long. Pacing, which sees the frames it sends, also ends a probe
//! ([`Policy::shrink`]) the moment raw frames would drop the colour level and compressed ones
//! would not: so trying raw frames costs one late frame, never a level. While the link holds the
//! colour level below the top, frames stay compressed (raw frames would only hold it lower, and
//! compressed ones let it climb back). A new page starts compressed, as nothing is known of its
//! link.
//!
//! On the wire a compressed frame is one binary message: the byte 0x00, then the raw DEFLATE
//! stream of the frame (an encoder frame never starts with 0x00).

use std::io::Write;
use std::time::{Duration, Instant};

use flate2::write::DeflateEncoder;
use flate2::Compression;

use super::options::Compress;

/// The first byte of a compressed frame's message.
pub const COMPRESSED: u8 = 0x00;
/// How much of the last second the gate may hold frames before raw frames are given up.
const HELD_TOO_LONG: Duration = Duration::from_millis(250);
/// How calm (held at most [`CALM_HELD`] a second) the link must stay before raw frames are tried.
const CALM_FOR: Duration = Duration::from_secs(2);
/// Holding that still counts as calm, per second.
const CALM_HELD: Duration = Duration::from_millis(50);
/// A compressed frame's share of its raw bytes until one was seen: the encoder's frames deflate
/// 3.8 to 4.4 times at level 1 (truecolor and 256 colours, 80×24 to 240×68, turning).
const RATIO_GUESS: f64 = 0.3;
/// The longest wait between two probes of raw frames.
const MAX_BACKOFF: Duration = Duration::from_secs(60);
/// How long the best delivery rate the acknowledgements showed is trusted.
const RATE_MEMORY: Duration = Duration::from_secs(3);

/// Whether frames go compressed, from how long the link held them.
#[derive(Debug, Clone)]
pub struct Policy {
    /// Always or never, when the operator chose (`--web-compress`).
    fixed: Option<bool>,
    compressing: bool,
    /// When the gate last started holding a frame, while it still does.
    held_since: Option<Instant>,
    /// Holding in the current second, and when that second began.
    window: (Instant, Duration),
    /// The last whole second's holding.
    last_second: Duration,
    /// Since when the link has been calm (compressed frames only).
    calm_since: Option<Instant>,
    /// How long to stay calm before the next probe of raw frames.
    backoff: Duration,
    /// When the current raw spell began (a probe, until it holds).
    raw_since: Option<Instant>,
    /// Whether the link holds the colour level down (then no raw frames).
    level_held: bool,
    /// Mean bytes of a frame before compression.
    raw_mean: f64,
    /// The best delivery rate the page's acknowledgements showed lately (bytes a second), and
    /// when: a raw frame stream that needs more is not tried.
    rate_peak: (f64, Instant),
    /// The time between frames at the session's frame rate.
    period: Duration,
    /// Mean share of its raw bytes a compressed frame kept.
    ratio: f64,
}

impl Policy {
    /// A policy for a new page: compressed until the link shows room (`Auto`), or as the
    /// operator chose.
    #[must_use]
    pub fn new(mode: Compress, now: Instant) -> Self {
        Self {
            fixed: match mode {
                Compress::Auto => None,
                Compress::Always => Some(true),
                Compress::Never => Some(false),
            },
            compressing: true,
            held_since: None,
            window: (now, Duration::ZERO),
            last_second: Duration::ZERO,
            calm_since: Some(now),
            backoff: CALM_FOR,
            raw_since: None,
            level_held: false,
            raw_mean: 0.0,
            rate_peak: (0.0, now),
            period: Duration::from_millis(33),
            ratio: RATIO_GUESS,
        }
    }

    /// A frame of `raw` bytes went as `wire` bytes.
    pub fn sent(&mut self, raw: usize, wire: usize) {
        // Status-line frames of a few dozen bytes deflate worse than any view does.
        if wire < raw && raw >= 1_000 {
            self.ratio = 0.75 * self.ratio + 0.25 * (wire as f64 / raw as f64);
        }
    }

    /// The share of their raw bytes frames would keep if compressed, while they go raw and the
    /// operator left the choice to the link.
    #[must_use]
    pub fn could_shrink(&self) -> Option<f64> {
        (self.fixed.is_none() && !self.compressing).then_some(self.ratio)
    }

    /// The link does not carry raw frames: compressed from the next, and the probe failed.
    pub fn shrink(&mut self, now: Instant) {
        if self.could_shrink().is_some() {
            self.back_to_compressed(Some(now));
        }
    }

    /// A frame of `raw` bytes (before compression) is about to go, frames going `period` apart;
    /// the page's acknowledgements lately showed `rate` bytes a second.
    pub fn frame(&mut self, raw: usize, (rate, period): (f64, Duration), now: Instant) {
        self.raw_mean = if self.raw_mean == 0.0 {
            raw as f64
        } else {
            0.75 * self.raw_mean + 0.25 * raw as f64
        };
        if rate >= self.rate_peak.0 || now.saturating_duration_since(self.rate_peak.1) > RATE_MEMORY
        {
            self.rate_peak = (rate, now);
        }
        self.period = period;
    }

    /// Whether raw frames at the full frame rate need no more than the link has shown it carries.
    fn raw_would_fit(&self) -> bool {
        self.raw_mean / self.period.as_secs_f64().max(1e-3) <= self.rate_peak.0
    }

    /// Whether the link holds the colour level down now: raw frames caused it if they were on,
    /// so a probe counts as failed; none are tried until the level is back at its top.
    pub fn level_held_down(&mut self, by_link: bool) {
        if by_link && !self.compressing {
            self.back_to_compressed(None);
        }
        self.level_held = by_link;
        if by_link {
            self.calm_since = None;
        }
    }

    /// The gate answered whether the next frame may go (`open`) at `now`.
    pub fn gate(&mut self, open: bool, now: Instant) {
        match (open, self.held_since) {
            (false, None) => self.held_since = Some(now),
            (true, Some(since)) => {
                self.held_since = None;
                self.add_held(now.saturating_duration_since(since), now);
            }
            _ => {}
        }
    }

    fn add_held(&mut self, d: Duration, now: Instant) {
        self.roll(now);
        self.window.1 += d;
    }

    /// Starts a new second of holding when the current one is over.
    fn roll(&mut self, now: Instant) {
        if now.saturating_duration_since(self.window.0) >= Duration::from_secs(1) {
            self.last_second = self.window.1;
            self.window = (now, Duration::ZERO);
        }
    }

    /// Whether the frame about to go at `now` is compressed.
    pub fn compress(&mut self, now: Instant) -> bool {
        if let Some(fixed) = self.fixed {
            return fixed;
        }
        self.roll(now);
        let open_hold = self
            .held_since
            .map_or(Duration::ZERO, |t| now.saturating_duration_since(t));
        let held = self.last_second.max(self.window.1 + open_hold);
        if self.compressing {
            if held > CALM_HELD || self.level_held {
                self.calm_since = None;
                return true;
            }
            let calm = *self.calm_since.get_or_insert(now);
            if now.saturating_duration_since(calm) >= self.backoff && self.raw_would_fit() {
                self.compressing = false;
                self.raw_since = Some(now);
                self.window = (now, Duration::ZERO);
                self.last_second = Duration::ZERO;
            }
        } else if self.window.1 + open_hold > HELD_TOO_LONG {
            self.back_to_compressed(Some(now));
        }
        self.compressing
    }

    /// Raw frames are more than this link carries: back to compressed, and a failed probe (raw
    /// for under a minute) waits twice as long before the next.
    fn back_to_compressed(&mut self, now: Option<Instant>) {
        let lasted = match (self.raw_since, now) {
            (Some(t), Some(now)) => now.saturating_duration_since(t),
            (Some(_), None) => Duration::ZERO,
            (None, _) => MAX_BACKOFF,
        };
        self.backoff = if lasted < MAX_BACKOFF {
            (self.backoff * 2).min(MAX_BACKOFF)
        } else {
            CALM_FOR
        };
        self.compressing = true;
        self.calm_since = None;
        self.raw_since = None;
        // The raw frames' holding says nothing of compressed ones.
        if let Some(now) = now {
            self.window = (now, Duration::ZERO);
        }
        self.last_second = Duration::ZERO;
        self.held_since = None;
    }
}

/// `frame` as a compressed message: [`COMPRESSED`], then its raw DEFLATE at the fastest level.
#[must_use]
pub fn compressed(frame: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(frame.len() / 3 + 16);
    out.push(COMPRESSED);
    let mut enc = DeflateEncoder::new(out, Compression::fast());
    // Writing into a Vec cannot fail.
    let _ = enc.write_all(frame);
    enc.finish().unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use std::io::Read;

    use super::*;

    fn ms(t0: Instant, n: u64) -> Instant {
        t0 + Duration::from_millis(n)
    }

    /// 30 kB frames on a link that has shown `mbps` megabytes a second.
    fn on_link(p: &mut Policy, mbps: f64, at: Instant) {
        p.frame(30_000, (mbps * 1e6, Duration::from_millis(33)), at);
    }

    #[test]
    fn a_compressed_frame_inflates_to_the_frame() {
        let frame = b"\x1b[38;2;10;20;30m\xe2\x96\x80".repeat(500);
        let msg = compressed(&frame);
        assert_eq!(msg[0], COMPRESSED);
        assert!(
            msg.len() * 4 < frame.len(),
            "{} of {}",
            msg.len(),
            frame.len()
        );
        let mut back = Vec::new();
        flate2::read::DeflateDecoder::new(&msg[1..])
            .read_to_end(&mut back)
            .unwrap();
        assert_eq!(back, frame);
    }

    #[test]
    fn a_calm_link_goes_raw_and_a_holding_one_goes_back_with_backoff() {
        let t0 = Instant::now();
        let mut p = Policy::new(Compress::Auto, t0);
        assert!(p.compress(t0), "a new page starts compressed");
        // Two calm seconds of frames (the gate always open): raw from then on.
        let mut t = 0;
        while p.compress(ms(t0, t)) {
            on_link(&mut p, 10.0, ms(t0, t));
            p.gate(true, ms(t0, t));
            t += 33;
            assert!(t < 3000, "never went raw");
        }
        assert!((2000..2100).contains(&t), "raw after {t} ms");
        // The link holds raw frames for most of a frame period each: compressed again.
        let raw_at = t;
        loop {
            p.gate(false, ms(t0, t));
            t += 30;
            p.gate(true, ms(t0, t));
            t += 3;
            if p.compress(ms(t0, t)) {
                break;
            }
            assert!(t < raw_at + 2000, "held raw frames stayed raw");
        }
        assert!(
            t - raw_at <= 400,
            "back to compressed {} ms later",
            t - raw_at
        );
        // The next probe waits twice as long (4 s of calm).
        let back_at = t;
        while p.compress(ms(t0, t)) {
            on_link(&mut p, 10.0, ms(t0, t));
            p.gate(true, ms(t0, t));
            t += 33;
        }
        let waited = t - back_at;
        assert!(
            (4000..4200).contains(&waited),
            "probed again after {waited} ms"
        );
    }

    #[test]
    fn a_level_the_link_holds_down_keeps_frames_compressed() {
        let t0 = Instant::now();
        let mut p = Policy::new(Compress::Auto, t0);
        let mut t = 0;
        while p.compress(ms(t0, t)) {
            on_link(&mut p, 10.0, ms(t0, t));
            p.gate(true, ms(t0, t));
            t += 33;
        }
        // Raw, then the level steps down for the link: compressed at once, and no probe while
        // the level is held down, however calm the link.
        p.level_held_down(true);
        for _ in 0..300 {
            t += 33;
            p.gate(true, ms(t0, t));
            assert!(
                p.compress(ms(t0, t)),
                "raw at {t} ms with the level held down"
            );
        }
        // Back at the top: raw again after a calm spell twice as long as the first.
        p.level_held_down(false);
        let top = t;
        while p.compress(ms(t0, t)) {
            on_link(&mut p, 10.0, ms(t0, t));
            p.gate(true, ms(t0, t));
            t += 33;
        }
        assert!(
            (4000..4200).contains(&(t - top)),
            "raw {} ms after the top",
            t - top
        );
    }

    #[test]
    fn raw_frames_are_not_tried_where_the_link_has_not_shown_their_rate() {
        let t0 = Instant::now();
        let mut p = Policy::new(Compress::Auto, t0);
        // 30 kB frames at 30 a second are 0.9 MB/s; this link has shown 0.5 MB/s.
        for i in 0..300 {
            let t = i * 33;
            on_link(&mut p, 0.5, ms(t0, t));
            p.gate(true, ms(t0, t));
            assert!(p.compress(ms(t0, t)), "raw at {t} ms");
        }
    }

    #[test]
    fn raw_frames_offer_to_shrink_by_what_compression_gave_and_a_shrink_is_a_failed_probe() {
        let t0 = Instant::now();
        let mut p = Policy::new(Compress::Auto, t0);
        assert_eq!(p.could_shrink(), None, "already compressed");
        let mut t = 0;
        while p.compress(ms(t0, t)) {
            on_link(&mut p, 10.0, ms(t0, t));
            // Frames that deflate to a fifth; status lines of a few bytes say nothing.
            p.sent(30_000, 6_000);
            p.sent(40, 30);
            p.gate(true, ms(t0, t));
            t += 33;
        }
        let r = p.could_shrink().expect("raw frames can shrink");
        assert!((0.2..0.22).contains(&r), "{r}");
        // Pacing found the raw frames too large: compressed from the next, and the next probe
        // waits twice as long (4 s of calm).
        p.shrink(ms(t0, t));
        assert_eq!(p.could_shrink(), None);
        let back_at = t;
        while p.compress(ms(t0, t)) {
            on_link(&mut p, 10.0, ms(t0, t));
            p.gate(true, ms(t0, t));
            t += 33;
        }
        assert!((4000..4200).contains(&(t - back_at)), "{} ms", t - back_at);
        // An operator's choice is never undone.
        for mode in [Compress::Always, Compress::Never] {
            let mut p = Policy::new(mode, t0);
            p.compress(t0);
            assert_eq!(p.could_shrink(), None, "{mode:?}");
        }
    }

    #[test]
    fn a_link_that_keeps_holding_stays_compressed() {
        let t0 = Instant::now();
        let mut p = Policy::new(Compress::Auto, t0);
        for i in 0..300 {
            let t = i * 33;
            p.gate(false, ms(t0, t));
            p.gate(true, ms(t0, t + 20));
            assert!(p.compress(ms(t0, t + 20)), "raw at {t} ms");
        }
    }
}
