//! The top view of one column's traversal, after Lode's figures: the grid around the ray with
//! its walls, the camera (position, `dir`, the plane), the ray, every x- and y-crossing numbered
//! in step order and labelled with its sideDist, the cells visited, the hit cell and the
//! perpendicular distance from the camera plane to the hit.

use super::drawing::{Anchor, Drawing, Stroke, Tag};
use super::palette::{
    CAMERA, GRID, HIT_CELL, PERP, PLANE, RAY, SMALL, TEXT, TEXT_SIZE, VISITED, WALL, X_SIDE, Y_SIDE,
};
use crate::map::{Cell, Map};
use crate::render::cast::Side;
use crate::render::derivation::{num, Derivation};
use crate::vec2::Vec2;

/// The cells the figure shows, [x0, x1) × [y0, y1), and the pixels per cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// First column and row of cells shown.
    pub min: (i64, i64),
    /// One past the last.
    pub max: (i64, i64),
    /// Pixels per cell.
    pub cell: f64,
    /// Where cell `min`'s top-left corner is drawn.
    pub origin: (f64, f64),
}

impl Frame {
    /// The cells around the start, every cell visited and the camera's plane, with a cell of
    /// margin; cells get smaller as the region grows so long rays still fit a page.
    #[must_use]
    pub fn around(d: &Derivation, origin: (f64, f64)) -> Self {
        let mut pts = vec![d.pos, d.pos + d.dir + d.plane, d.pos + d.dir - d.plane];
        pts.push(d.point_at(d.perp));
        let mut min = (d.start_cell.0, d.start_cell.1);
        let mut max = min;
        let mut take = |c: (i64, i64)| {
            min = (min.0.min(c.0), min.1.min(c.1));
            max = (max.0.max(c.0), max.1.max(c.1));
        };
        for c in &d.choices {
            take(c.cell);
        }
        for p in pts {
            take((p.x.floor() as i64, p.y.floor() as i64));
        }
        let min = (min.0 - 1, min.1 - 1);
        let max = (max.0 + 2, max.1 + 2);
        let span = (max.0 - min.0).max(max.1 - min.1) as f64;
        let cell = (720.0 / span).clamp(36.0, 72.0).floor();
        Self {
            min,
            max,
            cell,
            origin,
        }
    }

    /// Pixel position of map point `p`.
    #[must_use]
    pub fn at(&self, p: Vec2) -> (f64, f64) {
        (
            self.origin.0 + (p.x - self.min.0 as f64) * self.cell,
            self.origin.1 + (p.y - self.min.1 as f64) * self.cell,
        )
    }

    /// Pixel size of the region.
    #[must_use]
    pub fn size(&self) -> (f64, f64) {
        (
            (self.max.0 - self.min.0) as f64 * self.cell,
            (self.max.1 - self.min.1) as f64 * self.cell,
        )
    }

    fn contains(&self, p: Vec2) -> bool {
        p.x >= self.min.0 as f64
            && p.y >= self.min.1 as f64
            && p.x <= self.max.0 as f64
            && p.y <= self.max.1 as f64
    }
}

fn unit(v: Vec2) -> Vec2 {
    let l = v.length();
    if l > 0.0 {
        v * (1.0 / l)
    } else {
        Vec2::new(1.0, 0.0)
    }
}

/// Draws the top view into `out` within `frame`.
pub fn draw(out: &mut Drawing, map: &Map, d: &Derivation, frame: &Frame) {
    let cell_px = frame.cell;
    // Cells: walls filled, visited ones shaded, the hit cell marked.
    let visited: Vec<(i64, i64)> = std::iter::once(d.start_cell)
        .chain(d.choices.iter().map(|c| c.cell))
        .collect();
    for j in frame.min.1..frame.max.1 {
        for i in frame.min.0..frame.max.0 {
            let at = frame.at(Vec2::new(i as f64, j as f64));
            let what = map.cell(i, j);
            if (i, j) == d.hit_cell {
                out.rect(at, (cell_px, cell_px), HIT_CELL, 1.0);
            } else if what.blocks_ray() {
                out.rect(at, (cell_px, cell_px), WALL, 1.0);
            } else if visited.contains(&(i, j)) {
                out.rect(at, (cell_px, cell_px), VISITED, 1.0);
            }
            if matches!(what, Cell::Door(_)) {
                out.frame(
                    (at.0 + cell_px * 0.2, at.1 + cell_px * 0.2),
                    (cell_px * 0.6, cell_px * 0.6),
                    Stroke::dashed(WALL, 1.0),
                );
            }
        }
    }
    // Grid lines and their numbers (a cell's number is at its left or top edge).
    let (w, h) = frame.size();
    for i in frame.min.0..=frame.max.0 {
        let (x, y) = frame.at(Vec2::new(i as f64, frame.min.1 as f64));
        out.line((x, y), (x, y + h), Stroke::solid(GRID, 1.0));
        if i < frame.max.0 {
            out.text(
                (x + cell_px / 2.0, y - 6.0),
                i.to_string(),
                SMALL,
                TEXT,
                Anchor::Middle,
            );
        }
    }
    for j in frame.min.1..=frame.max.1 {
        let (x, y) = frame.at(Vec2::new(frame.min.0 as f64, j as f64));
        out.line((x, y), (x + w, y), Stroke::solid(GRID, 1.0));
        if j < frame.max.1 {
            out.text(
                (x - 6.0, y + cell_px / 2.0 + SMALL / 2.0),
                j.to_string(),
                SMALL,
                TEXT,
                Anchor::End,
            );
        }
    }
    // The face the ray hit, thick.
    let hit = d.point_at(d.perp);
    let (hc, hs) = (d.hit_cell, d.hit_side);
    let face = match d.perp_from {
        crate::render::derivation::PerpFrom::DoorPanel { line, .. } => match hs {
            Side::X => (
                Vec2::new(line, hc.1 as f64),
                Vec2::new(line, hc.1 as f64 + 1.0),
            ),
            Side::Y => (
                Vec2::new(hc.0 as f64, line),
                Vec2::new(hc.0 as f64 + 1.0, line),
            ),
        },
        crate::render::derivation::PerpFrom::GridLine { .. } => {
            let gx = if d.step.0 > 0 { hc.0 } else { hc.0 + 1 } as f64;
            let gy = if d.step.1 > 0 { hc.1 } else { hc.1 + 1 } as f64;
            match hs {
                Side::X => (Vec2::new(gx, hc.1 as f64), Vec2::new(gx, hc.1 as f64 + 1.0)),
                Side::Y => (Vec2::new(hc.0 as f64, gy), Vec2::new(hc.0 as f64 + 1.0, gy)),
            }
        }
    };
    out.line(frame.at(face.0), frame.at(face.1), Stroke::solid(PERP, 4.0));
    // The camera: the plane through the eye (where perp is measured from), dir and the plane.
    let along = d.plane * (d.camera_x * d.perp);
    let foot = d.pos + along;
    let pu = unit(d.plane);
    let reach = along.length() + 1.5;
    out.line(
        frame.at(d.pos - pu * reach),
        frame.at(d.pos + pu * reach),
        Stroke::dashed(PLANE, 1.0),
    );
    out.line(
        frame.at(d.pos + d.dir - d.plane),
        frame.at(d.pos + d.dir + d.plane),
        Stroke::solid(PLANE, 3.0),
    );
    let plane_end = frame.at(d.pos + d.dir + d.plane);
    out.text(
        (plane_end.0 + 6.0, plane_end.1 - 6.0),
        "plane",
        TEXT_SIZE,
        PLANE,
        Anchor::Start,
    );
    out.arrow(
        frame.at(d.pos),
        frame.at(d.pos + d.dir),
        Stroke::solid(CAMERA, 2.5),
    );
    let tip = frame.at(d.pos + d.dir * 0.55);
    let n = unit(d.dir.right_normal()) * -0.18;
    let lab = frame.at(d.pos + d.dir * 0.55 + n);
    out.text(
        (lab.0 + (lab.0 - tip.0).signum() * 2.0, lab.1 + 4.0),
        "dir",
        TEXT_SIZE,
        CAMERA,
        Anchor::Middle,
    );
    // The ray, from the eye through its point on the plane to the hit.
    out.line(frame.at(d.pos), frame.at(hit), Stroke::solid(RAY, 2.0));
    out.circle(frame.at(d.pos + d.ray_dir), 3.5, Some(RAY), None);
    out.circle(frame.at(d.pos), 5.0, Some(CAMERA), None);
    // perp: from the camera plane to the hit, parallel to dir.
    out.line(frame.at(foot), frame.at(hit), Stroke::dashed(PERP, 2.0));
    let mid = frame.at(foot + (hit - foot) * 0.5);
    let side = unit(d.dir.right_normal()) * 0.25;
    let lab = frame.at(foot + (hit - foot) * 0.5 + side);
    out.tagged_text(
        (lab.0, lab.1 + (lab.1 - mid.1).signum().max(0.0) * TEXT_SIZE),
        format!("perp {}", num(d.perp)),
        TEXT_SIZE,
        PERP,
        Anchor::Middle,
        Tag {
            class: "perp".into(),
            data: vec![("perp", d.perp.to_string())],
        },
    );
    // The crossings, numbered in step order and labelled with their sideDist; x labels on one
    // side of the ray, y labels on the other.
    let normal = unit(d.ray_dir.right_normal());
    for c in &d.choices {
        let t = c.crossing();
        let p = d.point_at(t);
        if !frame.contains(p) {
            continue;
        }
        let (colour, class, sign) = match c.side {
            Side::X => (X_SIDE, "crossing x", 1.0),
            Side::Y => (Y_SIDE, "crossing y", -1.0),
        };
        let at = frame.at(p);
        out.circle(
            at,
            5.0,
            Some(colour),
            Some(Stroke::solid(super::palette::BACKGROUND, 1.5)),
        );
        let off = (normal.x * sign * 12.0, normal.y * sign * 12.0);
        let anchor = if off.0 > 3.0 {
            Anchor::Start
        } else if off.0 < -3.0 {
            Anchor::End
        } else {
            Anchor::Middle
        };
        let name = match c.side {
            Side::X => "sideDistX",
            Side::Y => "sideDistY",
        };
        out.tagged_text(
            (at.0 + off.0, at.1 + off.1 + TEXT_SIZE / 2.0),
            format!("{}: {}", c.index, num(t)),
            TEXT_SIZE,
            colour,
            anchor,
            Tag {
                class: class.into(),
                data: vec![
                    ("step", c.index.to_string()),
                    ("name", name.into()),
                    ("side-dist", t.to_string()),
                ],
            },
        );
    }
}
