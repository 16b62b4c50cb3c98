//! A terminal frame as cells (grapheme, colours, underline colour, attributes): the common
//! ground for comparing PNG, ANSI and text frames, and the text form that snapshots pin.

mod cell;
mod colour;
mod diff;
mod glyph;
mod parse;
mod ratatui_debug;
#[cfg(any(test, feature = "vt100"))]
mod sgr_passes;
mod text;
mod text_v1;

pub use cell::TermCell;
pub use colour::{colour_name, named_colour, ratatui_rgb};
pub use diff::{diff, CellDiff, DiffReport};
pub use glyph::Glyph;
#[cfg(any(test, feature = "vt100"))]
pub use parse::{from_ansi, from_ansi_sized, from_screen, try_from_ansi};
pub use parse::{load, parse_frame, FrameFormat, MAX_FRAME, MAX_FRAME_BYTES};
pub use ratatui_debug::from_buffer_debug;
pub use text::{cell_code, from_cells_text, style_words, to_cells_text, CELLS_HEADER};

use crate::encode::glyph_cell::GlyphCell;
use crate::encode::glyph_frame::picture;
use crate::encode::glyph_mask::mask_of;
use crate::render::framebuffer::Framebuffer;
use crate::render::glyphs::Glyphs;

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
                .map(|c| {
                    TermCell::rgb(
                        crate::encode::glyph_mask::glyph(fb.glyphs(), c.mask),
                        Some(c.fg),
                        Some(c.bg),
                    )
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
                cells.push(TermCell::rgb('▀', Some(up), Some(low)));
            }
        }
        Self { cols, rows, cells }
    }

    /// A ratatui buffer as drawn (the whole TUI screen: panes, text, the view's half-blocks),
    /// every cell's grapheme, colours, underline colour and attributes as the buffer holds them.
    /// The columns a wide character covers read as continuations in its style, as a terminal
    /// shows them (ratatui does not draw them).
    #[must_use]
    pub fn from_buffer(buf: &ratatui::buffer::Buffer) -> Self {
        let area = buf.area;
        let (cols, rows) = (usize::from(area.width), usize::from(area.height));
        let mut cells: Vec<TermCell> = buf
            .content()
            .iter()
            .map(|c| TermCell {
                glyph: Glyph::new(c.symbol()),
                fg: c.fg,
                bg: c.bg,
                underline: c.underline_color,
                modifiers: c.modifier,
            })
            .collect();
        mark_continuations(&mut cells, cols);
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
                    let (fg, bg) = (
                        c.fg_rgb().unwrap_or_default(),
                        c.bg_rgb().unwrap_or_default(),
                    );
                    match mask_of(glyphs, c.glyph.first_char()) {
                        Some(mask) => GlyphCell { mask, fg, bg },
                        None => {
                            let look = c.appearance();
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
                let look = self.cell(x, y).appearance();
                fb.set(x, 2 * y, look.fg_rgb().unwrap_or_default());
                fb.set(x, 2 * y + 1, look.bg_rgb().unwrap_or_default());
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

impl From<&TermFrame> for TermFrame {
    /// A copy, so helpers taking `impl Into<TermFrame>` take a borrowed frame too.
    fn from(frame: &TermFrame) -> Self {
        frame.clone()
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

/// Makes the columns each wide character covers continuations in its style (what a terminal
/// shows there), row by row; a wide character at a row's end covers nothing.
fn mark_continuations(cells: &mut [TermCell], cols: usize) {
    for row in cells.chunks_mut(cols.max(1)) {
        let mut x = 0;
        while x < row.len() {
            let width = row[x].glyph.width().max(1);
            for k in 1..width.min(row.len() - x) {
                row[x + k] = TermCell {
                    glyph: Glyph::CONTINUATION,
                    ..row[x].clone()
                };
            }
            x += width;
        }
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
    fn a_buffer_keeps_every_part_of_each_cell() {
        use ratatui::buffer::Buffer;
        use ratatui::layout::Rect;
        use ratatui::style::{Color, Modifier, Style};
        let mut buf = Buffer::empty(Rect::new(0, 0, 6, 1));
        let style = Style::new()
            .fg(Color::Green)
            .bg(Color::Indexed(200))
            .underline_color(Color::Rgb(1, 2, 3))
            .add_modifier(Modifier::REVERSED | Modifier::DIM);
        buf.set_string(0, 0, "e\u{301}界x", style);
        let f = TermFrame::from_buffer(&buf);
        assert_eq!(f.cell(0, 0).glyph, "e\u{301}");
        assert_eq!(f.cell(1, 0).glyph, "界");
        assert!(f.cell(2, 0).glyph.is_continuation());
        assert_eq!(f.cell(3, 0).glyph, 'x');
        for x in 0..4 {
            let c = f.cell(x, 0);
            assert_eq!(
                (c.fg, c.bg, c.underline, c.modifiers),
                (
                    Color::Green,
                    Color::Indexed(200),
                    Color::Rgb(1, 2, 3),
                    Modifier::REVERSED | Modifier::DIM
                ),
                "{x}"
            );
        }
        assert_eq!(*f.cell(4, 0), TermCell::default());
    }

    #[test]
    fn framebuffer_round_trip() {
        let mut fb = Framebuffer::for_cells(3, 2);
        fb.set(2, 3, Rgb::new(9, 9, 9));
        assert_eq!(TermFrame::from_framebuffer(&fb).to_framebuffer(), fb);
    }
}
