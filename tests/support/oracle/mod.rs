//! An independent DDA walk (written apart from the library, crossing times only) that the
//! tests compare the caster's JSON output with. Shut doors are panels across their cell's middle.

/// One grid line crossed: the cell entered, the axis crossed (`"x"` = a vertical grid line),
/// and the crossing times of the next x and y grid lines after this step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    pub cell: (i64, i64),
    pub side: &'static str,
    pub side_dist: (f64, f64),
}

/// Where the ray stopped: the cell, the face's axis, the distance along the view direction
/// (for the camera's unnormalised rays) and where across the face it hit (0..1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    pub cell: (i64, i64),
    pub side: &'static str,
    pub perp: f64,
    pub wall_x: f64,
}

/// The whole walk: every step taken, and the hit that ended it.
#[derive(Debug, Clone, PartialEq)]
pub struct Walk {
    pub steps: Vec<Step>,
    pub hit: Hit,
}

/// Walks `ray` from `pos` through `grid` (rows of map bytes: `1` wall, `D` door, anything else
/// floor) until a wall, or a shut door's panel when `doors_open` is false.
pub fn walk(grid: &[Vec<u8>], pos: (f64, f64), ray: (f64, f64), doors_open: bool) -> Walk {
    let mut cell = (pos.0.floor() as i64, pos.1.floor() as i64);
    let axis = |p: f64, d: f64, c: i64| {
        if d > 0.0 {
            ((c as f64 + 1.0 - p) / d, 1.0 / d, 1)
        } else {
            ((p - c as f64) / -d, -1.0 / d, -1)
        }
    };
    let (mut tx, dx, sx) = axis(pos.0, ray.0, cell.0);
    let (mut ty, dy, sy) = axis(pos.1, ray.1, cell.1);
    let at = |i: i64, j: i64| grid[j as usize][i as usize];
    let mut steps = Vec::new();
    loop {
        let (side, t_in) = if tx < ty {
            cell.0 += sx;
            tx += dx;
            ("x", tx - dx)
        } else {
            cell.1 += sy;
            ty += dy;
            ("y", ty - dy)
        };
        steps.push(Step {
            cell,
            side,
            side_dist: (tx, ty),
        });
        match at(cell.0, cell.1) {
            b'1' => {
                let along = if side == "x" {
                    pos.1 + t_in * ray.1
                } else {
                    pos.0 + t_in * ray.0
                };
                let hit = Hit {
                    cell,
                    side,
                    perp: t_in,
                    wall_x: along - along.floor(),
                };
                return Walk { steps, hit };
            }
            b'D' if !doors_open => {
                let horizontal = at(cell.0 - 1, cell.1) == b'1' && at(cell.0 + 1, cell.1) == b'1';
                let (t, side) = if horizontal {
                    ((cell.1 as f64 + 0.5 - pos.1) / ray.1, "y")
                } else {
                    ((cell.0 as f64 + 0.5 - pos.0) / ray.0, "x")
                };
                if t.is_finite() && t >= t_in && t < tx.min(ty) {
                    let wall_x = if side == "x" {
                        pos.1 + t * ray.1 - cell.1 as f64
                    } else {
                        pos.0 + t * ray.0 - cell.0 as f64
                    };
                    let hit = Hit {
                        cell,
                        side,
                        perp: t,
                        wall_x,
                    };
                    return Walk { steps, hit };
                }
            }
            _ => {}
        }
    }
}

/// Equal up to rounding (relative 1e-9).
pub fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()))
}

/// Two hit positions across a face (0..1) are equal on the circle, so 0.9999999999 equals 0.0.
pub fn close_fraction(a: f64, b: f64) -> bool {
    let gap = (a - b).abs();
    gap.min(1.0 - gap) < 1e-9
}

/// A closed map grid of `w` × `h` cells for property tests: walls on the border and where
/// `walls[j * w + i]` holds, floor elsewhere, and the player's `letter` at `start`.
pub fn walled_grid(
    w: usize,
    h: usize,
    walls: &[bool],
    start: (usize, usize),
    letter: u8,
) -> Vec<Vec<u8>> {
    (0..h)
        .map(|j| {
            (0..w)
                .map(|i| {
                    let border = i == 0 || j == 0 || i == w - 1 || j == h - 1;
                    if (i, j) == start {
                        letter
                    } else if border || walls[j * w + i] {
                        b'1'
                    } else {
                        b'0'
                    }
                })
                .collect()
        })
        .collect()
}
