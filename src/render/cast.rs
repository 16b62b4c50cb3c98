//! The grid DDA for a camera: one ray per screen column, pure maths over a [`Map`] and a
//! [`Camera`], and the step-by-step trace of one column (each ray walks by `world::ray`).

use crate::camera::Camera;
use crate::map::Map;
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::ray::Setup;
pub use crate::world::ray::{cast_ray, cast_ray_doors, ColumnHit, DdaStep, Side, NEVER};

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
    /// closed (see `crate::render::height_cast`).
    pub columns: Vec<ColumnHit>,
    /// The step-by-step traversal of the traced column, when one was asked for.
    pub trace: Option<DdaTrace>,
    /// On maps with `Hz` heights, each column's draw list front to back (floors, ceilings and
    /// every vertical face with its rows); empty on flat maps, which are drawn from `columns`.
    pub heights: Vec<crate::render::height_column::HeightColumn>,
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
    let (trace, ()) = DdaTrace::record(x, camera.pos, ray_dir, |steps| {
        let hit = cast_ray_doors(map, doors, camera.pos, ray_dir, |s| steps.push(s));
        (hit, ())
    });
    trace
}

impl DdaTrace {
    /// Traces column `column`'s ray from `pos`: the set-up, then every step `walk` reports
    /// (`walk` is the caster's own walk, flat or through heights, with what else it returns),
    /// so the flat and the heights caster record a trace the same way.
    pub(crate) fn record<R>(
        column: usize,
        pos: Vec2,
        ray_dir: Vec2,
        walk: impl FnOnce(&mut Vec<DdaStep>) -> (ColumnHit, R),
    ) -> (Self, R) {
        let setup = Setup::new(pos, ray_dir);
        let mut steps = Vec::new();
        let (hit, rest) = walk(&mut steps);
        let trace = DdaTrace {
            column,
            ray_dir,
            delta_dist: setup.delta,
            start_cell: setup.cell,
            initial_side_dist: setup.side_dist,
            steps,
            hit,
        };
        (trace, rest)
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
