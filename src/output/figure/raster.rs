//! The PNG back-end: paints a [`Drawing`] into a [`Framebuffer`] (then `to_png`). Lines and
//! circles are anti-aliased by their distance to each pixel centre; text uses the project's own
//! bitmap font ([`super::font`]) scaled by whole pixels, so the output is the same everywhere.

use super::drawing::{Anchor, Drawing, Shape, Stroke};
use super::font;
use crate::color::Rgb;
use crate::render::framebuffer::Framebuffer;

/// Blends `c` over the pixel at (x, y) with coverage `a` in 0–1 (off-canvas points ignored).
fn blend(fb: &mut Framebuffer, x: i64, y: i64, c: Rgb, a: f64) {
    if a <= 0.0 || x < 0 || y < 0 || x as usize >= fb.width() || y as usize >= fb.height() {
        return;
    }
    let a = a.min(1.0);
    let (x, y) = (x as usize, y as usize);
    let u = fb.get(x, y);
    let m = |u: u8, o: u8| (f64::from(u) * (1.0 - a) + f64::from(o) * a).round() as u8;
    fb.set(x, y, Rgb::new(m(u.r, c.r), m(u.g, c.g), m(u.b, c.b)));
}

/// Pixel bounds (inclusive start, exclusive end) of a box, clipped to the canvas.
fn bounds(fb: &Framebuffer, x0: f64, y0: f64, x1: f64, y1: f64) -> (i64, i64, i64, i64) {
    let w = fb.width() as i64;
    let h = fb.height() as i64;
    (
        (x0.floor() as i64).clamp(0, w),
        (y0.floor() as i64).clamp(0, h),
        (x1.ceil() as i64 + 1).clamp(0, w),
        (y1.ceil() as i64 + 1).clamp(0, h),
    )
}

fn line(fb: &mut Framebuffer, from: (f64, f64), to: (f64, f64), s: &Stroke) {
    let half = s.width / 2.0;
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let len2 = dx * dx + dy * dy;
    let len = len2.sqrt();
    let (x0, y0, x1, y1) = bounds(
        fb,
        from.0.min(to.0) - half - 1.0,
        from.1.min(to.1) - half - 1.0,
        from.0.max(to.0) + half + 1.0,
        from.1.max(to.1) + half + 1.0,
    );
    for y in y0..y1 {
        for x in x0..x1 {
            let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
            let t = if len2 > 0.0 {
                (((px - from.0) * dx + (py - from.1) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            if s.dashed && ((t * len) / s.dash()).floor() as i64 % 2 == 1 {
                continue;
            }
            let (cx, cy) = (from.0 + t * dx, from.1 + t * dy);
            let dist = (px - cx).hypot(py - cy);
            blend(fb, x, y, s.colour, half + 0.5 - dist);
        }
    }
}

fn circle(fb: &mut Framebuffer, c: (f64, f64), r: f64, fill: Option<Rgb>, stroke: Option<&Stroke>) {
    let outer = r + stroke.map_or(0.0, |s| s.width / 2.0) + 1.0;
    let (x0, y0, x1, y1) = bounds(fb, c.0 - outer, c.1 - outer, c.0 + outer, c.1 + outer);
    for y in y0..y1 {
        for x in x0..x1 {
            let d = (x as f64 + 0.5 - c.0).hypot(y as f64 + 0.5 - c.1);
            if let Some(f) = fill {
                blend(fb, x, y, f, r + 0.5 - d);
            }
            if let Some(s) = stroke {
                blend(fb, x, y, s.colour, s.width / 2.0 + 0.5 - (d - r).abs());
            }
        }
    }
}

fn rect(fb: &mut Framebuffer, at: (f64, f64), size: (f64, f64), c: Rgb, a: f64) {
    let (x0, y0, x1, y1) = bounds(fb, at.0, at.1, at.0 + size.0, at.1 + size.1);
    for y in y0..y1 {
        for x in x0..x1 {
            // Coverage of the pixel by the rectangle, per axis.
            let cover = |p: i64, lo: f64, hi: f64| {
                ((p as f64 + 1.0).min(hi) - (p as f64).max(lo)).clamp(0.0, 1.0)
            };
            let k = cover(x, at.0, at.0 + size.0) * cover(y, at.1, at.1 + size.1);
            blend(fb, x, y, c, a * k);
        }
    }
}

fn polygon(fb: &mut Framebuffer, pts: &[(f64, f64)], c: Rgb, a: f64) {
    if pts.len() < 3 {
        return;
    }
    let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for p in pts {
        x0 = x0.min(p.0);
        y0 = y0.min(p.1);
        x1 = x1.max(p.0);
        y1 = y1.max(p.1);
    }
    let (bx0, by0, bx1, by1) = bounds(fb, x0, y0, x1, y1);
    for y in by0..by1 {
        for x in bx0..bx1 {
            let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
            // Even-odd rule.
            let mut inside = false;
            let mut j = pts.len() - 1;
            for i in 0..pts.len() {
                let (a1, b1) = (pts[i], pts[j]);
                if (a1.1 > py) != (b1.1 > py)
                    && px < (b1.0 - a1.0) * (py - a1.1) / (b1.1 - a1.1) + a1.0
                {
                    inside = !inside;
                }
                j = i;
            }
            if inside {
                blend(fb, x, y, c, a);
            }
        }
    }
}

/// Font scale (whole pixels per font pixel) for a cap height of `size` pixels.
#[must_use]
pub fn font_scale(size: f64) -> usize {
    ((size / font::GLYPH.1 as f64).round() as usize).max(1)
}

fn text(fb: &mut Framebuffer, at: (f64, f64), s: &str, size: f64, c: Rgb, anchor: Anchor) {
    let k = font_scale(size);
    let w = (font::text_width(s) * k) as f64;
    let left = match anchor {
        Anchor::Start => at.0,
        Anchor::Middle => at.0 - w / 2.0,
        Anchor::End => at.0 - w,
    }
    .round() as i64;
    let top = at.1.round() as i64 - (font::GLYPH.1 * k) as i64;
    for (i, ch) in s.chars().enumerate() {
        let ink = font::glyph(ch);
        let gx = left + (i * font::ADVANCE * k) as i64;
        for row in 0..font::GLYPH.1 {
            for col in 0..font::GLYPH.0 {
                if !ink(col, row) {
                    continue;
                }
                for dy in 0..k {
                    for dx in 0..k {
                        let x = gx + (col * k + dx) as i64;
                        let y = top + (row * k + dy) as i64;
                        blend(fb, x, y, c, 1.0);
                    }
                }
            }
        }
    }
}

/// Paints `d` into a new framebuffer of its size (rounded up to whole pixels).
#[must_use]
pub fn to_framebuffer(d: &Drawing) -> Framebuffer {
    let (w, h) = (
        d.width.ceil().max(1.0) as usize,
        d.height.ceil().max(1.0) as usize,
    );
    let mut fb = Framebuffer::new(w, h);
    for y in 0..h {
        for p in fb.row_mut(y) {
            *p = d.background;
        }
    }
    for shape in &d.shapes {
        match shape {
            Shape::Rect {
                at,
                size,
                fill,
                stroke,
            } => {
                if let Some((c, a)) = fill {
                    rect(&mut fb, *at, *size, *c, *a);
                }
                if let Some(s) = stroke {
                    let (x0, y0, x1, y1) = (at.0, at.1, at.0 + size.0, at.1 + size.1);
                    for (p, q) in [
                        ((x0, y0), (x1, y0)),
                        ((x1, y0), (x1, y1)),
                        ((x1, y1), (x0, y1)),
                        ((x0, y1), (x0, y0)),
                    ] {
                        line(&mut fb, p, q, s);
                    }
                }
            }
            Shape::Line { from, to, stroke } => line(&mut fb, *from, *to, stroke),
            Shape::Circle {
                centre,
                r,
                fill,
                stroke,
            } => circle(&mut fb, *centre, *r, *fill, stroke.as_ref()),
            Shape::Polygon { points, fill } => polygon(&mut fb, points, fill.0, fill.1),
            Shape::Text {
                at,
                text: s,
                size,
                colour,
                anchor,
                ..
            } => text(&mut fb, *at, s, *size, *colour, *anchor),
        }
    }
    fb
}

#[cfg(test)]
mod tests {
    use super::*;

    const WHITE: Rgb = Rgb::new(255, 255, 255);
    const BLACK: Rgb = Rgb::new(0, 0, 0);

    #[test]
    fn a_line_inks_the_pixels_it_crosses_and_a_dashed_one_skips_some() {
        let mut d = Drawing::new(20.0, 5.0, WHITE);
        d.line((0.0, 2.5), (20.0, 2.5), Stroke::solid(BLACK, 1.0));
        let fb = to_framebuffer(&d);
        assert!((0..20).all(|x| fb.get(x, 2) == BLACK));
        assert!((0..20).all(|x| fb.get(x, 0) == WHITE));
        let mut d = Drawing::new(20.0, 5.0, WHITE);
        d.line((0.0, 2.5), (20.0, 2.5), Stroke::dashed(BLACK, 1.0));
        let fb = to_framebuffer(&d);
        assert_eq!(fb.get(1, 2), BLACK);
        assert_eq!(fb.get(4, 2), WHITE);
    }

    #[test]
    fn text_is_drawn_with_the_bitmap_font_on_its_baseline() {
        let mut d = Drawing::new(12.0, 8.0, WHITE);
        d.text((0.0, 6.0), "1", 5.0, BLACK, Anchor::Start);
        let fb = to_framebuffer(&d);
        // '1' has ink at (1, 0) of its glyph: the glyph's top is 5 rows above the baseline.
        assert_eq!(fb.get(1, 1), BLACK);
        assert_eq!(fb.get(0, 1), WHITE);
        assert_eq!(font_scale(10.0), 2);
    }

    #[test]
    fn rects_circles_and_polygons_fill_their_inside() {
        let mut d = Drawing::new(30.0, 30.0, WHITE);
        d.rect((0.0, 0.0), (10.0, 10.0), BLACK, 1.0);
        d.circle((20.0, 20.0), 4.0, Some(BLACK), None);
        d.polygon(vec![(20.0, 0.0), (30.0, 0.0), (30.0, 10.0)], BLACK, 0.5);
        let fb = to_framebuffer(&d);
        assert_eq!(fb.get(5, 5), BLACK);
        assert_eq!(fb.get(20, 20), BLACK);
        assert_eq!(fb.get(14, 14), WHITE);
        assert_eq!(fb.get(29, 1), Rgb::new(128, 128, 128));
        assert_eq!(fb.get(21, 8), WHITE);
    }
}
