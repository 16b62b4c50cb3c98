//! One player's score in a level: points, the keys held and the treasures found.

use std::collections::BTreeSet;

/// What a player has gained in the level so far (per player, so a shared world keeps one each).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Score {
    /// Points (treasures add, being caught takes away; never below 0).
    pub points: i64,
    /// Names of the keys picked up.
    pub keys: BTreeSet<String>,
    /// Treasures (items that are not keys) picked up.
    pub found: usize,
}

impl Score {
    /// Whether the player holds key `name`.
    #[must_use]
    pub fn has_key(&self, name: &str) -> bool {
        self.keys.contains(name)
    }

    /// Takes up to `points` away without going below 0; returns how many were taken.
    pub fn lose(&mut self, points: i64) -> i64 {
        let lost = points.clamp(0, self.points.max(0));
        self.points -= lost;
        lost
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn losing_points_stops_at_zero() {
        let mut s = Score {
            points: 30,
            ..Score::default()
        };
        assert_eq!(s.lose(25), 25);
        assert_eq!(s.lose(25), 5);
        assert_eq!((s.points, s.lose(25)), (0, 0));
    }
}
