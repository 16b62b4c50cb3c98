//! Which map each round plays: the served maps in the order given, or (`--shuffle`) in a seeded
//! random order drawn afresh for each pass, never playing the same map twice in a row when
//! there are several. The map after this one is always known, so the results can name it.

use crate::game::rng::Rng;

/// The order rounds walk through `len` maps.
#[derive(Debug, Clone)]
pub struct Rotation {
    /// This pass through the maps (indices into the served list).
    pass: Vec<usize>,
    /// Where in `pass` this round is.
    at: usize,
    /// The pass after this one, drawn when this one reaches its last map.
    upcoming: Option<Vec<usize>>,
    /// Draws shuffled passes; `None` plays the maps in the order given.
    rng: Option<Rng>,
}

impl Rotation {
    /// Rotates through `len` maps (at least one), shuffled from `shuffle`'s seed if given.
    #[must_use]
    pub fn new(len: usize, shuffle: Option<u64>) -> Self {
        let len = len.max(1);
        let mut rng = shuffle.map(Rng::new);
        let pass = draw(len, rng.as_mut(), None);
        let mut r = Self {
            pass,
            at: 0,
            upcoming: None,
            rng,
        };
        r.prepare();
        r
    }

    /// The map this round plays.
    #[must_use]
    pub fn current(&self) -> usize {
        self.pass[self.at]
    }

    /// The map the next round will play.
    #[must_use]
    pub fn next(&self) -> usize {
        match &self.upcoming {
            Some(p) => p[0],
            None => self.pass[self.at + 1],
        }
    }

    /// Moves on to the next round's map.
    pub fn advance(&mut self) {
        if let Some(p) = self.upcoming.take() {
            self.pass = p;
            self.at = 0;
        } else {
            self.at += 1;
        }
        self.prepare();
    }

    /// Draws the following pass once this one is on its last map.
    fn prepare(&mut self) {
        if self.at + 1 == self.pass.len() && self.upcoming.is_none() {
            let last = self.current();
            self.upcoming = Some(draw(self.pass.len(), self.rng.as_mut(), Some(last)));
        }
    }
}

/// One pass over `len` maps: in order, or a Fisher-Yates shuffle that does not start with
/// `after` (the map just played) when another could start.
fn draw(len: usize, rng: Option<&mut Rng>, after: Option<usize>) -> Vec<usize> {
    let mut pass: Vec<usize> = (0..len).collect();
    let Some(rng) = rng else {
        return pass;
    };
    for i in (1..len).rev() {
        let j = rng.below(i + 1);
        pass.swap(i, j);
    }
    if len > 1 && after == Some(pass[0]) {
        let k = 1 + rng.below(len - 1);
        pass.swap(0, k);
    }
    pass
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rounds(r: &mut Rotation, n: usize) -> Vec<usize> {
        (0..n)
            .map(|_| {
                let now = r.current();
                let next = r.next();
                r.advance();
                assert_eq!(r.current(), next, "next() named the map that came");
                now
            })
            .collect()
    }

    #[test]
    fn in_order_the_maps_cycle() {
        assert_eq!(
            rounds(&mut Rotation::new(3, None), 7),
            [0, 1, 2, 0, 1, 2, 0]
        );
        assert_eq!(rounds(&mut Rotation::new(1, None), 3), [0, 0, 0]);
        assert_eq!(rounds(&mut Rotation::new(0, None), 2), [0, 0]);
    }

    #[test]
    fn shuffled_passes_hold_every_map_once_never_repeat_and_follow_the_seed() {
        let mut r = Rotation::new(4, Some(9));
        let played = rounds(&mut r, 40);
        for pass in played.chunks(4) {
            let mut sorted = pass.to_vec();
            sorted.sort_unstable();
            assert_eq!(sorted, [0, 1, 2, 3], "{played:?}");
        }
        assert!(played.windows(2).all(|w| w[0] != w[1]), "{played:?}");
        assert_eq!(played, rounds(&mut Rotation::new(4, Some(9)), 40));
        assert_ne!(played, rounds(&mut Rotation::new(4, Some(10)), 40));
        assert_ne!(played[..8], [0, 1, 2, 3, 0, 1, 2, 3]);
    }
}
