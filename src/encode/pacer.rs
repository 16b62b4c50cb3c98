//! Fitting the frame rate to a bandwidth cap (`--max-bandwidth 2mbit`): pure arithmetic, the caller
//! owns the clock.

use std::time::Duration;

use super::level::ColorLevel;

/// Parses a rate such as `2mbit`, `500kbit`, `1MB`, `64kB/s`, `3.5Mbps` into bits per second.
///
/// Decimal prefixes (k = 1000); `bit`, `bps` or a lowercase `b` count bits, an uppercase `B` or
/// `byte` counts bytes; a bare number is bits per second.
///
/// # Errors
/// A message naming the input when it is not a positive rate.
pub fn parse_rate(s: &str) -> Result<u64, String> {
    let bad = || format!("'{s}' is not a rate (examples: 2mbit, 500kbit, 1MB)");
    let t = s.trim();
    let t = t.strip_suffix("/s").unwrap_or(t);
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let value: f64 = num.parse().map_err(|_| bad())?;
    let unit = unit.trim();
    let (prefix, rest) = match unit.chars().next() {
        Some(c @ ('k' | 'K' | 'm' | 'M' | 'g' | 'G')) => (Some(c), &unit[1..]),
        _ => (None, unit),
    };
    let scale = match prefix.map(|c| c.to_ascii_lowercase()) {
        None => 1.0,
        Some('k') => 1e3,
        Some('m') => 1e6,
        _ => 1e9,
    };
    let per_unit = match rest {
        "" if prefix.is_none() => 1.0,
        "bit" | "bits" | "bps" | "b" => 1.0,
        "B" | "byte" | "bytes" | "Bps" => 8.0,
        _ => return Err(bad()),
    };
    let bits = value * scale * per_unit;
    if bits.is_finite() && bits >= 1.0 {
        Ok(bits.round() as u64)
    } else {
        Err(bad())
    }
}

/// Tracks bytes per frame and says how long to wait between frames to stay under a bit rate.
#[derive(Debug, Clone)]
pub struct Pacer {
    bits_per_sec: u64,
    max_fps: f64,
    /// Exponential moving average of bytes per frame (None before the first frame).
    mean: Option<f64>,
}

/// Weight of the newest frame in the moving average (about the last ten frames count).
const SMOOTHING: f64 = 0.1;

impl Pacer {
    /// A pacer for a link of `bits_per_sec`, never faster than `max_fps`.
    #[must_use]
    pub fn new(bits_per_sec: u64, max_fps: f64) -> Self {
        Self {
            bits_per_sec: bits_per_sec.max(1),
            max_fps: if max_fps > 0.0 { max_fps } else { 60.0 },
            mean: None,
        }
    }

    /// Records the size of a frame just sent.
    pub fn record(&mut self, bytes: usize) {
        let b = bytes as f64;
        self.mean = Some(match self.mean {
            None => b,
            Some(m) => m + SMOOTHING * (b - m),
        });
    }

    /// The smoothed bytes per frame (0 before any frame).
    #[must_use]
    pub fn bytes_per_frame(&self) -> f64 {
        self.mean.unwrap_or(0.0)
    }

    /// The wait between frame starts that keeps the mean frame under the cap (≥ 1 / max fps).
    #[must_use]
    pub fn frame_interval(&self) -> Duration {
        let floor = 1.0 / self.max_fps;
        let need = self.bytes_per_frame() * 8.0 / self.bits_per_sec as f64;
        Duration::from_secs_f64(floor.max(need))
    }

    /// The frame rate the cap allows now.
    #[must_use]
    pub fn fps(&self) -> f64 {
        1.0 / self.frame_interval().as_secs_f64()
    }

    /// Whether the cap allows at least `min_fps`; when not, the caller may drop a colour level.
    #[must_use]
    pub fn sustains(&self, min_fps: f64) -> bool {
        self.fps() + 1e-9 >= min_fps
    }

    /// The colour level to use next: `current`, or one rung lower when the cap cannot sustain
    /// `min_fps` at the measured frame size (call after a few frames; reset the pacer after a switch,
    /// since frame sizes change with the level).
    #[must_use]
    pub fn level_for(&self, current: ColorLevel, min_fps: f64) -> ColorLevel {
        if self.mean.is_some() && !self.sustains(min_fps) {
            current.lower().unwrap_or(current)
        } else {
            current
        }
    }

    /// The link use at the current frame rate, in kbit/s (for the status line).
    #[must_use]
    pub fn kbit_per_sec(&self) -> f64 {
        self.bytes_per_frame() * 8.0 * self.fps() / 1000.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_parse_in_bits_per_second() {
        assert_eq!(parse_rate("2mbit"), Ok(2_000_000));
        assert_eq!(parse_rate("500kbit"), Ok(500_000));
        assert_eq!(parse_rate("1MB"), Ok(8_000_000));
        assert_eq!(parse_rate("64kB/s"), Ok(512_000));
        assert_eq!(parse_rate("3.5Mbps"), Ok(3_500_000));
        assert_eq!(parse_rate("1gbit"), Ok(1_000_000_000));
        assert_eq!(parse_rate("9600"), Ok(9600));
        assert_eq!(parse_rate(" 10 kbit "), Ok(10_000));
        for bad in ["", "fast", "2 parsecs", "-1mbit", "0", "1.2.3kbit", "k"] {
            assert!(parse_rate(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn interval_fits_the_measured_frames_into_the_cap() {
        let mut p = Pacer::new(2_000_000, 60.0);
        assert_eq!(p.frame_interval(), Duration::from_secs_f64(1.0 / 60.0));
        p.record(25_000); // 200 kbit per frame at 2 Mbit/s → 10 fps
        assert!((p.fps() - 10.0).abs() < 1e-6);
        assert!(p.sustains(10.0) && !p.sustains(15.0));
        assert!((p.kbit_per_sec() - 2000.0).abs() < 1e-3);
        p.record(1_000); // small frames pull the mean down gradually
        assert!(p.fps() > 10.0 && p.fps() < 12.0);
    }

    #[test]
    fn a_cap_too_small_for_the_minimum_rate_steps_the_level_down() {
        let mut p = Pacer::new(2_000_000, 60.0);
        assert_eq!(
            p.level_for(ColorLevel::TrueColor, 15.0),
            ColorLevel::TrueColor
        );
        p.record(400_000); // 3.2 Mbit a frame: 0.6 fps on 2 Mbit/s
        assert_eq!(
            p.level_for(ColorLevel::TrueColor, 15.0),
            ColorLevel::Ansi256
        );
        assert_eq!(p.level_for(ColorLevel::Mono, 15.0), ColorLevel::Mono);
        let mut q = Pacer::new(2_000_000, 60.0);
        q.record(8_000); // 64 kbit: 31 fps
        assert_eq!(q.level_for(ColorLevel::Ansi256, 15.0), ColorLevel::Ansi256);
    }

    #[test]
    fn tiny_frames_are_capped_by_the_frame_rate() {
        let mut p = Pacer::new(100_000_000, 30.0);
        p.record(100);
        assert!((p.fps() - 30.0).abs() < 1e-6);
    }

    proptest::proptest! {
        #[test]
        fn interval_never_exceeds_the_cap(bytes in 1usize..2_000_000, rate in 1_000u64..100_000_000) {
            let mut p = Pacer::new(rate, 60.0);
            p.record(bytes);
            let bits_per_sec = p.bytes_per_frame() * 8.0 / p.frame_interval().as_secs_f64();
            proptest::prop_assert!(bits_per_sec <= rate as f64 * (1.0 + 1e-6));
        }
    }
}
