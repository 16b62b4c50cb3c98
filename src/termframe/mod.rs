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
use crate::render::framebuffer::Framebuffer;

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
    use crate::encode::glyph_mask::{full_mask, glyph, mask_of};
    use crate::render::glyphs::Glyphs;
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

    /// Back to pixels: upper and lower colour of each cell (default colours become black).
    #[must_use]
    pub fn to_framebuffer(&self) -> Framebuffer {
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
    fn framebuffer_round_trip() {
        let mut fb = Framebuffer::for_cells(3, 2);
        fb.set(2, 3, Rgb::new(9, 9, 9));
        assert_eq!(TermFrame::from_framebuffer(&fb).to_framebuffer(), fb);
    }
}
