//! A ray's walk through the world's grid (Lode's DDA): cell by cell, crossing the nearer of the
//! next x and y grid lines, until a wall or a shut part of a door stops it. The renderer's
//! columns (`render::cast`), the lamp bake's shadows and the game's sight all walk with it.

use crate::map::{Cell, DoorPlane, Map};
use crate::vec2::Vec2;
use crate::world::door::DoorState;

/// deltaDist for a ray component that is exactly zero (Lode's convention: finite, never chosen).
pub const NEVER: f64 = 1e30;

/// Which grid line a ray crossed to enter a cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Side {
    /// Crossed a vertical grid line (stepped in x).
    #[serde(rename = "x")]
    X,
    /// Crossed a horizontal grid line (stepped in y).
    #[serde(rename = "y")]
    Y,
}

impl Side {
    /// "x" or "y", as the JSON and the debug pane print it.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Side::X => "x",
            Side::Y => "y",
        }
    }
}

/// Where one column's ray stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColumnHit {
    /// The wall cell (i, j) that stopped the ray.
    pub cell: (i64, i64),
    /// What that cell is (a wall type, or void when the ray left the map).
    pub what: Cell,
    /// Which grid line the ray crossed into the wall (y-crossed walls are shaded darker).
    pub side: Side,
    /// Distance along the view direction (no fisheye): sideDist − deltaDist of `side`'s axis.
    pub perp_dist: f64,
    /// Where along the wall face the ray hit, in [0, 1); on a door, along the door's panel
    /// (already shifted by how far it is open).
    pub wall_x: f64,
    /// The column's ray direction, dir + plane·(2x/W − 1) (not normalised).
    pub ray_dir: Vec2,
}

/// One DDA step: the cell entered, the side crossed, and both sideDists after the step.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct DdaStep {
    /// The cell entered.
    pub cell: (i64, i64),
    /// The grid line crossed to enter it.
    pub side: Side,
    /// sideDistX/Y after the step.
    pub side_dist: (f64, f64),
}

/// The DDA's starting state for a ray.
pub(crate) struct Setup {
    pub(crate) cell: (i64, i64),
    pub(crate) delta: (f64, f64),
    pub(crate) step: (i64, i64),
    pub(crate) side_dist: (f64, f64),
}

impl Setup {
    pub(crate) fn new(pos: Vec2, ray: Vec2) -> Self {
        let cell = (pos.x.floor() as i64, pos.y.floor() as i64);
        let delta = |d: f64| if d == 0.0 { NEVER } else { (1.0 / d).abs() };
        let delta = (delta(ray.x), delta(ray.y));
        let axis = |d: f64, p: f64, m: i64, dd: f64| {
            if d < 0.0 {
                (-1, (p - m as f64) * dd)
            } else {
                (1, (m as f64 + 1.0 - p) * dd)
            }
        };
        let (sx, dx) = axis(ray.x, pos.x, cell.0, delta.0);
        let (sy, dy) = axis(ray.y, pos.y, cell.1, delta.1);
        Self {
            cell,
            delta,
            step: (sx, sy),
            side_dist: (dx, dy),
        }
    }
}

/// One DDA step (Lode's loop body): crosses the nearer of the next x and y grid lines, moving
/// `cell` and that axis's sideDist on; returns which side was crossed.
#[inline]
pub(crate) fn advance(
    side_dist: &mut (f64, f64),
    delta: (f64, f64),
    cell: &mut (i64, i64),
    step: (i64, i64),
) -> Side {
    if side_dist.0 < side_dist.1 {
        side_dist.0 += delta.0;
        cell.0 += step.0;
        Side::X
    } else {
        side_dist.1 += delta.1;
        cell.1 += step.1;
        Side::Y
    }
}

/// Walks one ray from `pos` until it enters a cell that blocks it, reporting each step.
/// Doors count as shut.
pub fn cast_ray(map: &Map, pos: Vec2, ray: Vec2, on_step: impl FnMut(DdaStep)) -> ColumnHit {
    cast_ray_doors(map, &DoorState::none(), pos, ray, on_step)
}

/// Where a ray meets a door's panel (the mid-line of its cell) while inside the cell, if it
/// meets the part not yet slid away: Wolfenstein's inset door.
#[inline]
#[allow(clippy::too_many_arguments)]
pub(crate) fn door_hit(
    doors: &DoorState,
    plane: DoorPlane,
    cell: (i64, i64),
    pos: Vec2,
    ray: Vec2,
    t_enter: f64,
    t_exit: f64,
) -> Option<ColumnHit> {
    let (t, along, side) = match plane {
        DoorPlane::X if ray.x != 0.0 => {
            let t = (cell.0 as f64 + 0.5 - pos.x) / ray.x;
            (t, pos.y + t * ray.y - cell.1 as f64, Side::X)
        }
        DoorPlane::Y if ray.y != 0.0 => {
            let t = (cell.1 as f64 + 0.5 - pos.y) / ray.y;
            (t, pos.x + t * ray.x - cell.0 as f64, Side::Y)
        }
        _ => return None,
    };
    if !(t >= t_enter && t < t_exit) {
        return None;
    }
    let along = along.clamp(0.0, 1.0 - 1e-12);
    let open = doors.open_amount(cell);
    if along < open {
        return None;
    }
    Some(ColumnHit {
        cell,
        what: Cell::Door(plane),
        side,
        perp_dist: t,
        wall_x: along - open,
        ray_dir: ray,
    })
}

/// [`cast_ray`] with doors open as far as `doors` says.
pub fn cast_ray_doors(
    map: &Map,
    doors: &DoorState,
    pos: Vec2,
    ray: Vec2,
    mut on_step: impl FnMut(DdaStep),
) -> ColumnHit {
    let Setup {
        mut cell,
        delta,
        step,
        mut side_dist,
    } = Setup::new(pos, ray);
    if let Cell::Door(plane) = map.cell(cell.0, cell.1) {
        let t_exit = side_dist.0.min(side_dist.1);
        if let Some(hit) = door_hit(doors, plane, cell, pos, ray, 0.0, t_exit) {
            return hit;
        }
    }
    loop {
        let side = advance(&mut side_dist, delta, &mut cell, step);
        on_step(DdaStep {
            cell,
            side,
            side_dist,
        });
        let what = map.cell(cell.0, cell.1);
        if let Cell::Door(plane) = what {
            let t_enter = match side {
                Side::X => side_dist.0 - delta.0,
                Side::Y => side_dist.1 - delta.1,
            };
            let t_exit = side_dist.0.min(side_dist.1);
            if let Some(hit) = door_hit(doors, plane, cell, pos, ray, t_enter, t_exit) {
                return hit;
            }
            continue;
        }
        if what.blocks_ray() {
            let perp_dist = match side {
                Side::X => side_dist.0 - delta.0,
                Side::Y => side_dist.1 - delta.1,
            };
            let along = match side {
                Side::X => pos.y + perp_dist * ray.y,
                Side::Y => pos.x + perp_dist * ray.x,
            };
            let wall_x = along - along.floor();
            return ColumnHit {
                cell,
                what,
                side,
                perp_dist,
                wall_x,
                ray_dir: ray,
            };
        }
    }
}
