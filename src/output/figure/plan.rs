//! The top view of one column's traversal, after Lode's figures: the grid around the ray with
//! its walls, the camera (position, `dir`, the plane), the ray, every x- and y-crossing numbered
//! in step order and labelled with its sideDist, the cells visited, the hit cell and the
//! perpendicular distance from the camera plane to the hit.

use super::drawing::{Anchor, Drawing, Stroke, Tag};
use super::palette::{
    CAMERA, GRID, HIT_CELL, PERP, PLANE, RAY, SMALL, TEXT, TEXT_SIZE, VISITED, WALL,
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

    /// The part of segment a–b inside the region (Liang–Barsky), if any.
    #[must_use]
    pub fn clip(&self, a: Vec2, b: Vec2) -> Option<(Vec2, Vec2)> {
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        let d = b - a;
        let (lo, hi) = (
            Vec2::new(self.min.0 as f64, self.min.1 as f64),
            Vec2::new(self.max.0 as f64, self.max.1 as f64),
        );
        for (p, q) in [
            (-d.x, a.x - lo.x),
            (d.x, hi.x - a.x),
            (-d.y, a.y - lo.y),
            (d.y, hi.y - a.y),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        (t0 <= t1).then(|| (a + d * t0, a + d * t1))
    }

    /// Whether `p` is inside the cells shown.
    pub(super) fn contains(&self, p: Vec2) -> bool {
        p.x >= self.min.0 as f64
            && p.y >= self.min.1 as f64
            && p.x <= self.max.0 as f64
            && p.y <= self.max.1 as f64
    }
}

/// `v` scaled to length 1 (east for a zero vector).
pub(super) fn unit(v: Vec2) -> Vec2 {
    let l = v.length();
    if l > 0.0 {
        v * (1.0 / l)
    } else {
        Vec2::new(1.0, 0.0)
    }
}

/// A label's box width in pixels (sized for the wider of the two back-ends' fonts: about
/// 8.4 px a character).
pub(super) fn label_width(text: &str) -> f64 {
    text.chars().count() as f64 * 8.4 + 4.0
}

/// The left edge of a label's box whose text is anchored at `x`.
pub(super) fn label_left(x: f64, text: &str, anchor: Anchor) -> f64 {
    let w = label_width(text);
    match anchor {
        Anchor::Start => x - 2.0,
        Anchor::Middle => x - w / 2.0,
        Anchor::End => x - w + 2.0,
    }
}

/// A pale box behind a label so it reads over walls and lines.
pub(super) fn halo(out: &mut Drawing, base: (f64, f64), text: &str, anchor: Anchor) {
    let w = label_width(text);
    let left = label_left(base.0, text, anchor);
    out.rect(
        (left, base.1 - TEXT_SIZE - 3.0),
        (w, TEXT_SIZE + 6.0),
        super::palette::BACKGROUND,
        0.8,
    );
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
    let along = d.plane * (d.camera_x * d.perp);
    let foot = d.pos + along;
    // The ray, from the eye through its point on the plane to the hit.
    out.line(frame.at(d.pos), frame.at(hit), Stroke::solid(RAY, 2.0));
    out.circle(frame.at(d.pos + d.ray_dir), 3.5, Some(RAY), None);
    // perp: from the camera plane to the hit, parallel to dir.
    out.line(frame.at(foot), frame.at(hit), Stroke::dashed(PERP, 2.0));
    let mid = frame.at(foot + (hit - foot) * 0.5);
    let side = unit(d.dir.right_normal()) * 0.25;
    let lab = frame.at(foot + (hit - foot) * 0.5 + side);
    let base = (lab.0, lab.1 + (lab.1 - mid.1).signum().max(0.0) * TEXT_SIZE);
    let label = format!("perp {}", num(d.perp));
    halo(out, base, &label, Anchor::Middle);
    out.tagged_text(
        base,
        label,
        TEXT_SIZE,
        PERP,
        Anchor::Middle,
        Tag {
            class: "perp".into(),
            data: vec![("perp", d.perp.to_string())],
        },
    );
    // The crossings, numbered and labelled, clear of the camera drawn over them.
    super::crossings::draw(out, d, frame, &super::crossings::camera_marks(d, frame));
    // The camera on top: the plane through the eye (where perp is measured from), dir and the
    // plane.
    let pu = unit(d.plane);
    let reach = (d.plane * (d.camera_x * d.perp)).length() + 1.5;
    if let Some((a, b)) = frame.clip(d.pos - pu * reach, d.pos + pu * reach) {
        out.line(frame.at(a), frame.at(b), Stroke::dashed(PLANE, 1.0));
    }
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
    // "dir" beside the arrow's middle, on the side away from the plane's far end.
    let beside = d.pos + d.dir * 0.45 - unit(d.plane) * 0.45;
    let lab = frame.at(beside);
    out.text(
        (lab.0, lab.1 + TEXT_SIZE / 2.0),
        "dir",
        TEXT_SIZE,
        CAMERA,
        Anchor::Middle,
    );
    out.circle(frame.at(d.pos), 5.0, Some(CAMERA), None);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_keeps_the_part_of_a_segment_inside_the_region() {
        let f = Frame {
            min: (0, 0),
            max: (4, 4),
            cell: 10.0,
            origin: (0.0, 0.0),
        };
        let (a, b) = f.clip(Vec2::new(-2.0, 2.0), Vec2::new(6.0, 2.0)).unwrap();
        assert_eq!((a, b), (Vec2::new(0.0, 2.0), Vec2::new(4.0, 2.0)));
        assert!(f.clip(Vec2::new(-2.0, 5.0), Vec2::new(6.0, 5.0)).is_none());
        assert_eq!(f.at(Vec2::new(1.5, 2.0)), (15.0, 20.0));
    }
}
