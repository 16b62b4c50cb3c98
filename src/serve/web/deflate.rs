//! Frames compressed only when the link needs it. A browser's frames are the encoder's bytes,
//! which raw DEFLATE shrinks about four times (measured at 80×24 to 240×68, truecolor and 256
//! colours), at a cost of a few hundred microseconds of one core a frame. So they are compressed
//! while the link holds frames back (the page's acknowledgements gate the next frame, and the
//! gate stays shut for much of a second), and sent as they are once the link has room: a probe
//! sends raw frames after a calm spell and goes back at the first sign of holding, each failed
//! probe waiting twice as long. A new page starts compressed, as nothing is known of its link.
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
/// The longest wait between two probes of raw frames.
const MAX_BACKOFF: Duration = Duration::from_secs(60);

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
            if held > CALM_HELD {
                self.calm_since = None;
            }
            let calm = *self.calm_since.get_or_insert(now);
            if now.saturating_duration_since(calm) >= self.backoff {
                self.compressing = false;
                self.raw_since = Some(now);
                self.window = (now, Duration::ZERO);
                self.last_second = Duration::ZERO;
            }
        } else if self.window.1 + open_hold > HELD_TOO_LONG {
            // Raw frames are more than this link carries: back to compressed, and a failed
            // probe (raw for under a minute) waits twice as long before the next.
            let lasted = self
                .raw_since
                .map_or(MAX_BACKOFF, |t| now.saturating_duration_since(t));
            self.backoff = if lasted < MAX_BACKOFF {
                (self.backoff * 2).min(MAX_BACKOFF)
            } else {
                CALM_FOR
            };
            self.compressing = true;
            self.calm_since = None;
            self.raw_since = None;
            // The raw frames' holding says nothing of compressed ones.
            self.window = (now, Duration::ZERO);
            self.last_second = Duration::ZERO;
            self.held_since = None;
        }
        self.compressing
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
