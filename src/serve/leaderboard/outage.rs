//! A database that stopped answering, as the writer thread sees it: when to try again (a pause
//! that grows from [`FIRST_RETRY`] to [`LAST_RETRY`]), and whether a failure starts an outage
//! (logged once) or continues one (not logged again), so an hour without the database is two
//! log lines, not thousands.

use std::time::{Duration, Instant};

/// The pause after the first failure.
pub const FIRST_RETRY: Duration = Duration::from_millis(250);

/// The longest pause between tries.
pub const LAST_RETRY: Duration = Duration::from_secs(5);

/// One kind of access (writing, or reading) and whether it works.
#[derive(Debug, Clone)]
pub struct Outage {
    /// When the first failure of this outage came (none: it works).
    since: Option<Instant>,
    /// No try before this.
    next_try: Option<Instant>,
    pause: Duration,
}

impl Default for Outage {
    fn default() -> Self {
        Self::new()
    }
}

impl Outage {
    /// Working, as far as anyone knows.
    #[must_use]
    pub fn new() -> Self {
        Self {
            since: None,
            next_try: None,
            pause: FIRST_RETRY,
        }
    }

    /// Whether a try is due at `now`.
    #[must_use]
    pub fn may_try(&self, now: Instant) -> bool {
        self.next_try.is_none_or(|t| now >= t)
    }

    /// How long from `now` until the next try is due (zero when it is due).
    #[must_use]
    pub fn until_next_try(&self, now: Instant) -> Duration {
        self.next_try
            .map_or(Duration::ZERO, |t| t.saturating_duration_since(now))
    }

    /// Whether an outage is going on.
    #[must_use]
    pub fn is_away(&self) -> bool {
        self.since.is_some()
    }

    /// A try failed at `now`: the next waits longer. True when this starts an outage (the one
    /// failure to log).
    pub fn failed(&mut self, now: Instant) -> bool {
        let first = self.since.is_none();
        if first {
            self.since = Some(now);
            self.pause = FIRST_RETRY;
        } else {
            self.pause = (self.pause * 2).min(LAST_RETRY);
        }
        self.next_try = Some(now + self.pause);
        first
    }

    /// A try worked at `now`: how long the outage lasted, if there was one.
    pub fn recovered(&mut self, now: Instant) -> Option<Duration> {
        self.next_try = None;
        self.pause = FIRST_RETRY;
        self.since.take().map(|s| now.saturating_duration_since(s))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_outage_is_reported_once_and_retried_ever_more_slowly_up_to_a_bound() {
        let t0 = Instant::now();
        let mut o = Outage::new();
        assert!(o.may_try(t0) && !o.is_away());
        assert!(o.failed(t0), "the first failure starts the outage");
        assert!(!o.may_try(t0) && o.may_try(t0 + FIRST_RETRY));
        let mut now = t0;
        let mut pauses = Vec::new();
        for _ in 0..10 {
            now += o.until_next_try(now);
            assert!(!o.failed(now), "later failures are the same outage");
            pauses.push(o.until_next_try(now));
        }
        assert!(pauses.windows(2).all(|w| w[0] <= w[1]), "{pauses:?}");
        assert_eq!(*pauses.last().unwrap(), LAST_RETRY);
        let lasted = o.recovered(now + Duration::from_secs(1)).unwrap();
        assert_eq!(lasted, now + Duration::from_secs(1) - t0);
        assert!(o.may_try(now) && o.recovered(now).is_none());
    }
}
