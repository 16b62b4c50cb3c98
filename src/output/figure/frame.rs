//! Where the top view sits in the figure, and how its labels are sized and set off: shared by
//! the plan (cells, walls, the ray) and the crossings drawn over it.

use super::drawing::{Anchor, Drawing};
use super::palette::TEXT_SIZE;
use crate::render::derivation::Derivation;
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
