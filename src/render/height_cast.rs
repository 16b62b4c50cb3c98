//! Casting on maps with `Hz` heights (issue 14): each column's ray keeps walking past steps and
//! lintels, and the column keeps the window of rows still open front to back (Build's
//! umost/dmost, Stephens' clipping) until a solid wall — or the cells' own floors and ceilings —
//! close it. Pure: the result is a draw list per column that [`crate::render::height_raster`] paints.
//!
//! Geometry. A walkable cell is open air between its floor and ceiling ([`Map::span`]); walls
//! and the void are solid at every height. Pixel row `y` of a column shows, at distance `t` along
//! the view direction, the height `z = eye − (y + 0.5 − horizon)·t/focal` (the pixel-centre rule
//! the flat renderer uses). Inside a cell the ray's height is linear in `t`, so a row hits the
//! cell's floor (or ceiling) exactly when its height where the ray leaves the cell is at or below
//! the floor (above the ceiling); where it enters a neighbour below that neighbour's floor it
//! hits a **step** face, above its ceiling a **lintel** face, and a solid neighbour is a **wall**.
//!
//! Which zone a face belongs to: the solid part of the cell being entered — a step face is the
//! side of the neighbour's raised floor, a lintel the side of the neighbour's lowered ceiling —
//! so the neighbour's `Wz` paints it (otherwise `NO`/`SO`/`WE`/`EA` by heading, as walls).

use crate::camera::Camera;
use crate::map::{Cell, Map, Span};
use crate::render::cast::{Cast, DdaTrace};
pub use crate::render::height_column::{
    Band, FaceKind, FaceSpan, FlatSpan, HeightColumn, WindowClosed,
};
use crate::render::view::View;
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::ray::{door_hit, ColumnHit, DdaStep, Setup, Side};

/// The vertical projection shared by every column of a frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// The eye's height in the world ([`View::eye`]).
    pub eye: f64,
    /// Pixels per world unit at distance 1.
    pub focal: f64,
    /// The horizon's row (pitch moves it).
    pub horizon: f64,
    /// Screen height in pixels.
    pub height: usize,
}

impl Projection {
    /// The projection of `view` on a `w` × `h`-pixel screen seen through `camera`.
    #[must_use]
    pub fn new(camera: &Camera, view: &View, w: usize, h: usize) -> Self {
        Self::with_pixel_height(camera, view, (w, h), 1.0)
    }

    /// [`Projection::new`] on a screen of `size` pixels each `pixel_height` times as tall as
    /// wide (a glyph sub-grid's, [`crate::Glyphs::pixel_height`]): the vertical focal length
    /// is divided by it, so walls stay square on screen.
    #[must_use]
    pub fn with_pixel_height(
        camera: &Camera,
        view: &View,
        size: (usize, usize),
        pixel_height: f64,
    ) -> Self {
        let (w, h) = size;
        let view = view.clamped();
        let focal = camera.focal_length(w) / pixel_height;
        Self {
            eye: view.eye(),
            focal,
            horizon: view.horizon(focal, h),
            height: h,
        }
    }

    /// The first row whose pixel centre, at distance `t`, is at or below height `z` (rows above
    /// it see higher): ⌈horizon − (z − eye)·focal/t − 0.5⌉, within [0, height].
    #[must_use]
    #[inline]
    pub fn row_at(&self, z: f64, t: f64) -> usize {
        let edge = self.horizon - (z - self.eye) * self.focal / t.max(1e-9) - 0.5;
        // ⌈edge⌉ without a libm call, within [0, height] (NaN reads as 0).
        let e = edge.clamp(0.0, self.height as f64);
        let r = e as usize;
        if (r as f64) < e {
            r + 1
        } else {
            r
        }
    }
}

/// Casts every column of a `width`-column view on an `Hz` map; traces column `traced`.
/// `columns` hold where each window closed, `heights` each column's draw list.
#[must_use]
pub fn cast_heights(
    map: &Map,
    doors: &DoorState,
    camera: &Camera,
    proj: &Projection,
    width: usize,
    traced: Option<usize>,
) -> Cast {
    let mut columns = Vec::with_capacity(width);
    let mut heights = Vec::with_capacity(width);
    let mut trace = None;
    for x in 0..width {
        if traced == Some(x) {
            let (t, col) = trace_column_heights(map, doors, camera, proj, x, width);
            columns.push(t.hit);
            heights.push(col);
            trace = Some(t);
        } else {
            let ray = camera.ray_dir(x, width);
            let (hit, col) = cast_column(map, doors, camera.pos, ray, proj, |_| {});
            columns.push(hit);
            heights.push(col);
        }
    }
    Cast {
        columns,
        trace,
        heights,
    }
}

/// Traces column `x` of `width` on an `Hz` map: its DDA steps and its draw list (what
/// [`cast_heights`] keeps for its traced column).
#[must_use]
pub fn trace_column_heights(
    map: &Map,
    doors: &DoorState,
    camera: &Camera,
    proj: &Projection,
    x: usize,
    width: usize,
) -> (DdaTrace, HeightColumn) {
    let ray = camera.ray_dir(x, width);
    DdaTrace::record(x, camera.pos, ray, |steps| {
        cast_column(map, doors, camera.pos, ray, proj, |s| steps.push(s))
    })
}

/// The open window of one column, narrowed front to back.
struct Window {
    top: usize,
    bottom: usize,
    bands: Vec<Band>,
}

impl Window {
    fn is_closed(&self) -> bool {
        self.top >= self.bottom
    }

    /// Draws the cell's ceiling on rows above `ceil_row` and its floor from `floor_row` down
    /// (rows still open only), narrowing the window to what lies between.
    fn flats(&mut self, base: FlatSpan, span: Span, ceil_row: usize, floor_row: usize) {
        let c_end = ceil_row.min(self.bottom);
        if c_end > self.top {
            self.bands.push(Band::Flat(FlatSpan {
                ceiling: true,
                z: span.ceil,
                rows: (self.top, c_end),
                ..base
            }));
            self.top = c_end;
        }
        let f_start = floor_row.max(self.top);
        if f_start < self.bottom {
            self.bands.push(Band::Flat(FlatSpan {
                ceiling: false,
                z: span.floor,
                rows: (f_start, self.bottom),
                ..base
            }));
            self.bottom = f_start;
        }
    }

    /// Draws a face on the open rows of [from, to) and narrows the window by them; from must be
    /// the window's top or to its bottom.
    fn face(&mut self, face: FaceSpan, from: usize, to: usize) {
        let (a, b) = (from.max(self.top), to.min(self.bottom));
        if a >= b {
            return;
        }
        self.bands.push(Band::Face(FaceSpan {
            rows: (a, b),
            ..face
        }));
        if a == self.top {
            self.top = b;
        } else {
            self.bottom = a;
        }
    }
    /// The door in the cell the ray is in, hit at `hit` after entering at `t_in`: the cell's
    /// ceiling and floor up to the door, then the door's panel on every row still open.
    #[inline]
    fn door(&mut self, flat: FlatSpan, span: Span, hit: &ColumnHit, proj: &Projection, t_in: f64) {
        let t = hit.perp_dist;
        self.flats(
            FlatSpan {
                dist: (t_in, t),
                ..flat
            },
            span,
            proj.row_at(span.ceil, t),
            proj.row_at(span.floor, t),
        );
        let face = FaceSpan {
            cell: hit.cell,
            what: hit.what,
            side: hit.side,
            perp_dist: t,
            wall_x: hit.wall_x,
            kind: FaceKind::Wall,
            z: (span.floor, span.ceil),
            rows: (0, 0),
        };
        let (top, bottom) = (self.top, self.bottom);
        self.face(face, top, bottom);
    }

    /// Crossing from a cell of `span` into one of `next`: the lintel where the ceiling comes
    /// down, from the window's top, and the step where the floor goes up, to its bottom.
    #[inline]
    fn crossing(&mut self, face: FaceSpan, span: Span, next: Span, proj: &Projection) {
        let t = face.perp_dist;
        let top = self.top;
        self.face(
            FaceSpan {
                kind: FaceKind::Lintel,
                z: (next.ceil, span.ceil),
                ..face
            },
            top,
            proj.row_at(next.ceil, t),
        );
        let bottom = self.bottom;
        self.face(
            FaceSpan {
                kind: FaceKind::Step,
                z: (span.floor, next.floor),
                ..face
            },
            proj.row_at(next.floor, t),
            bottom,
        );
    }
}

/// Where a ray crossing at distance `t` meets its face, along the face in [0, 1).
fn along(pos: Vec2, ray: Vec2, side: Side, t: f64) -> f64 {
    let a = match side {
        Side::X => pos.y + t * ray.y,
        Side::Y => pos.x + t * ray.x,
    };
    a - a.floor()
}

fn zone_of(cell: Cell) -> u8 {
    match cell {
        Cell::Floor { zone } => zone,
        _ => 0,
    }
}

/// Walks one column's ray through the heights until its window closes; reports each DDA step.
pub fn cast_column(
    map: &Map,
    doors: &DoorState,
    pos: Vec2,
    ray: Vec2,
    proj: &Projection,
    mut on_step: impl FnMut(DdaStep),
) -> (ColumnHit, HeightColumn) {
    let Setup {
        mut cell,
        delta,
        step,
        mut side_dist,
    } = Setup::new(pos, ray);
    let mut win = Window {
        top: 0,
        bottom: proj.height,
        bands: Vec::with_capacity(12),
    };
    let mut what = map.cell(cell.0, cell.1);
    let mut span = map.span(cell.0, cell.1).unwrap_or(Span::FLAT);
    let mut t_in = 0.0;
    loop {
        let t_exit = side_dist.0.min(side_dist.1);
        let flat = FlatSpan {
            cell,
            zone: zone_of(what),
            ceiling: false,
            z: span.floor,
            dist: (t_in, t_exit),
            rows: (0, 0),
        };
        if let Cell::Door(plane) = what {
            if let Some(hit) = door_hit(doors, plane, cell, pos, ray, t_in, t_exit) {
                win.door(flat, span, &hit, proj, t_in);
                let t = hit.perp_dist;
                return finish(hit, win, cell, t);
            }
        }
        win.flats(
            flat,
            span,
            proj.row_at(span.ceil, t_exit),
            proj.row_at(span.floor, t_exit),
        );
        // Step into the next cell.
        let side = crate::world::ray::advance(&mut side_dist, delta, &mut cell, step);
        on_step(DdaStep {
            cell,
            side,
            side_dist,
        });
        let t = t_exit;
        let next = map.cell(cell.0, cell.1);
        let hit = ColumnHit {
            cell,
            what: next,
            side,
            perp_dist: t,
            wall_x: along(pos, ray, side, t),
            ray_dir: ray,
        };
        if win.is_closed() {
            return finish(hit, win, cell, t);
        }
        let face = FaceSpan {
            cell,
            what: next,
            side,
            perp_dist: t,
            wall_x: hit.wall_x,
            kind: FaceKind::Wall,
            z: (span.floor, span.ceil),
            rows: (0, 0),
        };
        let Some(next_span) = map.span(cell.0, cell.1) else {
            let (top, bottom) = (win.top, win.bottom);
            win.face(face, top, bottom);
            return finish(hit, win, cell, t);
        };
        win.crossing(face, span, next_span, proj);
        if win.is_closed() {
            return finish(hit, win, cell, t);
        }
        what = next;
        span = next_span;
        t_in = t;
    }
}

fn finish(hit: ColumnHit, win: Window, cell: (i64, i64), t: f64) -> (ColumnHit, HeightColumn) {
    (
        hit,
        HeightColumn {
            bands: win.bands,
            closed: WindowClosed { cell, perp_dist: t },
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::parse_map;

    fn map(extra: &str, grid: &str) -> Map {
        let text = format!("NO n\nSO s\nWE w\nEA e\nF 1,2,3\nC 4,5,6\n{extra}{grid}");
        parse_map("t.cub", text.as_bytes()).unwrap()
    }

    /// Looking east along row 1 from (1.5, 1.5), 90° FOV, a 41-pixel-high screen.
    fn column(m: &Map, eye: f64) -> (ColumnHit, HeightColumn) {
        let cam = Camera::from_angle(Vec2::new(1.5, 1.5), 0.0, 90.0);
        let proj = Projection {
            eye,
            focal: 20.0,
            horizon: 20.5,
            height: 41,
        };
        cast_column(m, &DoorState::none(), cam.pos, cam.dir, &proj, |_| {})
    }

    fn covers_every_row_once(col: &HeightColumn, h: usize) {
        let mut seen = vec![0; h];
        for b in &col.bands {
            let (a, z) = b.rows();
            assert!(a < z, "{b:?}");
            for s in &mut seen[a..z] {
                *s += 1;
            }
        }
        assert!(seen.iter().all(|&n| n == 1), "{seen:?} {:?}", col.bands);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

        /// Every row of every column is in exactly one band, whatever the heights, pose and eye
        /// (even an eye outside its cell's open span), and faces come front to back.
        #[test]
        fn every_row_is_drawn_exactly_once(
            cells in proptest::collection::vec(0usize..5, 36),
            spans in proptest::collection::vec((-2.0f64..2.0, 0.1f64..3.0), 3),
            pos in (1.01f64..6.99, 1.01f64..6.99),
            angle in -180.0f64..180.0,
            eye in -3.0f64..5.0,
            horizon in -40.0f64..80.0,
            height in 1usize..70,
        ) {
            let mut header = String::new();
            for (k, (f, h)) in spans.iter().enumerate() {
                header += &format!("H{} {f} {}\n", (b'a' + k as u8) as char, f + h);
            }
            let mut grid = String::from("111111111\n");
            for j in 0..6 {
                grid.push('1');
                for i in 0..6 {
                    grid.push(match cells[j * 6 + i] {
                        0 => '0',
                        1 => '1',
                        k => (b'a' + k as u8 - 2) as char,
                    });
                }
                grid += "1\n";
            }
            grid += "1N1111111\n111111111\n";
            let m = map(&header, &grid);
            let cam = Camera::from_angle(Vec2::new(pos.0, pos.1), angle, 70.0);
            let proj = Projection { eye, focal: 30.0, horizon, height };
            for x in [0, 13, 30, 59] {
                let ray = cam.ray_dir(x, 60);
                let (_, col) = cast_column(&m, &DoorState::none(), cam.pos, ray, &proj, |_| {});
                covers_every_row_once(&col, height);
                let d: Vec<f64> = col.faces().map(|f| f.perp_dist).collect();
                proptest::prop_assert!(d.windows(2).all(|w| w[0] <= w[1]), "{d:?}");
            }
        }
    }

    #[test]
    fn a_step_up_is_drawn_and_the_wall_behind_shows_above_it() {
        // Cell (3,1) is a 0.5 step; the wall is at x = 6.
        let m = map("Ha 0.5 1\n", "1111111\n1N0a001\n1111111\n");
        let (hit, col) = column(&m, 0.5);
        covers_every_row_once(&col, 41);
        let faces: Vec<_> = col.faces().collect();
        assert_eq!(faces.len(), 2, "{faces:?}");
        assert_eq!((faces[0].kind, faces[0].cell), (FaceKind::Step, (3, 1)));
        assert_eq!(faces[0].z, (0.0, 0.5));
        // At distance 1.5 a step up to the eye's height starts at the horizon (row 20's centre).
        assert_eq!(faces[0].rows, (20, 27));
        // Over the step: the far wall between the ceilings and the step's top.
        assert_eq!((faces[1].kind, faces[1].cell), (FaceKind::Wall, (6, 1)));
        assert_eq!(faces[1].rows, (18, 20));
        assert_eq!(hit.cell, (6, 1));
    }

    #[test]
    fn a_lintel_and_a_step_frame_a_window() {
        let m = map("Hw 0.25 0.75\n", "111111\n1N0w01\n111111\n");
        let (_, col) = column(&m, 0.5);
        covers_every_row_once(&col, 41);
        let kinds: Vec<_> = col.faces().map(|f| (f.kind, f.cell)).collect();
        assert_eq!(
            &kinds[..2],
            &[(FaceKind::Lintel, (3, 1)), (FaceKind::Step, (3, 1))]
        );
    }

    #[test]
    fn a_flat_map_draws_the_flat_renderers_wall_rows() {
        let m = map("", "111111\n1N0001\n111111\n");
        let (hit, col) = column(&m, 0.5);
        covers_every_row_once(&col, 41);
        let wall = col.faces().next().unwrap();
        let flat = crate::render::raster::wall_span_at(hit.perp_dist, 20.0, 41, 20.5, 0.5);
        assert_eq!(wall.rows, flat.rows);
        assert_eq!(hit.cell, (5, 1));
    }

    #[test]
    fn looking_down_into_a_pit_the_window_closes_on_floors() {
        let m = map("Hp -1 1\n", "1111111\n1N0ppp1\n1111111\n");
        let (_, col) = column(&m, 0.5);
        covers_every_row_once(&col, 41);
        // The pit's far wall shows below the rim's floor line: more wall rows than a flat room.
        let wall = col.faces().last().unwrap();
        assert_eq!(wall.kind, FaceKind::Wall);
        assert_eq!(wall.z, (-1.0, 1.0));
    }
}
