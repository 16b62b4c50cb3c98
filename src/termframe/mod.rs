//! A terminal frame as cells (glyph + colours): the common ground for comparing PNG, ANSI and
//! text frames, and the colour-aware text form that snapshots pin.

mod diff;
mod parse;
mod text;

pub use diff::{diff, CellDiff, DiffReport};
#[cfg(any(test, feature = "vt100"))]
pub use parse::{from_ansi, from_screen, try_from_ansi};
pub use parse::{load, parse_frame, FrameFormat, MAX_FRAME, MAX_FRAME_BYTES};
pub use text::{cell_code, from_cells_text, to_cells_text, CELLS_HEADER};

use crate::color::Rgb;
use crate::encode::glyph_cell::GlyphCell;
use crate::encode::glyph_frame::picture;
use crate::encode::glyph_mask::mask_of;
use crate::render::framebuffer::Framebuffer;
use crate::render::glyphs::Glyphs;

/// One terminal cell as a person sees it: a glyph with a foreground and a background colour
/// (`None` = the terminal's default colour).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TermCell {
    /// The character shown.
    pub glyph: char,
    /// Foreground colour (`None` = the terminal's default).
    pub fg: Option<Rgb>,
    /// Background colour (`None` = the terminal's default).
    pub bg: Option<Rgb>,
}

impl TermCell {
    /// The visible content in a canonical form, so `▀` fg=a bg=b equals `▄` fg=b bg=a and
    /// a space equals `█` with swapped roles: (glyph class, upper colour, lower colour).
    #[must_use]
    pub fn appearance(&self) -> (char, Option<Rgb>, Option<Rgb>) {
        match self.glyph {
            '▀' => ('▀', self.fg, self.bg),
            '▄' => ('▀', self.bg, self.fg),
            ' ' => ('▀', self.bg, self.bg),
            '█' => ('▀', self.fg, self.fg),
            g => glyph_appearance(g, self.fg, self.bg),
        }
    }
}

/// A quadrant, sextant or octant cell in canonical form: a mask and its complement with the
/// colours swapped draw the same picture, so the form whose first pixel is the background
/// stands for both (other glyphs as they are).
fn glyph_appearance(g: char, fg: Option<Rgb>, bg: Option<Rgb>) -> (char, Option<Rgb>, Option<Rgb>) {
    use crate::encode::glyph_mask::{full_mask, glyph};
    for set in [Glyphs::Octant, Glyphs::Sextant] {
        if let Some(m) = mask_of(set, g) {
            if m & 1 != 0 {
                return (glyph(set, !m & full_mask(set)), bg, fg);
            }
            return (g, fg, bg);
        }
    }
    (g, fg, bg)
}

/// A grid of terminal cells, row-major.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TermFrame {
    /// Columns.
    pub cols: usize,
    /// Rows.
    pub rows: usize,
    /// The cells, row-major.
    pub cells: Vec<TermCell>,
}

impl TermFrame {
    /// The half-block view of a framebuffer: `▀` with fg = upper pixel, bg = lower pixel.
    #[must_use]
    ///
    /// A framebuffer at a finer glyph setting gives that setting's cells: each cell's chosen
    /// mask as its character, fg = the mask's colour, bg = the rest's.
    pub fn from_framebuffer(fb: &Framebuffer) -> Self {
        if fb.glyphs() != crate::render::glyphs::Glyphs::Half {
            let mut chosen = Vec::new();
            crate::encode::glyph_frame::glyph_cells(fb, &mut chosen);
            let cells = chosen
                .iter()
                .map(|c| TermCell {
                    glyph: crate::encode::glyph_mask::glyph(fb.glyphs(), c.mask),
                    fg: Some(c.fg),
                    bg: Some(c.bg),
                })
                .collect();
            let (cols, rows) = (fb.cell_cols(), fb.cell_rows());
            return Self { cols, rows, cells };
        }
        let (cols, rows) = (fb.width(), fb.cell_rows());
        let mut cells = Vec::with_capacity(cols * rows);
        for cy in 0..rows {
            for cx in 0..cols {
                let (up, low) = fb.cell(cx, cy);
                cells.push(TermCell {
                    glyph: '▀',
                    fg: Some(up),
                    bg: Some(low),
                });
            }
        }
        Self { cols, rows, cells }
    }

    /// A ratatui buffer as drawn (the whole TUI screen: panes, text, the view's half-blocks).
    #[must_use]
    pub fn from_buffer(buf: &ratatui::buffer::Buffer) -> Self {
        let area = buf.area;
        let (cols, rows) = (usize::from(area.width), usize::from(area.height));
        let cells = buf
            .content()
            .iter()
            .map(|c| TermCell {
                glyph: c.symbol().chars().next().unwrap_or(' '),
                fg: ratatui_rgb(c.fg),
                bg: ratatui_rgb(c.bg),
            })
            .collect();
        Self { cols, rows, cells }
    }

    /// The cell at column `x`, row `y`.
    #[must_use]
    pub fn cell(&self, x: usize, y: usize) -> &TermCell {
        &self.cells[y * self.cols + x]
    }

    /// The finest glyph setting the frame's block characters need: half-blocks unless a cell
    /// shows a quadrant, sextant or octant character (the first setting, coarsest first, that
    /// has every block character used; text and other characters do not count).
    #[must_use]
    pub fn glyphs(&self) -> Glyphs {
        let blocks: Vec<char> = {
            let mut seen: Vec<char> = self
                .cells
                .iter()
                .map(|c| c.glyph)
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

    /// Back to pixels at the frame's own glyph setting ([`TermFrame::glyphs`]): for half-blocks
    /// the upper and lower colour of each cell; for finer settings each cell's mask painted in
    /// its two colours on that setting's sub-grid, so a frame read back from ANSI compares pixel
    /// for pixel with the framebuffer it came from. Default colours become black; a character
    /// that is not a block character shows its foreground over the upper part of the cell and
    /// its background under it, as at half-blocks.
    #[must_use]
    pub fn to_framebuffer(&self) -> Framebuffer {
        let glyphs = self.glyphs();
        if glyphs != Glyphs::Half {
            let cells: Vec<GlyphCell> = self
                .cells
                .iter()
                .map(|c| {
                    let (fg, bg) = (c.fg.unwrap_or_default(), c.bg.unwrap_or_default());
                    match mask_of(glyphs, c.glyph) {
                        Some(mask) => GlyphCell { mask, fg, bg },
                        None => {
                            let (_, up, low) = c.appearance();
                            let (c_cols, c_rows) = glyphs.cell_size();
                            let upper = ((1u16 << (c_cols * (c_rows / 2))) - 1) as u8;
                            GlyphCell {
                                mask: upper,
                                fg: up.unwrap_or_default(),
                                bg: low.unwrap_or_default(),
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
                let (_, up, low) = self.cell(x, y).appearance();
                fb.set(x, 2 * y, up.unwrap_or_default());
                fb.set(x, 2 * y + 1, low.unwrap_or_default());
            }
        }
        fb
    }
}

impl From<&Framebuffer> for TermFrame {
    /// [`TermFrame::from_framebuffer`]: half blocks.
    fn from(fb: &Framebuffer) -> Self {
        Self::from_framebuffer(fb)
    }
}

impl From<&ratatui::buffer::Buffer> for TermFrame {
    /// [`TermFrame::from_buffer`]: the cells as drawn.
    fn from(buf: &ratatui::buffer::Buffer) -> Self {
        Self::from_buffer(buf)
    }
}

#[cfg(any(test, feature = "vt100"))]
impl From<&vt100::Screen> for TermFrame {
    /// The whole screen of a terminal model ([`from_screen`] at its size).
    fn from(screen: &vt100::Screen) -> Self {
        let (rows, cols) = screen.size();
        from_screen(screen, usize::from(cols), usize::from(rows))
    }
}

/// The RGB a ratatui colour shows as (`None` = the terminal's default).
#[must_use]
pub fn ratatui_rgb(c: ratatui::style::Color) -> Option<Rgb> {
    use ratatui::style::Color as C;
    let idx = match c {
        C::Reset => return None,
        C::Rgb(r, g, b) => return Some(Rgb::new(r, g, b)),
        C::Indexed(i) => i,
        C::Black => 0,
        C::Red => 1,
        C::Green => 2,
        C::Yellow => 3,
        C::Blue => 4,
        C::Magenta => 5,
        C::Cyan => 6,
        C::Gray => 7,
        C::DarkGray => 8,
        C::LightRed => 9,
        C::LightGreen => 10,
        C::LightYellow => 11,
        C::LightBlue => 12,
        C::LightMagenta => 13,
        C::LightCyan => 14,
        C::White => 15,
    };
    Some(crate::encode::palette::xterm_rgb(idx))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equivalent_glyphs_look_the_same() {
        let (a, b) = (Some(Rgb::new(1, 2, 3)), Some(Rgb::new(4, 5, 6)));
        let up = TermCell {
            glyph: '▀',
            fg: a,
            bg: b,
        };
        let low = TermCell {
            glyph: '▄',
            fg: b,
            bg: a,
        };
        assert_eq!(up.appearance(), low.appearance());
        let space = TermCell {
            glyph: ' ',
            fg: None,
            bg: a,
        };
        let full = TermCell {
            glyph: '█',
            fg: a,
            bg: b,
        };
        assert_eq!(space.appearance(), full.appearance());
    }

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
                .map(|&glyph| TermCell {
                    glyph,
                    fg: None,
                    bg: None,
                })
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
