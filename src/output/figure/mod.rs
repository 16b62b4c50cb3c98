//! Figures of one column's DDA traversal (`halfcast trace`, the game's figure key): a small
//! drawing model ([`drawing`]) built once from the trace by [`plan`] (and [`side_view`] on maps
//! with heights), written as SVG ([`svg`]) or painted for a PNG ([`raster`], with the project's
//! own bitmap [`font`]). The numbers come from [`Derivation`], the same trace the JSON prints.

mod crossings;
pub mod drawing;
pub mod font;
pub mod frame;
pub mod palette;
pub mod plan;
pub mod raster;
pub mod side_view;
pub mod svg;

use crate::camera::Camera;
use crate::map::Map;
use crate::render::cast::DdaTrace;
use crate::render::derivation::{num, Derivation};
use crate::render::height_cast::{HeightColumn, Projection};
use drawing::{Anchor, Drawing, Stroke};
use palette::{
    BACKGROUND, HIT_CELL, PERP, PLANE, RAY, TEXT, TEXT_SIZE, TITLE, VISITED, X_SIDE, Y_SIDE,
};

/// Everything a figure of one column shows.
#[derive(Debug, Clone, Copy)]
pub struct TraceFigure<'a> {
    /// The map the ray went through.
    pub map: &'a Map,
    /// The camera that cast it.
    pub camera: &'a Camera,
    /// Columns in the view (for `cameraX = 2x/w − 1`).
    pub width: usize,
    /// The column's trace (as the JSON prints it).
    pub trace: &'a DdaTrace,
    /// On maps with heights: the column's draw list and the frame's projection.
    pub heights: Option<(&'a HeightColumn, &'a Projection)>,
}

const MARGIN: f64 = 16.0;
const LINE: f64 = 18.0;

impl TraceFigure<'_> {
    /// The figure as a drawing (for either back-end).
    #[must_use]
    pub fn drawing(&self) -> Drawing {
        let d = Derivation::new(self.trace, self.camera, self.width);
        let plan_origin = (MARGIN + 36.0, 112.0);
        let frame = frame::Frame::around(&d, plan_origin);
        let (pw, ph) = frame.size();
        let notes = notes(&d);
        // Wide enough for the plan and for every line of text in the PNG font (2 px per font
        // pixel at the text size: 8 px a character; a 14 px monospace SVG font: about 8.4).
        let longest = notes.iter().map(|l| l.chars().count()).max().unwrap_or(0) as f64;
        let width = (pw + plan_origin.0 + MARGIN + 24.0)
            .max(longest * 8.6 + 2.0 * MARGIN)
            .max(720.0)
            .ceil();
        let text_top = plan_origin.1 + ph + 30.0;
        let mut height = text_top + notes.len() as f64 * LINE + MARGIN;
        let side_top = height + 24.0;
        if self.heights.is_some() {
            height = side_top + side_view::HEIGHT + side_view::LABELS + MARGIN;
        }
        let mut out = Drawing::new(width, height.ceil(), BACKGROUND);
        out.text(
            (MARGIN, MARGIN + TITLE),
            format!("halfcast trace: column {} of {}", d.column, d.width),
            TITLE,
            TEXT,
            Anchor::Start,
        );
        out.text(
            (MARGIN, MARGIN + TITLE + 22.0),
            format!(
                "pos ({}, {})   angle {} deg   FOV {} deg",
                num(d.pos.x),
                num(d.pos.y),
                num(self.camera.heading_deg()),
                num(self.camera.fov_deg())
            ),
            TEXT_SIZE,
            TEXT,
            Anchor::Start,
        );
        legend(&mut out, MARGIN + TITLE + 46.0);
        plan::draw(&mut out, self.map, &d, &frame);
        for (k, line) in notes.iter().enumerate() {
            out.text(
                (MARGIN, text_top + k as f64 * LINE),
                line.clone(),
                TEXT_SIZE,
                TEXT,
                Anchor::Start,
            );
        }
        if let Some((col, proj)) = self.heights {
            side_view::draw(
                &mut out,
                self.map,
                &d,
                col,
                proj,
                (MARGIN, side_top),
                width - 2.0 * MARGIN,
            );
        }
        out
    }

    /// The figure as an SVG document.
    #[must_use]
    pub fn to_svg(&self) -> String {
        svg::to_svg(&self.drawing())
    }

    /// The figure painted into a framebuffer (`to_png` gives the PNG file).
    #[must_use]
    pub fn to_framebuffer(&self) -> crate::render::Framebuffer {
        raster::to_framebuffer(&self.drawing())
    }
}

/// The derivation's key numbers, one line each, under the top view.
fn notes(d: &Derivation) -> Vec<String> {
    let a = match d.hit_side {
        crate::render::cast::Side::X => "X",
        crate::render::cast::Side::Y => "Y",
    };
    let perp = match d.perp_from {
        crate::render::derivation::PerpFrom::GridLine {
            side_dist,
            delta_dist,
            ..
        } => format!(
            "perp = sideDist{a} − deltaDist{a} = {} − {} = {}",
            num(side_dist),
            num(delta_dist),
            num(d.perp)
        ),
        crate::render::derivation::PerpFrom::DoorPanel { line, .. } => {
            format!(
                "perp = distance to the door panel at {} = {}",
                num(line),
                num(d.perp)
            )
        }
    };
    let sign = |s: i64| if s < 0 { "−1" } else { "+1" };
    vec![
        format!(
            "cameraX = 2·{}/{} − 1 = {}    rayDir = dir + plane·cameraX = ({}, {})",
            d.column,
            d.width,
            num(d.camera_x),
            num(d.ray_dir.x),
            num(d.ray_dir.y)
        ),
        format!(
            "deltaDist = |1/rayDir| = ({}, {})    step ({}, {})    first sideDist ({}, {})",
            num(d.delta_dist.0),
            num(d.delta_dist.1),
            sign(d.step.0),
            sign(d.step.1),
            num(d.initial_side_dist.0),
            num(d.initial_side_dist.1)
        ),
        format!(
            "{} steps; hit ({},{}) side {}: {perp}    wall_x {}",
            d.choices.len(),
            d.hit_cell.0,
            d.hit_cell.1,
            d.hit_side.as_str(),
            num(d.wall_x)
        ),
    ]
}

fn legend(out: &mut Drawing, y: f64) {
    let mut x = MARGIN;
    let mut item = |out: &mut Drawing, swatch: &dyn Fn(&mut Drawing, f64), label: &str| {
        swatch(out, x);
        out.text(
            (x + 16.0, y + TEXT_SIZE / 2.0),
            label,
            TEXT_SIZE,
            TEXT,
            Anchor::Start,
        );
        x += 16.0 + (label.chars().count() as f64) * 8.0 + 22.0;
    };
    item(
        out,
        &|o, x| o.circle((x + 5.0, y), 5.0, Some(X_SIDE), None),
        "x-crossing",
    );
    item(
        out,
        &|o, x| o.circle((x + 5.0, y), 5.0, Some(Y_SIDE), None),
        "y-crossing",
    );
    item(
        out,
        &|o, x| o.rect((x, y - 6.0), (12.0, 12.0), VISITED, 1.0),
        "visited",
    );
    item(
        out,
        &|o, x| o.rect((x, y - 6.0), (12.0, 12.0), HIT_CELL, 1.0),
        "hit",
    );
    item(
        out,
        &|o, x| o.line((x, y), (x + 12.0, y), Stroke::solid(RAY, 2.0)),
        "ray",
    );
    item(
        out,
        &|o, x| o.line((x, y), (x + 12.0, y), Stroke::solid(PLANE, 3.0)),
        "plane",
    );
    item(
        out,
        &|o, x| o.line((x, y), (x + 12.0, y), Stroke::dashed(PERP, 2.0)),
        "perp",
    );
}

/// One column cast for a figure, owning what [`TraceFigure`] borrows: the trace and, on maps
/// with heights, the column's draw list and the projection.
#[derive(Debug, Clone)]
pub struct ColumnCast {
    /// The column's trace.
    pub trace: DdaTrace,
    /// Its draw list and the projection, on maps with heights.
    pub heights: Option<(HeightColumn, Projection)>,
}

impl ColumnCast {
    /// Casts column `column` of a `cols` × `rows`-cell view (`rows` cells = 2·rows pixels) the
    /// way a frame of that size does.
    #[must_use]
    pub fn new(
        map: &Map,
        doors: &crate::world::door::DoorState,
        camera: &Camera,
        view: &crate::render::view::View,
        (cols, rows): (usize, usize),
        column: usize,
    ) -> Self {
        if map.has_heights() {
            let proj = Projection::new(camera, view, cols, rows * 2);
            let (trace, col) = crate::render::height_cast::trace_column_heights(
                map, doors, camera, &proj, column, cols,
            );
            Self {
                trace,
                heights: Some((col, proj)),
            }
        } else {
            Self {
                trace: crate::render::cast::trace_column_doors(map, doors, camera, column, cols),
                heights: None,
            }
        }
    }

    /// The figure of this column.
    #[must_use]
    pub fn figure<'a>(&'a self, map: &'a Map, camera: &'a Camera, cols: usize) -> TraceFigure<'a> {
        TraceFigure {
            map,
            camera,
            width: cols,
            trace: &self.trace,
            heights: self.heights.as_ref().map(|(c, p)| (c, p)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::drawing::Shape;
    use super::*;
    use crate::vec2::Vec2;
    use crate::world::World;

    fn texts(d: &Drawing, class: &str) -> Vec<String> {
        d.shapes
            .iter()
            .filter_map(|s| match s {
                Shape::Text { text, tag, .. } if tag.class.starts_with(class) => Some(text.clone()),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn every_step_is_one_numbered_crossing_and_the_perp_is_labelled() {
        let w = World::default_world();
        let cam = Camera::from_angle(Vec2::new(15.5, 5.5), 90.0, 66.0);
        let doors = crate::world::door::DoorState::new(&w.map);
        let view = crate::render::view::View::default();
        let col = ColumnCast::new(&w.map, &doors, &cam, &view, (40, 12), 20);
        assert!(col.heights.is_none());
        let d = col.figure(&w.map, &cam, 40).drawing();
        let crossings = texts(&d, "crossing");
        // North from (15.5, 5.5): y-lines at 0.5, 1.5, … (deltaDistY = 1), x never crossed.
        assert_eq!(
            crossings,
            ["1: 0.50", "2: 1.50", "3: 2.50", "4: 3.50", "5: 4.50"]
        );
        assert_eq!(texts(&d, "perp"), ["perp 4.50"]);
        assert!(texts(&d, "crossing x").is_empty());
    }
}
