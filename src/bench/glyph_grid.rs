//! The glyph ladder's figures without a clock: what a terminal shows at each setting, brought to
//! the octant grid (2W × 4H, the finest) so every setting is judged against one reference render
//! there, and the JSON shape of `halfcast bench --glyphs`.

use crate::color::{channel_to_linear, Rgb};
use crate::render::framebuffer::Framebuffer;
use crate::render::glyphs::Glyphs;

/// S-CIELAB viewing conditions at the octant grid: an octant pixel is half a half-block pixel
/// across, so the half-block bench's 4.5 and 9 ppd seats are 9 and 18 ppd here.
pub const OCTANT_PPDS: [f64; 2] = [9.0, 18.0];

/// `shown` (a picture at its setting's sub-grid, [`Framebuffer::for_glyphs`]) at the octant
/// grid of the same cells: each octant pixel is the area-weighted mean, in linear light, of the
/// shown pixels it overlaps (exact copies for half-blocks, quadrants and octants; sextant rows,
/// three to a cell, are mixed into four).
#[must_use]
pub fn at_octant_grid(shown: &Framebuffer) -> Framebuffer {
    let (cw, ch) = shown.glyphs().cell_size();
    let (cols, rows) = (shown.cell_cols(), shown.cell_rows());
    let mut out = Framebuffer::for_glyphs(cols as u16, rows as u16, Glyphs::Octant);
    let (ow, oh) = (out.width(), out.height());
    for y in 0..oh {
        // Octant row y covers [y/4, (y+1)/4) cell heights; shown row j covers [j/ch, (j+1)/ch).
        let (top, bottom) = (y as f64 / 4.0, (y + 1) as f64 / 4.0);
        let first = (top * ch as f64).floor() as usize;
        let last = ((bottom * ch as f64).ceil() as usize).min(rows * ch);
        for x in 0..ow {
            let sx = x * cw / 2;
            let mut acc = [0.0f64; 3];
            for j in first..last {
                let (a, b) = (j as f64 / ch as f64, (j + 1) as f64 / ch as f64);
                let weight = (b.min(bottom) - a.max(top)).max(0.0) * 4.0;
                let c = shown.get(sx, j);
                for (k, v) in [c.r, c.g, c.b].into_iter().enumerate() {
                    acc[k] += weight * f64::from(channel_to_linear(v));
                }
            }
            out.set(x, y, from_linear(acc));
        }
    }
    out
}

/// Linear light back to 8-bit sRGB.
fn from_linear(l: [f64; 3]) -> Rgb {
    let ch = |v: f64| -> u8 {
        let v = v.clamp(0.0, 1.0);
        let s = if v <= 0.003_130_8 {
            v * 12.92
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        };
        (s * 255.0).round() as u8
    };
    Rgb::new(ch(l[0]), ch(l[1]), ch(l[2]))
}

/// One glyph setting at one size: the figures `halfcast bench --glyphs` prints.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct GlyphRun {
    /// The setting (`half`, `quadrant`, `sextant`, `octant`).
    pub glyphs: String,
    /// View size in cells.
    pub cols: u16,
    /// View rows in cells.
    pub rows: u16,
    /// The colour level frames were encoded at.
    pub colors: String,
    /// Frames measured (the first, a full redraw, is not in the means).
    pub frames: usize,
    /// Mean S-CIELAB ΔE against the octant-grid reference at 9 ppd of that grid.
    pub scielab_9: f64,
    /// The same at 18 ppd.
    pub scielab_18: f64,
    /// `scielab_9` over half-blocks' at the same size.
    pub error_vs_half: f64,
    /// Mean bytes per frame after the first.
    pub bytes_per_frame: f64,
    /// `bytes_per_frame` over half-blocks'.
    pub bytes_vs_half: f64,
    /// Mean render ms per frame (cast + rasterize at the sub-grid).
    pub render_ms: f64,
    /// Mean encode ms per frame after the first (choosing cells + diff + bytes).
    pub encode_ms: f64,
    /// `render_ms + encode_ms` over half-blocks'.
    pub time_vs_half: f64,
    /// 1000 / (`render_ms + encode_ms`).
    pub fps: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_setting_comes_to_the_octant_grid_keeping_flat_colour() {
        for g in Glyphs::ALL {
            let mut fb = Framebuffer::for_glyphs(3, 2, g);
            for y in 0..fb.height() {
                for x in 0..fb.width() {
                    fb.set(x, y, Rgb::new(200, 100, 50));
                }
            }
            fb.set(0, 0, Rgb::new(0, 0, 0));
            let o = at_octant_grid(&fb);
            assert_eq!((o.width(), o.height()), (6, 8), "{g}");
            assert_eq!(o.get(5, 7), Rgb::new(200, 100, 50), "{g}");
        }
        // Half-blocks: one pixel becomes 2 × 2.
        let mut fb = Framebuffer::for_glyphs(1, 1, Glyphs::Half);
        fb.set(0, 0, Rgb::new(255, 255, 255));
        let o = at_octant_grid(&fb);
        let white = Rgb::new(255, 255, 255);
        assert_eq!(
            [o.get(0, 0), o.get(1, 1), o.get(1, 2)],
            [white, white, Rgb::default()]
        );
    }
}
