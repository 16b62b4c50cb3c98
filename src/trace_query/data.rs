//! The figure's data as JSON (`/trace.json`), for a page that draws the ray itself: the cells
//! the figure shows, the camera, and every number of Lode's derivation — `cameraX`, `rayDir`,
//! `deltaDist`, `step`, the first `sideDist`, each step's comparison and crossing, the hit,
//! `perp`, the line height, `wall_x` and the texture column; on maps with heights, how each
//! face the ray passes narrows the column's open window of rows (as the terminal's ray pane
//! says it). Numbers are the trace's own, at full precision.

use serde::Serialize;

use super::TracedRay;
use crate::map::{Cell, Map};
use crate::output::figure::frame::Frame;
use crate::render::cast::Side;
use crate::render::derivation::{Derivation, PerpFrom};
use crate::render::height_column::{Band, HeightColumn};
use crate::render::raster::{heading, texture_x, wall_span};
use crate::world::World;

/// A number as the figure and the ray pane print it; the page's `ray_text.js` prints the same.
pub use crate::render::derivation::num;

/// Everything the page's ray panel draws and writes.
#[derive(Debug, Serialize)]
pub struct TraceData {
    /// The address's query that reproduces this ray (`pos=…&angle=…&column=…&size=…`).
    pub address: String,
    /// The map's name as served.
    pub map: String,
    /// The cells around the ray (the figure's region).
    pub grid: Grid,
    /// The view's columns and rows in cells.
    pub size: [usize; 2],
    /// The screen column traced.
    pub column: usize,
    /// Camera position.
    pub pos: [f64; 2],
    /// Unit view direction.
    pub dir: [f64; 2],
    /// Camera plane (|plane| = tan(FOV/2)).
    pub plane: [f64; 2],
    /// Facing in degrees (0 east, 90 north).
    pub angle: f64,
    /// Horizontal field of view in degrees.
    pub fov: f64,
    /// `2x/w − 1`.
    pub camera_x: f64,
    /// `dir + plane·cameraX`.
    pub ray_dir: [f64; 2],
    /// `|1/rayDir|` per axis.
    pub delta_dist: [f64; 2],
    /// The cell the ray starts in.
    pub start_cell: [i64; 2],
    /// stepX/Y: −1 or +1.
    pub step: [i64; 2],
    /// How far the position is from the first grid line on each axis.
    pub gap: [f64; 2],
    /// sideDistX/Y before the first step.
    pub side_dist: [f64; 2],
    /// Every step: the comparison, the crossing it made and the cell it entered.
    pub steps: Vec<StepData>,
    /// Where the ray stopped.
    pub hit: HitData,
    /// The perpendicular distance and how it came out.
    pub perp: PerpData,
    /// Pixels per world unit at distance 1.
    pub focal: f64,
    /// The hit's line height in pixels.
    pub line_height: f64,
    /// The hit along its face (`posY + perp·rayDirY` or `posX + perp·rayDirX`).
    pub wall_along: f64,
    /// Its fraction in [0, 1).
    pub wall_x: f64,
    /// The texture column sampled.
    pub texture_x: usize,
    /// The texture's width in texels.
    pub texture_width: usize,
    /// On maps with heights: how each face narrowed the window of rows.
    pub heights: Option<HeightsData>,
}

/// The figure's cells, `x0..x0+width` × `y0..y0+height`, one letter each in `rows`: `#` a
/// wall, `.` a floor, `D` a door, space the void; on maps with heights each cell's floor and
/// ceiling (`null` where solid).
#[derive(Debug, Serialize)]
pub struct Grid {
    /// First column of cells shown.
    pub x0: i64,
    /// First row of cells shown.
    pub y0: i64,
    /// Columns of cells shown.
    pub width: usize,
    /// Rows of cells shown.
    pub height: usize,
    /// One string per row of cells, one letter per cell.
    pub rows: Vec<String>,
    /// On maps with heights: each cell's floor and ceiling.
    pub spans: Option<Vec<Vec<Option<[f64; 2]>>>>,
}

/// One DDA step.
#[derive(Debug, Serialize)]
pub struct StepData {
    /// From 1.
    pub index: usize,
    /// sideDistX/Y compared before the step.
    pub before: [f64; 2],
    /// The one that won (`x` when sideDistX < sideDistY, else `y`).
    pub side: Side,
    /// The ray length at the crossing (the winner's sideDist).
    pub crossing: f64,
    /// The point crossed.
    pub point: [f64; 2],
    /// The cell entered.
    pub cell: [i64; 2],
    /// sideDistX/Y after the step.
    pub after: [f64; 2],
}

/// The hit.
#[derive(Debug, Serialize)]
pub struct HitData {
    /// The cell hit.
    pub cell: [i64; 2],
    /// `wall N`, `door`, `void`.
    pub what: String,
    /// The grid line crossed into it.
    pub side: Side,
    /// The face met: `north`, `south`, `west`, `east` (of the hit cell), or `panel` (a door).
    pub face: &'static str,
    /// The wall texture used for that face: `NO`, `SO`, `WE`, `EA`.
    pub texture: &'static str,
    /// The point hit.
    pub point: [f64; 2],
}

/// `perp`: `sideDist − deltaDist` of the side crossed, or the distance to a door's panel.
#[derive(Debug, Serialize)]
pub struct PerpData {
    /// The perpendicular distance.
    pub value: f64,
    /// `grid` or `door`.
    pub from: &'static str,
    /// The crossed side's sideDist after the last step.
    pub side_dist: Option<f64>,
    /// The crossed side's deltaDist.
    pub delta_dist: Option<f64>,
    /// A door panel's line (its cell + 0.5).
    pub line: Option<f64>,
}

/// The column's window of open rows on a map with heights.
#[derive(Debug, Serialize)]
pub struct HeightsData {
    /// Pixel rows of the view (the window starts as all of them).
    pub rows: usize,
    /// Every vertical face the column drew, front to back, with the window before and after.
    pub faces: Vec<FaceData>,
    /// The cell where the window closed.
    pub closed: [i64; 2],
    /// The distance it closed at.
    pub closed_at: f64,
    /// The closing face's height span (the line is that tall), `null` when floors closed it.
    pub closing_dz: Option<f64>,
}

/// One face and how it narrowed the window.
#[derive(Debug, Serialize)]
pub struct FaceData {
    /// The cell whose solid part the face is.
    pub cell: [i64; 2],
    /// `wall`, `step` or `lintel`.
    pub kind: &'static str,
    /// The grid line crossed into the face.
    pub side: Side,
    /// Distance along the view direction to the face.
    pub perp_dist: f64,
    /// The heights it spans.
    pub z: [f64; 2],
    /// Pixel rows drawn, [top, bottom).
    pub rows: [usize; 2],
    /// The open window of rows before it.
    pub before: [usize; 2],
    /// The window after it.
    pub after: [usize; 2],
}

impl TracedRay {
    /// The data of this ray through `world` (the world it was cast in); `address` is the query
    /// that reproduces it.
    #[must_use]
    pub fn data(&self, world: &World, address: String) -> TraceData {
        let map = &world.map;
        let trace = &self.cast.trace;
        let d = Derivation::new(trace, &self.camera, self.size.0);
        let hit = &trace.hit;
        let focal = self.camera.focal_length(self.size.0);
        let heights = self
            .cast
            .heights
            .as_ref()
            .map(|(col, _)| heights(col, self.size.1 * 2));
        let line_height = match &heights {
            None => wall_span(d.perp, focal, self.size.1 * 2).height,
            Some(h) => h.closing_dz.map_or(0.0, |dz| dz * focal / d.perp.max(1e-9)),
        };
        let texture_width = world.wall_texture(hit.what, heading(hit)).width();
        let pair = |v: crate::vec2::Vec2| [v.x, v.y];
        TraceData {
            address,
            map: map.name.clone(),
            grid: grid(map, &Frame::around(&d, (0.0, 0.0))),
            size: [self.size.0, self.size.1],
            column: d.column,
            pos: pair(d.pos),
            dir: pair(d.dir),
            plane: pair(d.plane),
            angle: self.camera.heading_deg(),
            fov: self.camera.fov_deg(),
            camera_x: d.camera_x,
            ray_dir: pair(d.ray_dir),
            delta_dist: [d.delta_dist.0, d.delta_dist.1],
            start_cell: [d.start_cell.0, d.start_cell.1],
            step: [d.step.0, d.step.1],
            gap: [d.gap.0, d.gap.1],
            side_dist: [d.initial_side_dist.0, d.initial_side_dist.1],
            steps: d
                .choices
                .iter()
                .map(|c| StepData {
                    index: c.index,
                    before: [c.before.0, c.before.1],
                    side: c.side,
                    crossing: c.crossing(),
                    point: pair(d.point_at(c.crossing())),
                    cell: [c.cell.0, c.cell.1],
                    after: [c.after.0, c.after.1],
                })
                .collect(),
            hit: HitData {
                cell: [d.hit_cell.0, d.hit_cell.1],
                what: what(d.hit_what),
                side: d.hit_side,
                face: face(&d),
                texture: ["NO", "SO", "WE", "EA"][heading(hit)],
                point: pair(d.point_at(d.perp)),
            },
            perp: perp(&d),
            focal,
            line_height,
            wall_along: d.wall_along,
            wall_x: d.wall_x,
            texture_x: texture_x(hit, texture_width),
            texture_width,
            heights,
        }
    }
}

/// The cells of `frame`'s region.
fn grid(map: &Map, frame: &Frame) -> Grid {
    let (w, h) = (frame.max.0 - frame.min.0, frame.max.1 - frame.min.1);
    let cells = |f: &dyn Fn(i64, i64) -> char| -> Vec<String> {
        (frame.min.1..frame.max.1)
            .map(|j| (frame.min.0..frame.max.0).map(|i| f(i, j)).collect())
            .collect()
    };
    let rows = cells(&|i, j| match map.cell(i, j) {
        Cell::Void => ' ',
        Cell::Floor { .. } => '.',
        Cell::Wall(_) => '#',
        Cell::Door(_) => 'D',
    });
    let spans = map.has_heights().then(|| {
        (frame.min.1..frame.max.1)
            .map(|j| {
                (frame.min.0..frame.max.0)
                    .map(|i| map.span(i, j).map(|s| [s.floor, s.ceil]))
                    .collect()
            })
            .collect()
    });
    Grid {
        x0: frame.min.0,
        y0: frame.min.1,
        width: usize::try_from(w).unwrap_or(0),
        height: usize::try_from(h).unwrap_or(0),
        rows,
        spans,
    }
}

fn what(c: Cell) -> String {
    match c {
        Cell::Wall(n) => format!("wall {n}"),
        Cell::Void => "void".to_owned(),
        Cell::Floor { .. } => "floor".to_owned(),
        Cell::Door(_) => "door".to_owned(),
    }
}

/// The hit cell's face the ray met (map y grows southward).
fn face(d: &Derivation) -> &'static str {
    if matches!(d.perp_from, PerpFrom::DoorPanel { .. }) {
        return "panel";
    }
    match (d.hit_side, d.step) {
        (Side::X, (s, _)) if s > 0 => "west",
        (Side::X, _) => "east",
        (Side::Y, (_, s)) if s > 0 => "north",
        (Side::Y, _) => "south",
    }
}

fn perp(d: &Derivation) -> PerpData {
    match d.perp_from {
        PerpFrom::GridLine {
            side_dist,
            delta_dist,
            ..
        } => PerpData {
            value: d.perp,
            from: "grid",
            side_dist: Some(side_dist),
            delta_dist: Some(delta_dist),
            line: None,
        },
        PerpFrom::DoorPanel { line, .. } => PerpData {
            value: d.perp,
            from: "door",
            side_dist: None,
            delta_dist: None,
            line: Some(line),
        },
    }
}

/// The window of open rows, narrowed face by face as the column's draw list says: a band
/// reaching the window's top raises it, any other lowers its bottom.
fn heights(col: &HeightColumn, rows: usize) -> HeightsData {
    let faces = col
        .face_windows(col.first_window(rows))
        .into_iter()
        .map(|w| {
            let f = w.face;
            FaceData {
                cell: [f.cell.0, f.cell.1],
                kind: f.kind.as_str(),
                side: f.side,
                perp_dist: f.perp_dist,
                z: [f.z.0, f.z.1],
                rows: [f.rows.0, f.rows.1],
                before: [w.before.0, w.before.1],
                after: [w.after.0, w.after.1],
            }
        })
        .collect();
    let closing_dz = col.bands.iter().rev().find_map(|b| match b {
        Band::Face(f) if f.cell == col.closed.cell => Some(f.z.1 - f.z.0),
        _ => None,
    });
    HeightsData {
        rows,
        faces,
        closed: [col.closed.cell.0, col.closed.cell.1],
        closed_at: col.closed.perp_dist,
        closing_dz,
    }
}

impl TraceData {
    /// The data as one JSON document.
    #[must_use]
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("plain numbers and strings always serialise")
    }
}

#[cfg(test)]
mod tests {
    use super::super::TraceQuery;
    use crate::vec2::Vec2;
    use crate::world::World;

    #[test]
    fn north_from_the_start_the_data_has_lode_s_numbers() {
        let w = World::default_world();
        let mut q = TraceQuery::column(20);
        q.size = (40, 12);
        q.pos = Some(Vec2::new(15.5, 5.5));
        q.angle = Some(90.0);
        let data = q.trace(&w).unwrap().data(&w, "a".into());
        assert_eq!(data.camera_x, 0.0);
        assert_eq!(data.step[1], -1);
        let crossings: Vec<f64> = data.steps.iter().map(|s| s.crossing).collect();
        assert_eq!(crossings, [0.5, 1.5, 2.5, 3.5, 4.5]);
        assert_eq!(data.perp.value, 4.5);
        assert_eq!(data.hit.face, "south");
        assert_eq!(data.hit.cell, [15, 0]);
        assert_eq!(data.grid.rows.len(), data.grid.height);
        assert!(data.heights.is_none());
        let json = data.to_json();
        assert!(json.contains("\"side\":\"y\""), "{json}");
    }
}
