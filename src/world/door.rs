//! Door state: how far each `D` door has slid open. Dynamic, so it lives beside the world,
//! is advanced by the game step and is read (never written) by the renderer.

use crate::map::{Cell, Map};
use crate::vec2::Vec2;

/// Seconds a door takes to slide fully open or shut.
pub const SLIDE_SECONDS: f64 = 1.0;

/// How far a door must be open before one can walk through it.
pub const PASSABLE_OPEN: f64 = 0.9;

/// The reach for opening a door: its cell must start within this many cells in front of the eye.
pub const REACH: f64 = 1.5;

/// Open amounts per door cell (0 = shut, 1 = fully slid into the wall) and where each is heading.
#[derive(Debug, Clone, PartialEq)]
pub struct DoorState {
    /// Door cells, sorted, for binary search.
    cells: Vec<(i64, i64)>,
    open: Vec<f64>,
    /// Whether each door is heading open (true) or shut.
    opening: Vec<bool>,
}

impl DoorState {
    /// Every door of `map`, all shut.
    #[must_use]
    pub fn new(map: &Map) -> Self {
        let mut cells = map.door_cells();
        cells.sort_unstable();
        let n = cells.len();
        Self {
            cells,
            open: vec![0.0; n],
            opening: vec![false; n],
        }
    }

    /// A state without doors (a map without `D` cells, or "treat every door as shut").
    #[must_use]
    pub const fn none() -> Self {
        Self {
            cells: Vec::new(),
            open: Vec::new(),
            opening: Vec::new(),
        }
    }

    fn index(&self, cell: (i64, i64)) -> Option<usize> {
        self.cells.binary_search(&cell).ok()
    }

    /// The door cells this state tracks, sorted.
    #[must_use]
    pub fn cells(&self) -> &[(i64, i64)] {
        &self.cells
    }

    /// How far the door at `cell` is open, 0..=1 (0 for cells that are not doors).
    #[must_use]
    #[inline]
    pub fn open_amount(&self, cell: (i64, i64)) -> f64 {
        if self.cells.is_empty() {
            return 0.0;
        }
        self.index(cell).map_or(0.0, |i| self.open[i])
    }

    /// Sets a door's open amount directly (tests, replays, a half-open golden); it stays there.
    pub fn set_open(&mut self, cell: (i64, i64), amount: f64) {
        if let Some(i) = self.index(cell) {
            self.open[i] = amount.clamp(0.0, 1.0);
            // A door set part-way open keeps opening on the next update.
            self.opening[i] = self.open[i] > 0.0;
        }
    }

    /// Slides every door toward its target by `dt` seconds.
    pub fn update(&mut self, dt: f64) {
        let step = (dt.max(0.0)) / SLIDE_SECONDS;
        for (o, &opening) in self.open.iter_mut().zip(&self.opening) {
            *o = if opening {
                (*o + step).min(1.0)
            } else {
                (*o - step).max(0.0)
            };
        }
    }

    /// Whether the door at `cell` stops movement (any door not open far enough).
    #[must_use]
    pub fn blocks(&self, cell: (i64, i64)) -> bool {
        self.index(cell)
            .is_some_and(|i| self.open[i] < PASSABLE_OPEN)
    }

    /// Toggles the nearest door straight ahead of `pos` along `dir` within [`REACH`];
    /// returns its cell. A door is not shut while `pos` stands in its cell.
    pub fn toggle_facing(&mut self, map: &Map, pos: Vec2, dir: Vec2) -> Option<(i64, i64)> {
        let cell = door_ahead(map, pos, dir)?;
        let i = self.index(cell)?;
        let inside = (pos.x.floor() as i64, pos.y.floor() as i64) == cell;
        if self.opening[i] && inside {
            return None;
        }
        self.opening[i] = !self.opening[i];
        Some(cell)
    }
}

/// The first door cell a ray from `pos` along `dir` enters within [`REACH`], stopping at walls.
#[must_use]
pub fn door_ahead(map: &Map, pos: Vec2, dir: Vec2) -> Option<(i64, i64)> {
    let len = dir.length();
    if len == 0.0 || !len.is_finite() {
        return None;
    }
    let dir = dir * (1.0 / len);
    let mut cell = (pos.x.floor() as i64, pos.y.floor() as i64);
    if matches!(map.cell(cell.0, cell.1), Cell::Door(_)) {
        return Some(cell);
    }
    let delta = |d: f64| {
        if d == 0.0 {
            f64::INFINITY
        } else {
            (1.0 / d).abs()
        }
    };
    let (dx, dy) = (delta(dir.x), delta(dir.y));
    let (sx, mut tx) = if dir.x < 0.0 {
        (-1, (pos.x - cell.0 as f64) * dx)
    } else {
        (1, (cell.0 as f64 + 1.0 - pos.x) * dx)
    };
    let (sy, mut ty) = if dir.y < 0.0 {
        (-1, (pos.y - cell.1 as f64) * dy)
    } else {
        (1, (cell.1 as f64 + 1.0 - pos.y) * dy)
    };
    loop {
        let t = if tx < ty {
            cell.0 += sx;
            tx += dx;
            tx - dx
        } else {
            cell.1 += sy;
            ty += dy;
            ty - dy
        };
        if t > REACH {
            return None;
        }
        match map.cell(cell.0, cell.1) {
            Cell::Door(_) => return Some(cell),
            Cell::Floor { .. } => {}
            _ => return None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::parse_map;

    fn map() -> Map {
        let text = "NO n\nSO s\nWE w\nEA e\nF 1,2,3\nC 4,5,6\n111111\n1N0D01\n111111\n";
        parse_map("t.cub", text.as_bytes()).unwrap()
    }

    #[test]
    fn doors_start_shut_and_slide_over_a_second() {
        let m = map();
        let mut d = DoorState::new(&m);
        assert_eq!(d.cells(), &[(3, 1)]);
        assert!(d.blocks((3, 1)) && !d.blocks((2, 1)));
        assert_eq!(
            d.toggle_facing(&m, Vec2::new(2.2, 1.5), Vec2::new(1.0, 0.0)),
            Some((3, 1))
        );
        d.update(0.5);
        assert!((d.open_amount((3, 1)) - 0.5).abs() < 1e-12);
        d.update(10.0);
        assert_eq!(d.open_amount((3, 1)), 1.0);
        assert!(!d.blocks((3, 1)));
    }

    #[test]
    fn doors_out_of_reach_or_behind_are_not_toggled() {
        let m = map();
        let mut d = DoorState::new(&m);
        assert_eq!(
            d.toggle_facing(&m, Vec2::new(1.4, 1.5), Vec2::new(1.0, 0.0)),
            None
        );
        assert_eq!(
            d.toggle_facing(&m, Vec2::new(2.5, 1.5), Vec2::new(-1.0, 0.0)),
            None
        );
        assert_eq!(
            d.toggle_facing(&m, Vec2::new(2.5, 1.5), Vec2::new(0.0, 0.0)),
            None
        );
    }

    #[test]
    fn a_door_is_not_shut_on_the_player() {
        let m = map();
        let mut d = DoorState::new(&m);
        d.set_open((3, 1), 1.0);
        assert_eq!(
            d.toggle_facing(&m, Vec2::new(3.5, 1.5), Vec2::new(1.0, 0.0)),
            None
        );
        assert_eq!(
            d.toggle_facing(&m, Vec2::new(2.5, 1.5), Vec2::new(1.0, 0.0)),
            Some((3, 1))
        );
        d.update(2.0);
        assert_eq!(d.open_amount((3, 1)), 0.0);
    }
}
