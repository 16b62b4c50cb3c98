//! Lode's derivation of one traced column, number by number: `cameraX`, `rayDir`, `deltaDist`,
//! `stepX/Y` and the first `sideDist`s from the position's fraction, the comparison behind every
//! step, and `perp`. Read from a [`DdaTrace`] (the same trace the JSON prints) and the camera
//! that cast it, so the ray pane and the `halfcast trace` figure can never disagree with it.

use crate::camera::Camera;
use crate::map::Cell;
use crate::render::cast::{DdaTrace, Side};
use crate::vec2::Vec2;

/// One DDA step and why it went where it went.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Choice {
    /// Step number, from 1.
    pub index: usize,
    /// sideDistX/Y compared before the step.
    pub before: (f64, f64),
    /// The axis the comparison chose: x when sideDistX < sideDistY, else y (ties go to y).
    pub side: Side,
    /// The cell entered.
    pub cell: (i64, i64),
    /// sideDistX/Y after the step (the chosen one grew by its deltaDist).
    pub after: (f64, f64),
}

impl Choice {
    /// The chosen axis's sideDist before the step: the ray length at this crossing.
    #[must_use]
    pub fn crossing(&self) -> f64 {
        pick(self.side, self.before)
    }
}

/// How `perp` was found at the hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PerpFrom {
    /// A wall entered across a grid line: `perp = sideDist − deltaDist` of the side crossed.
    GridLine {
        /// The side crossed into the wall.
        side: Side,
        /// That axis's sideDist after the last step.
        side_dist: f64,
        /// That axis's deltaDist.
        delta_dist: f64,
    },
    /// A door's panel, on the mid-line of its cell: `perp = (mapX + 0.5 − posX) / rayDirX`
    /// (or y).
    DoorPanel {
        /// Which mid-line (x: a vertical panel).
        side: Side,
        /// The panel's coordinate (cell + 0.5).
        line: f64,
    },
}

/// The parts of a derivation's setup as a reader goes through them: `cameraX`; `rayDir`;
/// `deltaDist` with the start cell; X's `step` and first `sideDist`; Y's. The ray pane scrolls
/// into the setup a part at a time.
pub const SETUP_PARTS: usize = 5;

/// Every number of one column's derivation, in the order Lode's tutorial meets them.
#[derive(Debug, Clone, PartialEq)]
pub struct Derivation {
    /// The screen column and the view's width in columns.
    pub column: usize,
    /// Columns in the view (w in `cameraX = 2x/w − 1`).
    pub width: usize,
    /// `2x/w − 1`: −1 at the left edge, +1 at the right.
    pub camera_x: f64,
    /// The camera's position, view direction and plane.
    pub pos: Vec2,
    /// Unit view direction.
    pub dir: Vec2,
    /// Camera plane (|plane| = tan(FOV/2)).
    pub plane: Vec2,
    /// `dir + plane·cameraX`, as the trace holds it.
    pub ray_dir: Vec2,
    /// `|1/rayDir|` per axis (1e30 for a zero component).
    pub delta_dist: (f64, f64),
    /// The cell the position is in.
    pub start_cell: (i64, i64),
    /// stepX/Y: −1 or +1.
    pub step: (i64, i64),
    /// How far (in cells) the position is from the first grid line the ray meets on each axis:
    /// `posX − mapX` stepping west, `mapX + 1 − posX` stepping east.
    pub gap: (f64, f64),
    /// sideDistX/Y before the first step (`gap · deltaDist`, from the trace).
    pub initial_side_dist: (f64, f64),
    /// Every step with its comparison.
    pub choices: Vec<Choice>,
    /// The cell that stopped the ray, what it is and the side crossed into it.
    pub hit_cell: (i64, i64),
    /// What the hit cell is.
    pub hit_what: Cell,
    /// Side crossed into the hit cell.
    pub hit_side: Side,
    /// How `perp` came out.
    pub perp_from: PerpFrom,
    /// Perpendicular distance to the hit (no fisheye).
    pub perp: f64,
    /// The hit along its face: `posY + perp·rayDirY` (side x) or `posX + perp·rayDirX` (side y).
    pub wall_along: f64,
    /// Its fraction in [0, 1), the texture coordinate.
    pub wall_x: f64,
}

fn pick(side: Side, v: (f64, f64)) -> f64 {
    match side {
        Side::X => v.0,
        Side::Y => v.1,
    }
}

impl Derivation {
    /// The derivation of `trace`, cast by `camera` in a view `width` columns wide.
    #[must_use]
    pub fn new(trace: &DdaTrace, camera: &Camera, width: usize) -> Self {
        let ray = trace.ray_dir;
        let pos = camera.pos;
        let step = (
            if ray.x < 0.0 { -1 } else { 1 },
            if ray.y < 0.0 { -1 } else { 1 },
        );
        let gap_of = |s: i64, p: f64, m: i64| {
            if s < 0 {
                p - m as f64
            } else {
                m as f64 + 1.0 - p
            }
        };
        let gap = (
            gap_of(step.0, pos.x, trace.start_cell.0),
            gap_of(step.1, pos.y, trace.start_cell.1),
        );
        let mut before = trace.initial_side_dist;
        let choices = trace
            .steps
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let c = Choice {
                    index: i + 1,
                    before,
                    side: s.side,
                    cell: s.cell,
                    after: s.side_dist,
                };
                before = s.side_dist;
                c
            })
            .collect();
        let hit = &trace.hit;
        let perp_from = match hit.what {
            Cell::Door(_) => PerpFrom::DoorPanel {
                side: hit.side,
                line: pick(hit.side, (hit.cell.0 as f64, hit.cell.1 as f64)) + 0.5,
            },
            _ => PerpFrom::GridLine {
                side: hit.side,
                side_dist: trace
                    .steps
                    .last()
                    .map_or(pick(hit.side, trace.initial_side_dist), |s| {
                        pick(hit.side, s.side_dist)
                    }),
                delta_dist: pick(hit.side, trace.delta_dist),
            },
        };
        let wall_along = match hit.side {
            Side::X => pos.y + hit.perp_dist * ray.y,
            Side::Y => pos.x + hit.perp_dist * ray.x,
        };
        Self {
            column: trace.column,
            width,
            camera_x: 2.0 * trace.column as f64 / width.max(1) as f64 - 1.0,
            pos,
            dir: camera.dir,
            plane: camera.plane,
            ray_dir: ray,
            delta_dist: trace.delta_dist,
            start_cell: trace.start_cell,
            step,
            gap,
            initial_side_dist: trace.initial_side_dist,
            choices,
            hit_cell: hit.cell,
            hit_what: hit.what,
            hit_side: hit.side,
            perp_from,
            perp: hit.perp_dist,
            wall_along,
            wall_x: hit.wall_x,
        }
    }

    /// The ray's point at ray length `t` (sideDist units: `pos + rayDir·t`).
    #[must_use]
    pub fn point_at(&self, t: f64) -> Vec2 {
        self.pos + self.ray_dir * t
    }
}

/// A number as the pane and the figure print it: 2 decimals, or `1e30`-style for the huge
/// values a zero ray component gives (so a learner sees Lode's 1e30, not a made-up infinity).
#[must_use]
pub fn num(v: f64) -> String {
    num_with(v, 2)
}

/// [`num`] with `decimals` decimals.
#[must_use]
pub fn num_with(v: f64, decimals: usize) -> String {
    if v.abs() >= 1e6 {
        return format!("{v:.0e}");
    }
    let s = format!("{v:.decimals$}");
    // -0.00 reads as a sign error to a learner.
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_owned()
    } else {
        s
    }
}

/// Two sideDists printed so their order shows: 2 decimals, more (up to 6) when 2 would print
/// them equal although they differ; and the sign between them (`<`, `>` or `=`).
#[must_use]
pub fn compared(a: f64, b: f64) -> (String, &'static str, String) {
    let sign = if a < b {
        "<"
    } else if a > b {
        ">"
    } else {
        "="
    };
    let mut d = 2;
    while sign != "=" && d < 6 && num_with(a, d) == num_with(b, d) {
        d += 1;
    }
    (num_with(a, d), sign, num_with(b, d))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::grid_map;
    use crate::render::cast::trace_column;

    #[test]
    fn the_numbers_of_a_hand_worked_ray() {
        // From (1.5, 1.5) along (1, 0.5): deltaDist (1, 2), sideDist starts (0.5, 1.0).
        let m = grid_map("111111\n100001\n100001\n1N0001\n100001\n111111\n");
        let cam = Camera {
            pos: Vec2::new(1.5, 1.5),
            dir: Vec2::new(1.0, 0.5),
            plane: Vec2::new(0.0, 0.0),
        };
        let t = trace_column(&m, &cam, 1, 2);
        let d = Derivation::new(&t, &cam, 2);
        assert_eq!(d.camera_x, 0.0);
        assert_eq!((d.step, d.gap), ((1, 1), (0.5, 0.5)));
        assert_eq!(d.initial_side_dist, (0.5, 1.0));
        let c = &d.choices;
        assert_eq!(
            (c[0].before, c[0].side, c[0].cell),
            ((0.5, 1.0), Side::X, (2, 1))
        );
        assert_eq!((c[1].before, c[1].side), ((1.5, 1.0), Side::Y));
        assert_eq!(c[1].crossing(), 1.0);
        assert_eq!(
            d.perp_from,
            PerpFrom::GridLine {
                side: Side::X,
                side_dist: 4.5,
                delta_dist: 1.0
            }
        );
        assert_eq!(d.perp, 3.5);
        assert_eq!((d.wall_along, d.wall_x), (3.25, 0.25));
        assert_eq!(d.point_at(d.perp), Vec2::new(5.0, 3.25));
    }

    #[test]
    fn numbers_print_short_and_ties_and_near_ties_show() {
        assert_eq!(num(1e30), "1e30");
        assert_eq!(num(5e29), "5e29");
        assert_eq!(num(-0.001), "0.00");
        assert_eq!(num(2.876), "2.88");
        assert_eq!(compared(2.88, 0.51), ("2.88".into(), ">", "0.51".into()));
        assert_eq!(compared(1.5, 1.5), ("1.50".into(), "=", "1.50".into()));
        assert_eq!(
            compared(1.0001, 1.0003),
            ("1.0001".into(), "<", "1.0003".into())
        );
    }
}
