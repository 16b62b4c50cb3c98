//! Whether `--pos` puts the eye somewhere a frame can be drawn from (`render`, `trace`) or a
//! player can stand (the game): not off the map, not in the void around it, not in a wall. The
//! message names the map's size, so the next try can be inside it.

use crate::map::{Cell, Map};
use crate::vec2::Vec2;

/// What the position is for: a still view may start in a door's cell, a player only on a floor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PoseUse {
    /// `render` and `trace`: a floor or a door cell.
    View,
    /// The game (`play`, `record`): a floor cell.
    Player,
}

/// `map`'s size as the messages give it: `16x9 cells, x 0 to 16 and y 0 to 9`.
fn size_of(map: &Map) -> String {
    format!(
        "{}x{} cells, x 0 to {} and y 0 to {}",
        map.width, map.height, map.width, map.height
    )
}

/// `Ok` when `pos` is in an open cell of `map` for `use_`.
///
/// # Errors
/// Where the position is and how large the map is (what `halfcast` prints for `--pos`).
pub fn check_pos(map: &Map, pos: Vec2, use_: PoseUse) -> Result<(), String> {
    let (i, j) = (pos.x.floor() as i64, pos.y.floor() as i64);
    let inside = (0..map.width as i64).contains(&i) && (0..map.height as i64).contains(&j);
    let (name, size) = (&map.name, size_of(map));
    let problem = match map.cell(i, j) {
        Cell::Floor { .. } => return Ok(()),
        Cell::Door(_) if use_ == PoseUse::View => return Ok(()),
        _ if !inside => format!("is outside the map: {name} is {size}"),
        Cell::Void => {
            format!("is outside the map's walls, in the void of cell ({i},{j}) of {name} ({size})")
        }
        Cell::Wall(_) => {
            format!("is inside a wall, cell ({i},{j}) of {name} ({size}): start in an open cell")
        }
        Cell::Door(_) => format!(
            "is in a door, cell ({i},{j}) of {name} ({size}): a player starts on a floor cell"
        ),
    };
    Err(format!("--pos {},{} {problem}", pos.x, pos.y))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map() -> Map {
        let text = "NO a\nSO a\nWE a\nEA a\nF 1,1,1\nC 2,2,2\n\n 111\n11D11\n10N01\n11111\n";
        crate::map::parse_map("t.cub", text.as_bytes()).unwrap()
    }

    fn message(x: f64, y: f64, use_: PoseUse) -> Option<String> {
        check_pos(&map(), Vec2::new(x, y), use_).err()
    }

    #[test]
    fn open_cells_pass_and_doors_only_for_a_view() {
        assert_eq!(message(2.5, 2.5, PoseUse::Player), None);
        assert_eq!(message(2.5, 1.5, PoseUse::View), None);
        assert_eq!(
            message(2.5, 1.5, PoseUse::Player).unwrap(),
            "--pos 2.5,1.5 is in a door, cell (2,1) of t.cub (5x4 cells, x 0 to 5 and y 0 to 4): \
             a player starts on a floor cell"
        );
    }

    #[test]
    fn off_the_map_in_the_void_and_in_walls_name_the_size() {
        let size = "5x4 cells, x 0 to 5 and y 0 to 4";
        assert_eq!(
            message(500.0, 2.0, PoseUse::View).unwrap(),
            format!("--pos 500,2 is outside the map: t.cub is {size}")
        );
        assert_eq!(
            message(-0.5, 1.0, PoseUse::Player).unwrap(),
            format!("--pos -0.5,1 is outside the map: t.cub is {size}")
        );
        assert_eq!(
            message(0.5, 0.5, PoseUse::View).unwrap(),
            format!("--pos 0.5,0.5 is outside the map's walls, in the void of cell (0,0) of t.cub ({size})")
        );
        assert_eq!(
            message(1.5, 3.5, PoseUse::View).unwrap(),
            format!("--pos 1.5,3.5 is inside a wall, cell (1,3) of t.cub ({size}): start in an open cell")
        );
    }
}
