//! Moving a round-ish player (an axis-aligned square of half-size `radius`) through the grid.
//!
//! Each axis moves on its own, so pushing diagonally into a wall slides along it; a blocked
//! axis stops exactly `radius` short of the wall, so the eye never enters a wall and the
//! view never reaches past a corner. On maps with heights the same goes for a ledge too high
//! to step onto and a ceiling too low to pass ([`Body::can_enter`]).

use super::body::Body;
use crate::map::{Cell, Map};
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::SolidDisc;

/// Player half-size in cells; small enough to pass a one-cell corridor comfortably.
pub const PLAYER_RADIUS: f64 = 0.2;

/// Longest move tried at once, so a long frame cannot tunnel through a thin wall.
const MAX_SUBSTEP: f64 = 0.1;

/// Slack so a player resting exactly against a wall does not count as overlapping it.
const EPS: f64 = 1e-9;

/// Everything that stops the player: the grid (walls, void, doors not open far enough), solid
/// sprites as discs, and cells the body cannot enter at its height.
#[derive(Debug, Clone, Copy)]
pub struct Obstacles<'a> {
    /// The grid: walls, void and doors.
    pub map: &'a Map,
    /// `None` treats every door as shut.
    pub doors: Option<&'a DoorState>,
    /// Solid sprites, as discs.
    pub discs: &'a [SolidDisc],
    /// The moving body's feet and eye; `None` ignores floor and ceiling heights (only walls,
    /// doors and discs stop it).
    pub body: Option<Body>,
}

impl<'a> Obstacles<'a> {
    /// Only the grid, every door shut (tests, maps without doors or solid sprites).
    #[must_use]
    pub fn grid(map: &'a Map) -> Self {
        Self {
            map,
            doors: None,
            discs: &[],
            body: None,
        }
    }

    fn blocks(&self, i: i64, j: i64) -> bool {
        match self.map.cell(i, j) {
            Cell::Floor { .. } => false,
            Cell::Door(_) => self.doors.is_none_or(|d| d.blocks((i, j))),
            _ => true,
        }
    }

    /// Whether moving a square of half-size `r` from `from` to `to` takes the body into a cell it
    /// cannot enter: one the square did not cover before, or — the floor stood on being the
    /// centre's cell — a centre crossing onto a floor too high to step onto from where the feet
    /// are now. Cells it already overlaps stay allowed otherwise, so a body resting half under a
    /// low ceiling can leave; but one that dropped into a pit while half over its rim cannot walk
    /// back up onto the rim (it must jump, as from anywhere else in the pit).
    fn refuses_entry(&self, from: Vec2, to: Vec2, r: f64) -> bool {
        let Some(body) = self.body else {
            return false;
        };
        let ((a0, a1), (b0, b1)) = covered(from, r);
        let ((i0, i1), (j0, j1)) = covered(to, r);
        let newly = (j0..=j1).any(|j| {
            (i0..=i1).any(|i| {
                let before = (a0..=a1).contains(&i) && (b0..=b1).contains(&j);
                !before && !body.can_enter(self.map, i, j)
            })
        });
        let (centre, next) = (centre_cell(from), centre_cell(to));
        newly
            || (centre != next
                && self
                    .map
                    .span(next.0, next.1)
                    .is_some_and(|s| !body.can_step_onto(s)))
    }

    /// Whether a player of half-size `r` at `p` overlaps a solid sprite's disc.
    fn hits_disc(&self, p: Vec2, r: f64) -> bool {
        self.discs.iter().any(|d| {
            let gap = d.radius + r;
            (d.centre - p).dot(d.centre - p) < gap * gap - EPS
        })
    }
}

/// The cells (inclusive ranges) a square of half-size `r` at `p` overlaps.
fn covered(p: Vec2, r: f64) -> ((i64, i64), (i64, i64)) {
    let lo = |c: f64| (c - r + EPS).floor() as i64;
    let hi = |c: f64| (c + r - EPS).ceil() as i64 - 1;
    ((lo(p.x), hi(p.x)), (lo(p.y), hi(p.y)))
}

/// The cell a point is in (the player's cell: its floor is the one stood on).
#[must_use]
pub fn centre_cell(p: Vec2) -> (i64, i64) {
    (p.x.floor() as i64, p.y.floor() as i64)
}

/// The lowest ceiling over the cells a square of half-size `r` at `p` covers (walls have none;
/// infinite if no covered cell is open), which caps how high the head may rise there.
#[must_use]
pub fn lowest_ceiling(map: &Map, p: Vec2, r: f64) -> f64 {
    let ((i0, i1), (j0, j1)) = covered(p, r);
    (j0..=j1)
        .flat_map(|j| (i0..=i1).filter_map(move |i| map.span(i, j)))
        .map(|s| s.ceil)
        .fold(f64::INFINITY, f64::min)
}

/// Whether `body` fits under the ceiling of every open cell a square of half-size `r` at `p`
/// covers: getting up (or jumping) is allowed only where this holds.
#[must_use]
pub fn fits_here(map: &Map, p: Vec2, r: f64, body: Body) -> bool {
    let ((i0, i1), (j0, j1)) = covered(p, r);
    (j0..=j1).all(|j| (i0..=i1).all(|i| map.span(i, j).is_none_or(|s| body.fits_under(s))))
}

/// Whether a player of half-size `r` standing at `p` overlaps a solid cell (wall, void, shut door).
#[must_use]
pub fn overlaps_wall(obstacles: &Obstacles, p: Vec2, r: f64) -> bool {
    let ((i0, i1), (j0, j1)) = covered(p, r);
    (j0..=j1).any(|j| (i0..=i1).any(|i| obstacles.blocks(i, j)))
}

/// Moves `from` by `delta`, x then y in short sub-steps, stopping each axis at walls, shut
/// doors and solid sprites.
#[must_use]
pub fn slide(obstacles: &Obstacles, from: Vec2, delta: Vec2, r: f64) -> Vec2 {
    let len = delta.length();
    if len == 0.0 || !len.is_finite() {
        return from;
    }
    let n = (len / MAX_SUBSTEP).ceil().max(1.0);
    let part = delta * (1.0 / n);
    let mut p = from;
    for _ in 0..n as usize {
        p.x = move_axis(obstacles, p, part.x, r, true);
        p.y = move_axis(obstacles, p, part.y, r, false);
    }
    p
}

/// The new coordinate on one axis: `p + d` if free, else flush against the wall it met.
fn move_axis(obstacles: &Obstacles, p: Vec2, d: f64, r: f64, along_x: bool) -> f64 {
    if d == 0.0 {
        return if along_x { p.x } else { p.y };
    }
    let moved = if along_x {
        Vec2::new(p.x + d, p.y)
    } else {
        Vec2::new(p.x, p.y + d)
    };
    let c = if along_x { p.x } else { p.y };
    if !overlaps_wall(obstacles, moved, r) && !obstacles.refuses_entry(p, moved, r) {
        // A sprite stops the sub-step; moving away from one that overlaps already is allowed.
        let into_disc = obstacles.hits_disc(moved, r) && !obstacles.hits_disc(p, r);
        return match (into_disc, along_x) {
            (true, _) => c,
            (false, true) => moved.x,
            (false, false) => moved.y,
        };
    }
    // The sub-step is shorter than a cell, so the only new line of cells is the leading one:
    // rest against its near edge (or stay put if that is behind us, e.g. starting overlapped).
    let flush = if d > 0.0 {
        (c + d + r - EPS).floor() - r
    } else {
        (c + d - r + EPS).floor() + 1.0 + r
    };
    if (d > 0.0 && flush >= c) || (d < 0.0 && flush <= c) {
        flush
    } else {
        c
    }
}

/// Nudges a spawn point that overlaps a wall, or a neighbour a standing body on its own floor
/// could not enter (a ledge, a low ceiling), back inside its own cell (the cell is floor).
#[must_use]
pub fn settle(map: &Map, p: Vec2, r: f64) -> Vec2 {
    let (i, j) = centre_cell(p);
    let standing = Body {
        feet: map.floor_height(i, j),
        eye: crate::render::view::STANDING_EYE,
    };
    let ((i0, i1), (j0, j1)) = covered(p, r);
    let ledge = (j0..=j1).any(|b| {
        (i0..=i1)
            .any(|a| (a, b) != (i, j) && map.span(a, b).is_some() && !standing.can_enter(map, a, b))
    });
    if !ledge && !overlaps_wall(&Obstacles::grid(map), p, r) {
        return p;
    }
    let clamp = |c: f64| {
        let base = c.floor();
        c.clamp(base + r, base + 1.0 - r)
    };
    Vec2::new(clamp(p.x), clamp(p.y))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::grid_map;

    fn map(grid: &str) -> Map {
        grid_map(grid)
    }

    /// A 4×4 room (cells 1..=4) with a pillar at (3,2).
    fn room() -> Map {
        map("111111\n1N0001\n100101\n100001\n100001\n111111\n")
    }

    const R: f64 = PLAYER_RADIUS;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-6
    }

    #[test]
    fn walking_into_a_wall_stops_at_the_radius() {
        let m = room();
        let p = slide(
            &Obstacles::grid(&m),
            Vec2::new(1.5, 4.5),
            Vec2::new(10.0, 0.0),
            R,
        );
        assert!(close(p.x, 5.0 - R) && close(p.y, 4.5), "{p:?}");
        let p = slide(
            &Obstacles::grid(&m),
            Vec2::new(1.5, 4.5),
            Vec2::new(-3.0, 0.0),
            R,
        );
        assert!(close(p.x, 1.0 + R), "{p:?}");
        let p = slide(
            &Obstacles::grid(&m),
            Vec2::new(1.5, 4.5),
            Vec2::new(0.0, 3.0),
            R,
        );
        assert!(close(p.y, 5.0 - R), "{p:?}");
        let p = slide(
            &Obstacles::grid(&m),
            Vec2::new(1.5, 4.5),
            Vec2::new(0.0, -9.0),
            R,
        );
        assert!(close(p.y, 1.0 + R), "{p:?}");
    }

    #[test]
    fn resting_against_a_wall_is_not_overlapping_and_can_leave() {
        let m = room();
        let p = slide(
            &Obstacles::grid(&m),
            Vec2::new(1.5, 4.5),
            Vec2::new(10.0, 0.0),
            R,
        );
        assert!(!overlaps_wall(&Obstacles::grid(&m), p, R));
        // Pushing on into the wall again changes nothing; backing off works.
        assert_eq!(slide(&Obstacles::grid(&m), p, Vec2::new(0.5, 0.0), R), p);
        let back = slide(&Obstacles::grid(&m), p, Vec2::new(-0.5, 0.0), R);
        assert!(close(back.x, p.x - 0.5));
    }

    #[test]
    fn pushing_diagonally_into_a_wall_slides_along_it() {
        let m = room();
        // Against the east wall, moving north-east: x is stuck, y keeps going.
        let start = Vec2::new(5.0 - R, 4.5);
        let p = slide(&Obstacles::grid(&m), start, Vec2::new(0.3, -0.6), R);
        assert!(close(p.x, 5.0 - R), "{p:?}");
        assert!(close(p.y, 3.9), "{p:?}");
        // The slide continues past the pillar's row since the pillar is not in the way.
        let p = slide(&Obstacles::grid(&m), start, Vec2::new(0.3, -2.0), R);
        assert!(close(p.x, 5.0 - R) && close(p.y, 2.5), "{p:?}");
    }

    #[test]
    fn a_pillar_corner_stops_the_player_at_the_radius_on_both_axes() {
        let m = room();
        // Pillar (3,2) spans [3,4)×[2,3). Approach its north-west corner diagonally.
        let p = slide(
            &Obstacles::grid(&m),
            Vec2::new(2.5, 1.5),
            Vec2::new(1.0, 1.0),
            R,
        );
        assert!(!overlaps_wall(&Obstacles::grid(&m), p, R), "{p:?}");
        // One axis got blocked at the radius, the other slid past the corner's reach.
        let x_blocked = close(p.x, 3.0 - R);
        let y_blocked = close(p.y, 2.0 - R);
        assert!(x_blocked || y_blocked, "{p:?}");
    }

    #[test]
    fn cannot_squeeze_through_a_diagonal_gap_between_two_walls() {
        // Walls at (2,1) and (1,2) touch only at the corner (2,2).
        let m = map("11111\n1N101\n11001\n10001\n11111\n");
        let mut p = Vec2::new(1.5, 1.5);
        for _ in 0..100 {
            p = slide(&Obstacles::grid(&m), p, Vec2::new(0.05, 0.05), R);
        }
        assert!(p.x < 2.0 - R + 1e-6 && p.y < 2.0 - R + 1e-6, "{p:?}");
    }

    #[test]
    fn a_huge_frame_step_does_not_tunnel() {
        let m = room();
        let p = slide(
            &Obstacles::grid(&m),
            Vec2::new(1.5, 1.5),
            Vec2::new(1000.0, 0.0),
            R,
        );
        assert!(close(p.x, 3.0 - R) || close(p.x, 5.0 - R), "{p:?}");
        assert!(!overlaps_wall(&Obstacles::grid(&m), p, R));
        // A non-finite step is ignored.
        assert_eq!(
            slide(
                &Obstacles::grid(&m),
                Vec2::new(1.5, 1.5),
                Vec2::new(f64::NAN, 0.0),
                R
            ),
            Vec2::new(1.5, 1.5)
        );
    }

    #[test]
    fn settle_pulls_a_spawn_off_the_walls() {
        let m = room();
        let p = settle(&m, Vec2::new(1.05, 1.02), R);
        assert!(close(p.x, 1.0 + R) && close(p.y, 1.0 + R), "{p:?}");
        assert!(!overlaps_wall(&Obstacles::grid(&m), p, R));
        let free = Vec2::new(2.5, 2.5);
        assert_eq!(settle(&m, free, R), free);
    }

    proptest::proptest! {
        #[test]
        fn random_walks_never_enter_a_wall(moves in proptest::collection::vec((-1.5f64..1.5, -1.5f64..1.5), 1..60)) {
            let map = crate::map::parse_map(crate::world::DEFAULT_MAP_NAME, crate::world::DEFAULT_MAP.as_bytes()).unwrap();
            let m = &map;
            let mut p = m.start.pos();
            for (dx, dy) in moves {
                p = slide(&Obstacles::grid(m), p, Vec2::new(dx, dy), R);
                proptest::prop_assert!(!overlaps_wall(&Obstacles::grid(m), p, R), "{:?}", p);
            }
        }
    }
}
