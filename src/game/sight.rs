//! Line of sight and flight paths on the grid, walked with the renderer's own DDA
//! ([`crate::render::cast`]'s `Setup` and `advance`): what a creature sees and where a tag stops
//! are decided by exactly the steps a ray of the 3D view takes.
//!
//! On maps with heights (`Hz`) a line also has a height at each end, and it is stopped where it
//! leaves the open air of a cell it crosses: the face of a step or a balcony, a lintel, a floor
//! or a ceiling, as the renderer draws them.

use crate::map::{Cell, Map};
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::ray::{advance, Setup, Side};

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
    walk(map, doors, from, to, |_, _, _| None)
}

/// Where the straight line from (`from`, `from_z`) to (`to`, `to_z`) is first stopped: as
/// [`first_block`], and on maps with heights also where the line's height leaves the open span
/// of a cell it is in (a step face, a floor, a ledge's underside, a lintel). The cell returned is
/// the one whose solid part stops it, with the fraction of the segment at which it does.
#[must_use]
pub fn first_block_at(
    map: &Map,
    doors: &DoorState,
    (from, from_z): (Vec2, f64),
    (to, to_z): (Vec2, f64),
) -> Option<((i64, i64), f64)> {
    if !map.has_heights() {
        return first_block(map, doors, from, to);
    }
    let z = |t: f64| from_z + (to_z - from_z) * t;
    // Where, within [t0, t1] of cell c, the line is outside c's open air (None: inside all along).
    let leaves = |c: (i64, i64), t0: f64, t1: f64| -> Option<f64> {
        const EPS: f64 = 1e-9;
        let Some(span) = map.span(c.0, c.1) else {
            return Some(t0);
        };
        let (z0, z1) = (z(t0), z(t1));
        if z0 < span.floor - EPS || z0 > span.ceil + EPS {
            return Some(t0);
        }
        let bound = if z1 < span.floor - EPS {
            span.floor
        } else if z1 > span.ceil + EPS {
            span.ceil
        } else {
            return None;
        };
        // z is linear and crosses `bound` between t0 and t1 (z0 is inside, z1 beyond).
        Some(t0 + (t1 - t0) * (bound - z0) / (z1 - z0))
    };
    walk(map, doors, from, to, leaves)
}

/// The DDA walk both share: each cell from `from`'s to `to`'s is checked for walls and shut
/// doors as it is entered, and `leaves(cell, t_in, t_out)` says where within the part of the
/// segment in `cell` (fractions of it) the line leaves its open air, if it does.
fn walk(
    map: &Map,
    doors: &DoorState,
    from: Vec2,
    to: Vec2,
    leaves: impl Fn((i64, i64), f64, f64) -> Option<f64>,
) -> Option<((i64, i64), f64)> {
    let target = (to.x.floor() as i64, to.y.floor() as i64);
    let Setup {
        mut cell,
        delta,
        step,
        mut side_dist,
    } = Setup::new(from, to - from);
    if cell == target {
        return leaves(cell, 0.0, 1.0).map(|t| (cell, t));
    }
    let mut entered = 0.0;
    // A straight segment crosses exactly this many grid lines; a few more absorb rounding.
    let lines = (target.0 - cell.0).unsigned_abs() + (target.1 - cell.1).unsigned_abs() + 2;
    for _ in 0..lines {
        let before = cell;
        let side = advance(&mut side_dist, delta, &mut cell, step);
        let t = match side {
            Side::X => side_dist.0 - delta.0,
            Side::Y => side_dist.1 - delta.1,
        }
        .clamp(0.0, 1.0);
        if let Some(at) = leaves(before, entered, t.max(entered)) {
            return Some((before, at));
        }
        if blocks_sight(map, doors, cell.0, cell.1) {
            return Some((cell, t));
        }
        entered = t.max(entered);
        if cell == target {
            return leaves(cell, entered, 1.0).map(|t| (cell, t));
        }
    }
    // Rounding walked the ray past the target's cell without entering it: the way there was
    // clear (every cell on it was checked), so count it as reached.
    leaves(cell, entered, 1.0).map(|t| (cell, t))
}

/// Whether `to` can be seen from `from`: the DDA from one toward the other enters `to`'s cell
/// before any wall, void or shut door (distance not considered).
#[cfg(test)]
#[must_use]
pub(crate) fn line_of_sight(map: &Map, doors: &DoorState, from: Vec2, to: Vec2) -> bool {
    first_block(map, doors, from, to).is_none()
}

/// Whether `to` is within `range` cells of `from` (on the map plane) and in its line of sight,
/// each point with its height (heights matter on `Hz` maps only).
#[must_use]
pub fn sees(map: &Map, doors: &DoorState, from: (Vec2, f64), to: (Vec2, f64), range: f64) -> bool {
    (to.0 - from.0).length() <= range && first_block_at(map, doors, from, to).is_none()
}

/// A test map of one row: the start (floor 0, ceiling 1) at x 1, then a room two walls tall
/// from x 2 to 6 whose cell 3 is `Hs step` (e.g. "0.8 2": a step; "-1.5 2": a pit).
#[cfg(test)]
pub(crate) fn stepped_row(step: &str) -> Map {
    crate::map::parse_map(
        "t.cub",
        format!(
            "NO ./a.png\nSO ./a.png\nWE ./a.png\nEA ./a.png\nF 1,1,1\nC 2,2,2\n\
             Hr 0 2\nHs {step}\n\n11111111\n1Nrsrrr1\n11111111\n"
        )
        .as_bytes(),
    )
    .expect("map")
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
        let (ea, eb) = ((a, 0.5), (b, 0.5));
        assert!(sees(&m, &doors, ea, eb, 8.0) && !sees(&m, &doors, ea, eb, 4.0));
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

    #[test]
    fn on_height_maps_a_step_face_stops_lines_below_its_top_but_not_above() {
        let m = stepped_row("0.8 2");
        let doors = DoorState::none();
        let (a, b) = (Vec2::new(1.5, 1.5), Vec2::new(5.5, 1.5));
        // Eye to eye at 0.5: the step's face (0 to 0.8) is in the way, entered at x = 3.
        let (cell, t) = first_block_at(&m, &doors, (a, 0.5), (b, 0.5)).expect("blocked");
        assert_eq!(cell, (3, 1));
        assert!((t - 1.5 / 4.0).abs() < 1e-12, "{t}");
        assert!(!sees(&m, &doors, (a, 0.5), (b, 0.5), 8.0));
        // Over its top: seen both ways.
        assert!(sees(&m, &doors, (a, 0.9), (b, 0.9), 8.0));
        assert!(sees(&m, &doors, (b, 0.9), (a, 0.9), 8.0));
        // Down from the step's top to the far floor: the line passes the step's edge above it.
        assert!(sees(&m, &doors, (Vec2::new(3.5, 1.5), 1.3), (b, 0.5), 8.0));
        // From the floor up to just above the step: the line meets its face below its top.
        let up = first_block_at(&m, &doors, (b, 0.5), (Vec2::new(3.5, 1.5), 0.85));
        assert_eq!(up.map(|(c, _)| c), Some((3, 1)));
        // The step's top is solid ground: a line down into it stops at its floor, 0.8.
        let (cell, t) = first_block_at(
            &m,
            &doors,
            (Vec2::new(3.5, 1.5), 1.6),
            (Vec2::new(3.9, 1.5), 0.0),
        )
        .expect("into the floor");
        assert_eq!(cell, (3, 1));
        assert!((t - 0.5).abs() < 1e-12, "{t}");
    }

    #[test]
    fn a_lowered_ceiling_stops_lines_above_it_and_flat_maps_ignore_heights() {
        let m = stepped_row("0 0.4");
        let doors = DoorState::none();
        let (a, b) = (Vec2::new(1.5, 1.5), Vec2::new(5.5, 1.5));
        assert!(!sees(&m, &doors, (a, 0.5), (b, 0.5), 8.0));
        assert!(sees(&m, &doors, (a, 0.3), (b, 0.3), 8.0));
        let flat = grid_map("1111111\n1N00001\n1111111\n");
        for z in [-3.0, 0.5, 7.0] {
            assert_eq!(
                first_block_at(&flat, &doors, (a, z), (b, 0.5)),
                first_block(&flat, &doors, a, b)
            );
        }
    }
}
