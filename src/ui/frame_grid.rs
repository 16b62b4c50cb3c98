//! The frame-rate cap both loops keep: at most one frame a period, on a grid a period apart. A
//! frame may come a quarter period before its slot, so frames that arrive with some jitter (the
//! world's snapshots, a busy machine's wake-ups) are each drawn as they come and the rate holds on
//! average; after a pause the grid starts again from the next frame.

use std::time::{Duration, Instant};

/// When frames may be drawn.
#[derive(Debug, Clone, Copy)]
pub struct FrameGrid {
    period: Duration,
    /// The next frame's slot, once a frame was drawn.
    next: Option<Instant>,
}

impl FrameGrid {
    /// A grid of `fps` frames a second (clamped to 1..=240).
    #[must_use]
    pub fn new(fps: u32) -> Self {
        Self::every(Duration::from_secs_f64(1.0 / f64::from(fps.clamp(1, 240))))
    }

    /// A grid a `period` apart.
    #[must_use]
    pub fn every(period: Duration) -> Self {
        Self { period, next: None }
    }

    /// The time between slots.
    #[must_use]
    pub fn period(&self) -> Duration {
        self.period
    }

    /// Changes the time between slots from the next frame on (a lower rate a link asks for).
    pub fn set_period(&mut self, period: Duration) {
        self.period = period;
    }

    /// When the next frame may be drawn, if that is after `now` (`None`: it may be drawn now).
    #[must_use]
    pub fn wait_until(&self, now: Instant) -> Option<Instant> {
        self.next.map(|t| t - self.period / 4).filter(|&t| t > now)
    }

    /// Records a frame drawn at `now`: the next slot is a period after this one's, or after
    /// `now` when the frame came more than a quarter period late.
    pub fn drawn(&mut self, now: Instant) {
        let early = self.period / 4;
        let base = self.next.map_or(now, |t| t.max(now - early));
        self.next = Some(base + self.period);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const P: Duration = Duration::from_millis(40);

    #[test]
    fn frames_on_time_keep_the_grid_and_may_come_a_quarter_early() {
        let t = Instant::now();
        let mut g = FrameGrid::every(P);
        assert_eq!(g.wait_until(t), None, "the first frame goes at once");
        g.drawn(t);
        assert_eq!(g.wait_until(t), Some(t + P - P / 4));
        // Drawn 5 ms early: the slot after it stays on the grid.
        g.drawn(t + P - Duration::from_millis(5));
        assert_eq!(g.wait_until(t + P), Some(t + 2 * P - P / 4));
    }

    #[test]
    fn after_a_pause_the_grid_starts_again() {
        let t = Instant::now();
        let mut g = FrameGrid::every(P);
        g.drawn(t);
        let late = t + 10 * P;
        assert_eq!(g.wait_until(late), None);
        g.drawn(late);
        assert_eq!(g.wait_until(late), Some(late - P / 4 + P - P / 4));
    }

    #[test]
    fn a_hundred_frames_on_a_late_machine_keep_the_rate() {
        let t = Instant::now();
        let mut g = FrameGrid::every(P);
        let mut now = t;
        for _ in 0..100 {
            now = g.wait_until(now).unwrap_or(now) + Duration::from_millis(2);
            g.drawn(now);
        }
        let mean = (now - t).as_secs_f64() / 99.0;
        assert!((mean - P.as_secs_f64()).abs() < 0.001, "mean period {mean}");
    }
}
