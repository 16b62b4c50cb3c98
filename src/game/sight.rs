//! Line of sight and flight paths on the grid, walked with the renderer's own DDA
//! ([`crate::render::cast`]'s `Setup` and `advance`): what a creature sees and where a tag stops
//! are decided by exactly the steps a ray of the 3D view takes.

use crate::map::{Cell, Map};
use crate::render::cast::{advance, Setup, Side};
use crate::vec2::Vec2;
use crate::world::door::DoorState;

/// Farthest a wandering or patrolling creature sees, in cells.
pub const SIGHT_RANGE: f64 = 8.0;

/// Whether cell (`i`, `j`) stops sight and flight: walls, the void, and doors not open far
/// enough to walk through.
#[must_use]
pub fn blocks_sight(map: &Map, doors: &DoorState, i: i64, j: i64) -> bool {
    match map.cell(i, j) {
        Cell::Floor { .. } => false,
        Cell::Door(_) => doors.blocks((i, j)),
        Cell::Wall(_) | Cell::Void => true,
    }
}

/// The first blocking cell on the straight segment `from` → `to` (`to`'s own cell included),
/// with the fraction (0..=1) of the segment at which the DDA enters it; `None` when the DDA
/// reaches `to`'s cell and it is open.
#[must_use]
pub fn first_block(
    map: &Map,
    doors: &DoorState,
    from: Vec2,
    to: Vec2,
) -> Option<((i64, i64), f64)> {
    let target = (to.x.floor() as i64, to.y.floor() as i64);
    let Setup {
        mut cell,
        delta,
        step,
        mut side_dist,
    } = Setup::new(from, to - from);
    if cell == target {
        return None;
    }
    // A straight segment crosses exactly this many grid lines; a few more absorb rounding.
    let lines = (target.0 - cell.0).unsigned_abs() + (target.1 - cell.1).unsigned_abs() + 2;
    for _ in 0..lines {
        let side = advance(&mut side_dist, delta, &mut cell, step);
        if blocks_sight(map, doors, cell.0, cell.1) {
            let t = match side {
                Side::X => side_dist.0 - delta.0,
                Side::Y => side_dist.1 - delta.1,
            };
            return Some((cell, t.clamp(0.0, 1.0)));
        }
        if cell == target {
            return None;
        }
    }
    // Rounding walked the ray past the target's cell without entering it: the way there was
    // clear (every cell on it was checked), so count it as reached.
    None
}

/// Whether `to` can be seen from `from`: the DDA from one toward the other enters `to`'s cell
/// before any wall, void or shut door (distance not considered).
#[must_use]
pub fn line_of_sight(map: &Map, doors: &DoorState, from: Vec2, to: Vec2) -> bool {
    first_block(map, doors, from, to).is_none()
}

/// Whether `to` is within `range` cells of `from` and in its line of sight.
#[must_use]
pub fn sees(map: &Map, doors: &DoorState, from: Vec2, to: Vec2, range: f64) -> bool {
    (to - from).length() <= range && line_of_sight(map, doors, from, to)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::grid_map;

    #[test]
    fn walls_and_shut_doors_hide_open_doors_do_not() {
        let m = grid_map("11111111\n1N00D001\n10011001\n11111111\n");
        let mut doors = DoorState::new(&m);
        let (a, b) = (Vec2::new(1.5, 1.5), Vec2::new(6.5, 1.5));
        assert!(!line_of_sight(&m, &doors, a, b));
        assert_eq!(first_block(&m, &doors, a, b).map(|(c, _)| c), Some((4, 1)));
        doors.set_open((4, 1), 1.0);
        assert!(line_of_sight(&m, &doors, a, b));
        assert!(line_of_sight(&m, &doors, b, a));
        // The wall at (3, 2) stands between these two.
        assert!(!line_of_sight(
            &m,
            &doors,
            Vec2::new(2.5, 2.5),
            Vec2::new(5.5, 2.5)
        ));
        assert!(sees(&m, &doors, a, b, 8.0) && !sees(&m, &doors, a, b, 4.0));
        // Same cell: always seen.
        assert!(line_of_sight(&m, &doors, a, Vec2::new(1.9, 1.1)));
    }

    #[test]
    fn the_block_fraction_is_where_the_segment_enters_the_wall() {
        let m = grid_map("111111\n1N0001\n111111\n");
        let doors = DoorState::none();
        let (cell, t) = first_block(&m, &doors, Vec2::new(1.5, 1.5), Vec2::new(7.5, 1.5)).unwrap();
        assert_eq!(cell, (5, 1));
        assert!((t - 3.5 / 6.0).abs() < 1e-12, "{t}");
    }
}
