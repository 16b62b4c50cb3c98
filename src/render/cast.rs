//! The grid DDA: one ray per screen column, pure maths over a [`Map`] and a [`Camera`].

use crate::camera::Camera;
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

/// The whole traversal of one column's ray, for the debug pane and the JSON.
#[derive(Debug, Clone, PartialEq)]
pub struct DdaTrace {
    /// The screen column traced.
    pub column: usize,
    /// Its ray direction.
    pub ray_dir: Vec2,
    /// deltaDistX/Y: ray length between two x (or y) grid lines.
    pub delta_dist: (f64, f64),
    /// The cell the ray starts in.
    pub start_cell: (i64, i64),
    /// sideDistX/Y before the first step.
    pub initial_side_dist: (f64, f64),
    /// Every cell entered, in order; the last one is the hit.
    pub steps: Vec<DdaStep>,
    /// Where the ray ended.
    pub hit: ColumnHit,
}

/// Every column's hit, plus the full trace of the column asked for.
#[derive(Debug, Clone, PartialEq)]
pub struct Cast {
    /// One hit per column: on maps with `Hz` heights, where the column's window of open rows
    /// closed (see [`crate::render::height_cast`]).
    pub columns: Vec<ColumnHit>,
    /// The step-by-step traversal of the traced column, when one was asked for.
    pub trace: Option<DdaTrace>,
    /// On maps with `Hz` heights, each column's draw list front to back (floors, ceilings and
    /// every vertical face with its rows); empty on flat maps, which are drawn from `columns`.
    pub heights: Vec<crate::render::height_cast::HeightColumn>,
}

/// Casts one ray per column of a `width`-column view; traces column `traced` step by step.
/// Doors count as shut.
#[must_use]
pub fn cast(map: &Map, camera: &Camera, width: usize, traced: Option<usize>) -> Cast {
    cast_with_doors(map, &DoorState::none(), camera, width, traced)
}

/// [`cast`] with doors open as far as `doors` says.
#[must_use]
pub fn cast_with_doors(
    map: &Map,
    doors: &DoorState,
    camera: &Camera,
    width: usize,
    traced: Option<usize>,
) -> Cast {
    let columns = (0..width)
        .map(|x| cast_ray_doors(map, doors, camera.pos, camera.ray_dir(x, width), |_| {}))
        .collect();
    let trace = traced
        .filter(|&x| x < width)
        .map(|x| trace_column_doors(map, doors, camera, x, width));
    Cast {
        columns,
        trace,
        heights: Vec::new(),
    }
}

/// Traces column `x` of `width`: every step, for debugging and the JSON `centre_trace`.
#[must_use]
pub fn trace_column(map: &Map, camera: &Camera, x: usize, width: usize) -> DdaTrace {
    trace_column_doors(map, &DoorState::none(), camera, x, width)
}

/// [`trace_column`] with doors open as far as `doors` says.
#[must_use]
pub fn trace_column_doors(
    map: &Map,
    doors: &DoorState,
    camera: &Camera,
    x: usize,
    width: usize,
) -> DdaTrace {
    let ray_dir = camera.ray_dir(x, width);
    let setup = Setup::new(camera.pos, ray_dir);
    let mut steps = Vec::new();
    let hit = cast_ray_doors(map, doors, camera.pos, ray_dir, |s| steps.push(s));
    DdaTrace {
        column: x,
        ray_dir,
        delta_dist: setup.delta,
        start_cell: setup.cell,
        initial_side_dist: setup.side_dist,
        steps,
        hit,
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::grid_map;

    fn map(grid: &str) -> Map {
        grid_map(grid)
    }

    fn room() -> Map {
        map("111111\n100001\n100001\n10N001\n100001\n111111\n")
    }

    fn approx(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn east_ray_from_cell_centre_hits_the_east_wall() {
        let m = room();
        let hit = cast_ray(&m, Vec2::new(2.5, 3.5), Vec2::new(1.0, 0.0), |_| {});
        assert_eq!((hit.cell, hit.side), ((5, 3), Side::X));
        assert!(approx(hit.perp_dist, 2.5), "{}", hit.perp_dist);
        assert!(approx(hit.wall_x, 0.5));
    }

    #[test]
    fn axis_aligned_rays_in_all_four_directions() {
        let m = room();
        let p = Vec2::new(2.25, 3.75);
        let cases = [
            (Vec2::new(1.0, 0.0), (5, 3), Side::X, 2.75, 0.75),
            (Vec2::new(-1.0, 0.0), (0, 3), Side::X, 1.25, 0.75),
            (Vec2::new(0.0, -1.0), (2, 0), Side::Y, 2.75, 0.25),
            (Vec2::new(0.0, 1.0), (2, 5), Side::Y, 1.25, 0.25),
        ];
        for (ray, cell, side, dist, wx) in cases {
            let hit = cast_ray(&m, p, ray, |_| {});
            assert_eq!((hit.cell, hit.side), (cell, side), "{ray:?}");
            assert!(
                approx(hit.perp_dist, dist) && approx(hit.wall_x, wx),
                "{ray:?}: {hit:?}"
            );
        }
    }

    #[test]
    fn zero_component_uses_the_finite_never_value() {
        let m = room();
        let mut steps = Vec::new();
        cast_ray(&m, Vec2::new(2.5, 3.5), Vec2::new(0.0, -1.0), |s| {
            steps.push(s)
        });
        assert_eq!(steps.len(), 3);
        assert!(steps
            .iter()
            .all(|s| s.side == Side::Y && approx(s.side_dist.0, 0.5 * NEVER)));
        assert_eq!(
            steps.iter().map(|s| s.cell).collect::<Vec<_>>(),
            [(2, 2), (2, 1), (2, 0)]
        );
    }

    #[test]
    fn ray_exactly_through_a_grid_corner_steps_y_first_on_ties() {
        let m = room();
        let mut steps = Vec::new();
        let hit = cast_ray(&m, Vec2::new(2.5, 3.5), Vec2::new(1.0, -1.0), |s| {
            steps.push(s)
        });
        let cells: Vec<_> = steps.iter().map(|s| (s.cell, s.side)).collect();
        assert_eq!(cells[0], ((2, 2), Side::Y));
        assert_eq!(cells[1], ((3, 2), Side::X));
        assert_eq!(hit.cell, (4, 0));
        assert_eq!(hit.side, Side::Y);
        assert!(approx(hit.perp_dist, 2.5));
        assert!(approx(hit.wall_x, 0.0));
    }

    #[test]
    fn ray_from_a_cell_edge_starts_with_zero_side_dist() {
        let m = room();
        let mut steps = Vec::new();
        let hit = cast_ray(&m, Vec2::new(3.0, 3.5), Vec2::new(-1.0, 0.0), |s| {
            steps.push(s)
        });
        assert!(approx(steps[0].side_dist.0, 1.0));
        assert_eq!(steps[0].cell, (2, 3));
        assert_eq!(hit.cell, (0, 3));
        assert!(approx(hit.perp_dist, 2.0));
    }

    #[test]
    fn diagonal_ray_hand_computed() {
        let m = room();
        let ray = Vec2::new(1.0, 0.5);
        let mut steps = Vec::new();
        let hit = cast_ray(&m, Vec2::new(1.5, 1.5), ray, |s| steps.push(s));
        // deltaDist = (1, 2); sideDist starts (0.5, 1.0).
        let expect = [
            ((2, 1), Side::X, (1.5, 1.0)),
            ((2, 2), Side::Y, (1.5, 3.0)),
            ((3, 2), Side::X, (2.5, 3.0)),
            ((4, 2), Side::X, (3.5, 3.0)),
            ((4, 3), Side::Y, (3.5, 5.0)),
            ((5, 3), Side::X, (4.5, 5.0)),
        ];
        assert_eq!(steps.len(), expect.len());
        for (s, (cell, side, sd)) in steps.iter().zip(expect) {
            assert_eq!((s.cell, s.side), (cell, side));
            assert!(
                approx(s.side_dist.0, sd.0) && approx(s.side_dist.1, sd.1),
                "{s:?}"
            );
        }
        assert!(approx(hit.perp_dist, 3.5));
        assert!(approx(hit.wall_x, 0.25));
    }

    #[test]
    fn trace_ends_at_the_hit_and_matches_cast() {
        let m = room();
        let cam = Camera::from_angle(Vec2::new(2.5, 3.5), 30.0, 66.0);
        let c = cast(&m, &cam, 40, Some(20));
        let t = c.trace.unwrap();
        assert_eq!(t.hit, c.columns[20]);
        assert_eq!(t.steps.last().unwrap().cell, t.hit.cell);
        assert_eq!(t.start_cell, (2, 3));
    }
}
