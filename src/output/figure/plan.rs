//! The top view of one column's traversal, after Lode's figures: the grid around the ray with
//! its walls, the camera (position, `dir`, the plane), the ray, every x- and y-crossing numbered
//! in step order and labelled with its sideDist, the cells visited, the hit cell and the
//! perpendicular distance from the camera plane to the hit.

use super::drawing::{Anchor, Drawing, Stroke, Tag};
use super::frame::{halo, unit, Frame};
use super::palette::{
    CAMERA, GRID, HIT_CELL, PERP, PLANE, RAY, SMALL, TEXT, TEXT_SIZE, VISITED, WALL,
};
use crate::map::{Cell, Map};
use crate::render::cast::Side;
use crate::render::derivation::{num, Derivation};
use crate::vec2::Vec2;

/// Draws the top view into `out` within `frame`.
pub fn draw(out: &mut Drawing, map: &Map, d: &Derivation, frame: &Frame) {
    cells(out, map, d, frame);
    grid_lines(out, frame);
    // The face the ray hit, thick.
    let face = hit_face(d);
    out.line(frame.at(face.0), frame.at(face.1), Stroke::solid(PERP, 4.0));
    ray_and_perp(out, d, frame);
    // The crossings, numbered and labelled, clear of the camera drawn over them.
    super::crossings::draw(out, d, frame, &super::crossings::camera_marks(d, frame));
    camera(out, d, frame);
}

/// The cells in the frame: walls filled, visited ones shaded, the hit cell marked, doors outlined.
fn cells(out: &mut Drawing, map: &Map, d: &Derivation, frame: &Frame) {
    let cell_px = frame.cell;
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
}

/// The grid lines and their numbers (a cell's number is at its left or top edge).
fn grid_lines(out: &mut Drawing, frame: &Frame) {
    let cell_px = frame.cell;
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
}

/// The face the ray hit, as a segment: the door's panel, or the grid line it crossed last.
fn hit_face(d: &Derivation) -> (Vec2, Vec2) {
    let (hc, hs) = (d.hit_cell, d.hit_side);
    match d.perp_from {
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
    }
}

/// The ray from the eye through its point on the plane to the hit, and `perp` with its label.
fn ray_and_perp(out: &mut Drawing, d: &Derivation, frame: &Frame) {
    let hit = d.point_at(d.perp);
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
}

/// The camera, drawn on top: the plane through the eye (where perp is measured from), `dir`
/// and the plane.
fn camera(out: &mut Drawing, d: &Derivation, frame: &Frame) {
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
