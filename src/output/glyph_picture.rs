//! A frame as the terminal shows it at its glyph setting: every cell's mask painted in its two
//! colours, at a size where a cell is twice as tall as it is wide (what `render --format png`
//! writes for quadrants, sextants and octants).

use crate::encode::glyph_frame::{glyph_cells, picture};
use crate::render::framebuffer::Framebuffer;
use crate::render::glyphs::Glyphs;

/// Image pixels per sub-grid pixel (across, down), so a cell comes out 1∶2: half-blocks and
/// octants 1×1, quadrants 1×2 (2×4 per cell), sextants 3×4 (6×12 per cell).
#[must_use]
pub fn scale(glyphs: Glyphs) -> (usize, usize) {
    match glyphs {
        Glyphs::Half | Glyphs::Octant => (1, 1),
        Glyphs::Quadrant => (1, 2),
        Glyphs::Sextant => (3, 4),
    }
}

/// The picture a terminal shows for `fb`: half-block frames as they are (a cell's two pixels are
/// its two colours), finer ones as chosen masks and colours, scaled by [`scale`].
#[must_use]
pub fn shown_picture(fb: &Framebuffer) -> Framebuffer {
    let glyphs = fb.glyphs();
    if glyphs == Glyphs::Half {
        return fb.clone();
    }
    let mut cells = Vec::new();
    glyph_cells(fb, &mut cells);
    let sub = picture(&cells, fb.cell_cols(), glyphs);
    let (sx, sy) = scale(glyphs);
    let mut out = Framebuffer::new(sub.width() * sx, sub.height() * sy);
    for y in 0..out.height() {
        for x in 0..out.width() {
            out.set(x, y, sub.get(x / sx, y / sy));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    #[test]
    fn cells_come_out_twice_as_tall_as_wide() {
        for g in Glyphs::ALL {
            let mut fb = Framebuffer::for_glyphs(3, 2, g);
            fb.set(0, 0, Rgb::new(255, 0, 0));
            let p = shown_picture(&fb);
            assert_eq!(p.height() * 3, p.width() * 2 * 2, "{g}");
            assert_eq!(p.get(0, 0), Rgb::new(255, 0, 0));
        }
    }
}
