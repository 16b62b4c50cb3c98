//! Terminal frames and halfcast's pixels: a framebuffer as the cells a terminal shows, and a
//! frame back to pixels at its own glyph setting.

use crate::encode::glyph_cell::GlyphCell;
use crate::encode::glyph_frame::picture;
use crate::encode::glyph_mask::mask_of;
use crate::render::framebuffer::Framebuffer;
use crate::render::glyphs::Glyphs;
use crate::termframe::{appearance, CellRgb, TermCell, TermFrame};

/// A [`TermFrame`] to and from halfcast's [`Framebuffer`] (`use halfcast::termframe::FramePixels`
/// to call these on a frame).
pub trait FramePixels {
    /// The half-block view of a framebuffer: `▀` with fg = upper pixel, bg = lower pixel.
    ///
    /// A framebuffer at a finer glyph setting gives that setting's cells: each cell's chosen
    /// mask as its character, fg = the mask's colour, bg = the rest's.
    fn from_framebuffer(fb: &Framebuffer) -> TermFrame;

    /// The finest glyph setting the frame's block characters need: half-blocks unless a cell
    /// shows a quadrant, sextant or octant character (the first setting, coarsest first, that
    /// has every block character used; text and other characters do not count).
    fn glyphs(&self) -> Glyphs;

    /// Back to pixels at the frame's own glyph setting ([`FramePixels::glyphs`]): for
    /// half-blocks the upper and lower colour of each cell; for finer settings each cell's mask
    /// painted in its two colours on that setting's sub-grid, so a frame read back from ANSI
    /// compares pixel for pixel with the framebuffer it came from. Default colours become
    /// black; a character that is not a block character shows its foreground over the upper
    /// part of the cell and its background under it, as at half-blocks.
    fn to_framebuffer(&self) -> Framebuffer;
}

impl FramePixels for TermFrame {
    fn from_framebuffer(fb: &Framebuffer) -> TermFrame {
        if fb.glyphs() != Glyphs::Half {
            let mut chosen = Vec::new();
            crate::encode::glyph_frame::glyph_cells(fb, &mut chosen);
            let cells = chosen
                .iter()
                .map(|c| {
                    TermCell::rgb(
                        crate::encode::glyph_mask::glyph(fb.glyphs(), c.mask),
                        Some(c.fg),
                        Some(c.bg),
                    )
                })
                .collect();
            let (cols, rows) = (fb.cell_cols(), fb.cell_rows());
            return TermFrame { cols, rows, cells };
        }
        let (cols, rows) = (fb.width(), fb.cell_rows());
        let mut cells = Vec::with_capacity(cols * rows);
        for cy in 0..rows {
            for cx in 0..cols {
                let (up, low) = fb.cell(cx, cy);
                cells.push(TermCell::rgb('▀', Some(up), Some(low)));
            }
        }
        TermFrame { cols, rows, cells }
    }

    fn glyphs(&self) -> Glyphs {
        let blocks: Vec<char> = {
            let mut seen: Vec<char> = self
                .cells
                .iter()
                .map(|c| c.glyph.first_char())
                .filter(|&g| {
                    mask_of(Glyphs::Octant, g).is_some() || mask_of(Glyphs::Sextant, g).is_some()
                })
                .collect();
            seen.sort_unstable();
            seen.dedup();
            seen
        };
        Glyphs::ALL
            .into_iter()
            .find(|&set| blocks.iter().all(|&g| mask_of(set, g).is_some()))
            .unwrap_or(Glyphs::Half)
    }

    fn to_framebuffer(&self) -> Framebuffer {
        let glyphs = self.glyphs();
        if glyphs != Glyphs::Half {
            let cells: Vec<GlyphCell> = self
                .cells
                .iter()
                .map(|c| {
                    let (fg, bg) = (
                        c.fg_rgb().unwrap_or_default(),
                        c.bg_rgb().unwrap_or_default(),
                    );
                    match mask_of(glyphs, c.glyph.first_char()) {
                        Some(mask) => GlyphCell { mask, fg, bg },
                        None => {
                            let look = appearance(c);
                            let (c_cols, c_rows) = glyphs.cell_size();
                            let upper = ((1u16 << (c_cols * (c_rows / 2))) - 1) as u8;
                            GlyphCell {
                                mask: upper,
                                fg: look.fg_rgb().unwrap_or_default(),
                                bg: look.bg_rgb().unwrap_or_default(),
                            }
                        }
                    }
                })
                .collect();
            return picture(&cells, self.cols, glyphs);
        }
        let mut fb = Framebuffer::new(self.cols, self.rows * 2);
        for y in 0..self.rows {
            for x in 0..self.cols {
                let look = appearance(self.cell(x, y));
                fb.set(x, 2 * y, look.fg_rgb().unwrap_or_default());
                fb.set(x, 2 * y + 1, look.bg_rgb().unwrap_or_default());
            }
        }
        fb
    }
}

impl From<&Framebuffer> for TermFrame {
    /// [`FramePixels::from_framebuffer`]: half blocks.
    fn from(fb: &Framebuffer) -> Self {
        TermFrame::from_framebuffer(fb)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    #[test]
    fn two_colour_cells_round_trip_at_every_glyph_setting() {
        // Each cell is exactly two colours in some pattern, so the chosen cells are exact and
        // reading them back gives the same pixels at the same setting.
        for glyphs in Glyphs::ALL {
            let (c, r) = glyphs.cell_size();
            let mut fb = Framebuffer::for_glyphs(5, 3, glyphs);
            for cy in 0..3 {
                for cx in 0..5 {
                    let k = cy * 5 + cx;
                    let mask = (k * 37 + 11) as u32;
                    let (ink, paper) = (Rgb::new(200, 40, k as u8 * 9), Rgb::new(10, 90, 30));
                    for dy in 0..r {
                        for dx in 0..c {
                            let on = mask >> ((dy * c + dx) % 8) & 1 == 1;
                            fb.set(cx * c + dx, cy * r + dy, if on { ink } else { paper });
                        }
                    }
                }
            }
            let back = TermFrame::from_framebuffer(&fb).to_framebuffer();
            assert_eq!(back.glyphs(), glyphs);
            assert_eq!(back.pixels(), fb.pixels(), "{glyphs}");
        }
    }

    #[test]
    fn the_setting_is_the_coarsest_with_every_block_character() {
        let frame = |glyphs: &[char]| TermFrame {
            cols: glyphs.len(),
            rows: 1,
            cells: glyphs
                .iter()
                .map(|&glyph| TermCell::rgb(glyph, None, None))
                .collect(),
        };
        assert_eq!(frame(&['▀', '▄', 'a', ' ']).glyphs(), Glyphs::Half);
        assert_eq!(frame(&['▀', '▌', '▚']).glyphs(), Glyphs::Quadrant);
        assert_eq!(frame(&['▌', '\u{1FB00}']).glyphs(), Glyphs::Sextant);
        // No setting draws both (`▀` splits a sextant cell's middle row): read as half-blocks.
        assert_eq!(frame(&['▀', '\u{1FB00}']).glyphs(), Glyphs::Half);
        assert_eq!(frame(&['▘', '\u{1CD00}']).glyphs(), Glyphs::Octant);
    }

    #[test]
    fn framebuffer_round_trip() {
        let mut fb = Framebuffer::for_cells(3, 2);
        fb.set(2, 3, Rgb::new(9, 9, 9));
        assert_eq!(TermFrame::from_framebuffer(&fb).to_framebuffer(), fb);
    }
}
