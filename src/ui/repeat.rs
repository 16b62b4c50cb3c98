//! The keyboard's auto-repeat timing, learned from the presses themselves.
//!
//! Without key-release events a held key looks like: press, a pause (the repeat delay), then
//! presses every repeat interval. Presses closer together than a person taps are auto-repeat
//! (the key is held), and a held key is let go a few intervals after its repeats stop. Defaults
//! fit common settings (≈450 ms delay, 45 ms interval); after one real auto-repeat run we use
//! the measured figures.

use std::time::Duration;

/// What is believed about the auto-repeat of this terminal's keyboard.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RepeatTiming {
    delay: Duration,
    interval: Duration,
}

impl Default for RepeatTiming {
    fn default() -> Self {
        Self {
            delay: Duration::from_millis(450),
            interval: Duration::from_millis(45),
        }
    }
}

impl RepeatTiming {
    /// Longest repeat delay believed (a slower "repeat" is the player tapping).
    pub const MAX_DELAY: Duration = Duration::from_millis(1200);

    /// Whether a press `gap` after the previous press of the same key is its auto-repeat
    /// (closer together than a person taps), rather than another tap.
    #[must_use]
    pub fn is_repeat(&self, gap: Duration) -> bool {
        gap <= self.repeat_hold()
    }

    /// How long a first press of a key with no tap step (crouch) counts as held: the delay plus
    /// a margin for jitter.
    #[must_use]
    pub fn first_hold(&self) -> Duration {
        let d = self.delay + self.delay / 10 + Duration::from_millis(30);
        d.clamp(Duration::from_millis(150), Duration::from_millis(1000))
    }

    /// How long after a repeat the key still counts as held: a few intervals.
    #[must_use]
    pub fn repeat_hold(&self) -> Duration {
        (self.interval * 3).clamp(Duration::from_millis(60), Duration::from_millis(250))
    }

    /// Learns from one key's press → first repeat gap and first repeat → second repeat gap;
    /// ignored unless it looks like auto-repeat (steady repeats much faster than the delay).
    pub fn observe(&mut self, delay: Duration, interval: Duration) {
        if delay <= Self::MAX_DELAY && !interval.is_zero() && interval * 2 < delay {
            self.delay = delay;
            self.interval = interval;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    #[test]
    fn defaults_bridge_a_half_second_delay() {
        let t = RepeatTiming::default();
        assert!(t.first_hold() > ms(500) && t.first_hold() < ms(560));
        assert_eq!(t.repeat_hold(), ms(135));
    }

    #[test]
    fn learns_a_fast_keyboard_and_a_slow_one() {
        let mut t = RepeatTiming::default();
        t.observe(ms(250), ms(33));
        assert_eq!(t.first_hold(), ms(305));
        assert_eq!(t.repeat_hold(), ms(99));
        t.observe(ms(660), ms(40));
        assert_eq!(t.first_hold(), ms(756));
    }

    #[test]
    fn taps_are_not_mistaken_for_auto_repeat() {
        let mut t = RepeatTiming::default();
        t.observe(ms(300), ms(280));
        t.observe(ms(2000), ms(30));
        assert_eq!(t, RepeatTiming::default());
    }
}
