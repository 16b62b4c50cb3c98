//! The top view's crossings: every x- and y-crossing of the ray, numbered in step order and
//! labelled with its sideDist, x labels on one side of the ray and y labels on the other, each
//! moved further out while it would cover the camera (the `dir` arrow, the plane and their
//! names), which is drawn over the labels.

use super::drawing::{Anchor, Drawing, Stroke, Tag};
use super::frame::{halo, label_left, label_width, unit, Frame};
use super::palette::{TEXT_SIZE, X_SIDE, Y_SIDE};
use crate::render::cast::Side;
use crate::render::derivation::{num, Derivation};

/// How far a label is pushed each time it would cover the camera, in pixels (one label row).
const ROW: f64 = 14.0;

/// Most rows a label is pushed out before it stays where it is.
const MAX_PUSH: usize = 4;

/// Points (pixels) along the camera's marks that a label must not cover: the `dir` arrow, the
/// plane bar, and the boxes of their names (as [`super::plan`] places them).
#[must_use]
pub fn camera_marks(d: &Derivation, frame: &Frame) -> Vec<(f64, f64)> {
    let mut points = Vec::new();
    let mut segment = |a: (f64, f64), b: (f64, f64)| {
        for k in 0..=24 {
            let t = f64::from(k) / 24.0;
            points.push((a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t));
        }
    };
    segment(frame.at(d.pos), frame.at(d.pos + d.dir));
    segment(
        frame.at(d.pos + d.dir - d.plane),
        frame.at(d.pos + d.dir + d.plane),
    );
    // The names: a line through the middle of each text box.
    let plane_end = frame.at(d.pos + d.dir + d.plane);
    let plane_base = (plane_end.0 + 6.0, plane_end.1 - 6.0);
    let dir_at = frame.at(d.pos + d.dir * 0.45 - unit(d.plane) * 0.45);
    let dir_base = (dir_at.0, dir_at.1 + TEXT_SIZE / 2.0);
    for (base, text, anchor) in [
        (plane_base, "plane", Anchor::Start),
        (dir_base, "dir", Anchor::Middle),
    ] {
        let left = label_left(base.0, text, anchor);
        let mid = base.1 - TEXT_SIZE / 2.0;
        segment((left, mid), (left + label_width(text), mid));
    }
    points
}

/// Whether a label at `base` (its halo box, plus a pixel) covers any of `marks`.
fn covers(base: (f64, f64), text: &str, anchor: Anchor, marks: &[(f64, f64)]) -> bool {
    let left = label_left(base.0, text, anchor) - 1.0;
    let right = left + label_width(text) + 2.0;
    let (top, bottom) = (base.1 - TEXT_SIZE - 4.0, base.1 + 4.0);
    marks
        .iter()
        .any(|&(x, y)| x >= left && x <= right && y >= top && y <= bottom)
}

/// Draws every crossing of `d` inside `frame`, its label clear of `marks` where it can be.
pub fn draw(out: &mut Drawing, d: &Derivation, frame: &Frame, marks: &[(f64, f64)]) {
    let normal = unit(d.ray_dir.right_normal());
    // Crossings closer than a label's width alternate between a near and a far row.
    let spacing = |side: Side| {
        let delta = match side {
            Side::X => d.delta_dist.0,
            Side::Y => d.delta_dist.1,
        };
        (d.ray_dir * delta).length() * frame.cell
    };
    let mut seen = (0usize, 0usize);
    for c in &d.choices {
        let nth = match c.side {
            Side::X => &mut seen.0,
            Side::Y => &mut seen.1,
        };
        *nth += 1;
        let far = if spacing(c.side) < 72.0 && *nth % 2 == 0 {
            ROW
        } else {
            0.0
        };
        let t = c.crossing();
        let p = d.point_at(t);
        if !frame.contains(p) {
            continue;
        }
        let (colour, class, sign, name) = match c.side {
            Side::X => (X_SIDE, "crossing x", 1.0, "sideDistX"),
            Side::Y => (Y_SIDE, "crossing y", -1.0, "sideDistY"),
        };
        let at = frame.at(p);
        out.circle(
            at,
            5.0,
            Some(colour),
            Some(Stroke::solid(super::palette::BACKGROUND, 1.5)),
        );
        let label = format!("{}: {}", c.index, num(t));
        let place = |push: usize| {
            let out_by = sign * (16.0 + far + ROW * push as f64);
            let off = (normal.x * out_by, normal.y * out_by);
            let anchor = if off.0 > 3.0 {
                Anchor::Start
            } else if off.0 < -3.0 {
                Anchor::End
            } else {
                Anchor::Middle
            };
            ((at.0 + off.0, at.1 + off.1 + TEXT_SIZE / 2.0), anchor)
        };
        let push = (0..=MAX_PUSH)
            .find(|&k| {
                let (base, anchor) = place(k);
                !covers(base, &label, anchor, marks)
            })
            .unwrap_or(0);
        let (base, anchor) = place(push);
        halo(out, base, &label, anchor);
        out.tagged_text(
            base,
            label,
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
