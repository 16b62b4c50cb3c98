//! Where the world's round stands, as a draining world needs to know it: nobody is playing,
//! a round is being played, or its results show (since when). The world task publishes it, and
//! a draining world holds the results instead of starting another round
//! ([`super::ops::drain_wait`]).

use std::time::Instant;

/// The round's state, as the world task last saw it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RoundPhase {
    /// Nobody is in the round (its clock waits).
    Waiting,
    /// A round is being played.
    Playing,
    /// The round is over and its results show, since `since`.
    Results {
        /// When the round ended.
        since: Instant,
    },
}

impl RoundPhase {
    /// The phase of a world with `players` in it whose round `ended` or not; `was` is the
    /// phase before, so the results keep the moment they started.
    #[must_use]
    pub fn next(was: Self, ended: bool, players: usize, now: Instant) -> Self {
        match (ended, was) {
            (true, Self::Results { since }) => Self::Results { since },
            (true, _) => Self::Results { since: now },
            (false, _) if players == 0 => Self::Waiting,
            (false, _) => Self::Playing,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_keep_the_moment_they_started() {
        let t0 = Instant::now();
        let later = t0 + std::time::Duration::from_secs(1);
        assert_eq!(
            RoundPhase::next(RoundPhase::Waiting, false, 0, t0),
            RoundPhase::Waiting
        );
        let playing = RoundPhase::next(RoundPhase::Waiting, false, 2, t0);
        assert_eq!(playing, RoundPhase::Playing);
        let over = RoundPhase::next(playing, true, 2, t0);
        assert_eq!(over, RoundPhase::Results { since: t0 });
        assert_eq!(RoundPhase::next(over, true, 2, later), over);
        assert_eq!(RoundPhase::next(over, false, 1, later), RoundPhase::Playing);
    }
}
