//! Tiny drawing primitives on a [`Framebuffer`] used as a canvas (the minimap's pixels).

use crate::color::Rgb;
use crate::render::fast_floor::fast_floor;
use crate::render::framebuffer::Framebuffer;

/// Mixes `over` onto `under` with opacity `alpha` in 0..=256.
#[must_use]
pub fn mix(under: Rgb, over: Rgb, alpha: u16) -> Rgb {
    let a = u32::from(alpha.min(256));
    let m = |u: u8, o: u8| ((u32::from(u) * (256 - a) + u32::from(o) * a) >> 8) as u8;
    Rgb::new(m(under.r, over.r), m(under.g, over.g), m(under.b, over.b))
}

/// Blends one pixel, silently ignoring points off the canvas.
pub fn blend(fb: &mut Framebuffer, x: i64, y: i64, c: Rgb, alpha: u16) {
    if x < 0 || y < 0 || x as usize >= fb.width() || y as usize >= fb.height() {
        return;
    }
    let (x, y) = (x as usize, y as usize);
    let under = fb.get(x, y);
    fb.set(x, y, mix(under, c, alpha));
}

/// A one-pixel line between two points in pixel coordinates (each pixel blended once).
pub fn line(fb: &mut Framebuffer, from: (f64, f64), to: (f64, f64), c: Rgb, alpha: u16) {
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let n = dx.abs().max(dy.abs()).ceil();
    if !n.is_finite() || n > 1e5 {
        return;
    }
    let n = n.max(1.0) as usize;
    let mut last = None;
    for i in 0..=n {
        let t = i as f64 / n as f64;
        let p = (fast_floor(from.0 + dx * t), fast_floor(from.1 + dy * t));
        if last != Some(p) {
            blend(fb, p.0, p.1, c, alpha);
            last = Some(p);
        }
    }
}

/// A filled square of side `size` centred on a point, for the player marker.
pub fn dot(fb: &mut Framebuffer, at: (f64, f64), size: usize, c: Rgb) {
    let half = size as f64 / 2.0;
    let x0 = (at.0 - half).round() as i64;
    let y0 = (at.1 - half).round() as i64;
    for y in y0..y0 + size as i64 {
        for x in x0..x0 + size as i64 {
            blend(fb, x, y, c, 256);
        }
    }
}

/// A filled disc of `radius` pixels centred on a point (pixel centres inside it are blended).
pub fn disc(fb: &mut Framebuffer, at: (f64, f64), radius: f64, c: Rgb, alpha: u16) {
    if !(radius.is_finite() && at.0.is_finite() && at.1.is_finite()) || radius > 1e4 {
        return;
    }
    // The bounding box, cut to the canvas (the minimap's sprites are mostly off it).
    let (w, h) = (fb.width() as i64, fb.height() as i64);
    let ceil = |v: f64| fast_floor(-v).saturating_neg();
    let (x0, x1) = (fast_floor(at.0 - radius).max(0), ceil(at.0 + radius).min(w));
    let (y0, y1) = (fast_floor(at.1 - radius).max(0), ceil(at.1 + radius).min(h));
    for y in y0..y1 {
        for x in x0..x1 {
            let (dx, dy) = (x as f64 + 0.5 - at.0, y as f64 + 0.5 - at.1);
            if dx * dx + dy * dy <= radius * radius {
                blend(fb, x, y, c, alpha);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mixing_ends_are_the_inputs() {
        let (a, b) = (Rgb::new(0, 100, 200), Rgb::new(255, 0, 50));
        assert_eq!(mix(a, b, 0), a);
        assert_eq!(mix(a, b, 256), b);
    }

    #[test]
    fn lines_stay_on_the_canvas_and_hit_both_ends() {
        let mut fb = Framebuffer::new(5, 5);
        let white = Rgb::new(255, 255, 255);
        line(&mut fb, (0.5, 0.5), (4.5, 4.5), white, 256);
        assert_eq!(fb.get(0, 0), white);
        assert_eq!(fb.get(4, 4), white);
        assert_eq!(fb.get(4, 0), Rgb::default());
        line(&mut fb, (-50.0, 2.5), (50.0, 2.5), white, 256);
        line(&mut fb, (0.0, 0.0), (f64::INFINITY, 1.0), white, 256);
        dot(&mut fb, (0.0, 0.0), 3, white);
        assert!(fb.row(2).iter().all(|&p| p == white));
    }

    #[test]
    fn discs_cut_by_the_canvas_keep_exactly_the_pixel_centres_inside() {
        let white = Rgb::new(255, 255, 255);
        for &(at, r) in &[
            ((2.5, 2.5), 1.5),
            ((-0.7, 3.2), 2.3),
            ((6.1, -1.4), 3.0),
            ((-9.0, -9.0), 2.0),
            ((4.0, 5.9), 0.8),
            ((1e19, 2.0), 1.0),
            ((-1e19, 2.0), 1.0),
        ] {
            let mut fb = Framebuffer::new(6, 5);
            disc(&mut fb, at, r, white, 256);
            for y in 0..5 {
                for x in 0..6 {
                    let (dx, dy) = (x as f64 + 0.5 - at.0, y as f64 + 0.5 - at.1);
                    let inside = dx * dx + dy * dy <= r * r;
                    assert_eq!(fb.get(x, y) == white, inside, "{at:?} {r} at ({x}, {y})");
                }
            }
        }
    }
}
