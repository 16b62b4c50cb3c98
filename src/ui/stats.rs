//! Frame timing: the live figures in the status line and an optional summary at exit.

use std::time::{Duration, Instant};

/// How often the fps figure is recomputed.
const FPS_WINDOW: Duration = Duration::from_millis(500);

/// Most samples kept for the exit summary (about 4.6 hours at 60 fps).
const MAX_SAMPLES: usize = 1 << 20;

/// Running frame statistics; the clock is passed in.
#[derive(Debug, Clone, Default)]
pub struct FrameStats {
    /// Frames per second over the last window.
    pub fps: f64,
    /// Smoothed time to cast and rasterize the 3D view, in ms, as of the last window (the
    /// figures shown change with the fps, not every frame: a still screen stays still).
    pub render_ms: f64,
    /// Smoothed time to build, diff and write the terminal frame, in ms, as of the last window.
    pub draw_ms: f64,
    /// Smoothed bytes sent to the terminal per frame, as of the last window.
    pub bytes_per_frame: f64,
    /// Output rate over the last window, in kbit/s.
    pub kbit_s: f64,
    /// The colour level frames are sent at and why (shown in the status line).
    pub level: Option<crate::encode::ColourChoice>,
    /// The view's block characters (shown in the status line; the U key cycles them).
    pub glyphs: crate::render::glyphs::Glyphs,
    /// The smoothed figures, every frame; shown as of the last window.
    smoothed: Smoothed,
    window_bytes: u64,
    window_start: Option<Instant>,
    window_frames: u32,
    first: Option<Instant>,
    last: Option<Instant>,
    samples: Vec<(f32, f32)>,
}

/// Render and draw ms and bytes per frame, smoothed over recent frames.
#[derive(Debug, Clone, Copy, Default)]
struct Smoothed {
    render_ms: f64,
    draw_ms: f64,
    bytes_per_frame: f64,
}

/// `old` moved a tenth of the way to `new` (`new` itself when there is nothing yet).
fn smooth(old: f64, new: f64) -> f64 {
    if old == 0.0 {
        new
    } else {
        old * 0.9 + new * 0.1
    }
}

impl FrameStats {
    /// Records the bytes one frame sent (before [`FrameStats::record`] for that frame).
    pub fn record_bytes(&mut self, bytes: usize) {
        self.smoothed.bytes_per_frame = smooth(self.smoothed.bytes_per_frame, bytes as f64);
        if self.bytes_per_frame == 0.0 {
            // The first figure shows at once; later ones with the window.
            self.bytes_per_frame = self.smoothed.bytes_per_frame;
        }
        self.window_bytes += bytes as u64;
    }

    /// Records one finished frame.
    pub fn record(&mut self, now: Instant, render: Duration, draw: Duration) {
        let (r, d) = (render.as_secs_f64() * 1e3, draw.as_secs_f64() * 1e3);
        let first = self.window_start.is_none();
        self.smoothed.render_ms = smooth(self.smoothed.render_ms, r);
        self.smoothed.draw_ms = smooth(self.smoothed.draw_ms, d);
        if first {
            self.show_smoothed();
        }
        let start = *self.window_start.get_or_insert(now);
        self.window_frames += 1;
        let elapsed = now.duration_since(start);
        if elapsed >= FPS_WINDOW {
            self.fps = f64::from(self.window_frames) / elapsed.as_secs_f64();
            self.kbit_s = self.window_bytes as f64 * 8.0 / 1000.0 / elapsed.as_secs_f64();
            self.show_smoothed();
            self.window_start = Some(now);
            self.window_frames = 0;
            self.window_bytes = 0;
        }
        self.first.get_or_insert(now);
        self.last = Some(now);
        if self.samples.len() < MAX_SAMPLES {
            self.samples.push((r as f32, d as f32));
        }
    }

    /// Shows the smoothed figures (at the first frame and each window's end).
    fn show_smoothed(&mut self) {
        self.render_ms = self.smoothed.render_ms;
        self.draw_ms = self.smoothed.draw_ms;
        if self.smoothed.bytes_per_frame > 0.0 {
            self.bytes_per_frame = self.smoothed.bytes_per_frame;
        }
    }

    /// A one-line summary: frames, mean fps, render and draw ms (mean, p50, p95, max).
    #[must_use]
    pub fn summary(&self) -> String {
        let n = self.samples.len();
        let secs = match (self.first, self.last) {
            (Some(a), Some(b)) => b.duration_since(a).as_secs_f64(),
            _ => 0.0,
        };
        let fps = if secs > 0.0 {
            (n.saturating_sub(1)) as f64 / secs
        } else {
            0.0
        };
        let describe = |pick: fn(&(f32, f32)) -> f32| {
            let mut v: Vec<f32> = self.samples.iter().map(pick).collect();
            v.sort_by(f32::total_cmp);
            if v.is_empty() {
                return "n/a".to_owned();
            }
            let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
            let mean = v.iter().map(|&x| f64::from(x)).sum::<f64>() / v.len() as f64;
            format!(
                "mean {mean:.2} p50 {:.2} p95 {:.2} max {:.2}",
                at(0.5),
                at(0.95),
                at(1.0)
            )
        };
        format!(
            "{n} frames in {secs:.1} s ({fps:.1} fps); render ms: {}; draw ms: {}",
            describe(|s| s.0),
            describe(|s| s.1)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fps_is_counted_over_a_window_and_times_are_smoothed() {
        let t0 = Instant::now();
        let mut s = FrameStats::default();
        for i in 0..=60 {
            let now = t0 + Duration::from_micros(i * 16_667);
            s.record(now, Duration::from_millis(2), Duration::from_millis(4));
        }
        assert!((s.fps - 60.0).abs() < 1.0, "{}", s.fps);
        assert!((s.render_ms - 2.0).abs() < 1e-9 && (s.draw_ms - 4.0).abs() < 1e-9);
        let line = s.summary();
        assert!(line.starts_with("61 frames in 1.0 s (60.0 fps)"), "{line}");
        assert!(line.contains("render ms: mean 2.00 p50 2.00"), "{line}");
    }

    #[test]
    fn the_shown_figures_change_only_when_the_fps_window_ends() {
        let t0 = Instant::now();
        let mut s = FrameStats::default();
        s.record_bytes(1000);
        s.record(t0, Duration::from_millis(2), Duration::from_millis(4));
        let first = (s.render_ms, s.draw_ms, s.bytes_per_frame);
        assert_eq!(first, (2.0, 4.0, 1000.0));
        // Slower, bigger frames within the window: the figures shown hold.
        let frame = Duration::from_millis(33);
        for i in 1..10 {
            s.record_bytes(5000);
            s.record(
                t0 + frame * i,
                Duration::from_millis(8),
                Duration::from_millis(9),
            );
            assert_eq!(
                (s.render_ms, s.draw_ms, s.bytes_per_frame),
                first,
                "frame {i}"
            );
        }
        // The window ends: they move to the smoothed figures at once.
        s.record_bytes(5000);
        s.record(
            t0 + frame * 16,
            Duration::from_millis(8),
            Duration::from_millis(9),
        );
        assert!(s.render_ms > 2.0 && s.draw_ms > 4.0 && s.bytes_per_frame > 1000.0);
        assert!(s.fps > 0.0);
    }
}
