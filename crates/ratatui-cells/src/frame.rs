//! A grid of terminal cells: what a ratatui `Buffer`, a snapshot file or the bytes a backend
//! sent all become, so any two can be compared.

use ratatui_core::backend::TestBackend;
use ratatui_core::buffer::Buffer;

use crate::cell::TermCell;
use crate::glyph::Glyph;

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
    /// A frame of `cols` × `rows` blank cells (a space in the default colours).
    #[must_use]
    pub fn blank(cols: usize, rows: usize) -> Self {
        Self {
            cols,
            rows,
            cells: vec![TermCell::default(); cols * rows],
        }
    }

    /// A ratatui buffer as drawn: every cell's grapheme, colours, underline colour and
    /// attributes as the buffer holds them. The columns a wide character covers read as
    /// continuations in its style, as a terminal shows them (ratatui does not draw them).
    #[must_use]
    pub fn from_buffer(buf: &Buffer) -> Self {
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
    ///
    /// # Panics
    /// When (`x`, `y`) is outside the frame.
    #[must_use]
    pub fn cell(&self, x: usize, y: usize) -> &TermCell {
        assert!(
            x < self.cols && y < self.rows,
            "cell ({x},{y}) is outside the frame"
        );
        &self.cells[y * self.cols + x]
    }

    /// The cell at column `x`, row `y`, to change it (building an expected frame).
    ///
    /// # Panics
    /// When (`x`, `y`) is outside the frame.
    pub fn cell_mut(&mut self, x: usize, y: usize) -> &mut TermCell {
        assert!(
            x < self.cols && y < self.rows,
            "cell ({x},{y}) is outside the frame"
        );
        &mut self.cells[y * self.cols + x]
    }
}

impl From<&Buffer> for TermFrame {
    /// [`TermFrame::from_buffer`]: the cells as drawn.
    fn from(buf: &Buffer) -> Self {
        Self::from_buffer(buf)
    }
}

impl From<Buffer> for TermFrame {
    /// [`TermFrame::from_buffer`] of an owned buffer (`terminal.backend().buffer().clone()`).
    fn from(buf: Buffer) -> Self {
        Self::from_buffer(&buf)
    }
}

impl From<&TestBackend> for TermFrame {
    /// The backend's buffer ([`TermFrame::from_buffer`]): what `terminal.backend()` shows.
    fn from(backend: &TestBackend) -> Self {
        Self::from_buffer(backend.buffer())
    }
}

impl From<&TermFrame> for TermFrame {
    /// A copy, so helpers taking `impl Into<TermFrame>` take a borrowed frame too.
    fn from(frame: &TermFrame) -> Self {
        frame.clone()
    }
}

/// Makes the columns each wide character covers continuations in its style (what a terminal
/// shows there), row by row; a wide character at a row's end covers nothing.
pub(crate) fn mark_continuations(cells: &mut [TermCell], cols: usize) {
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
    use ratatui_core::layout::Rect;
    use ratatui_core::style::{Color, Modifier, Style};

    #[test]
    fn a_buffer_keeps_every_part_of_each_cell() {
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
        assert_eq!(TermFrame::from(buf.clone()), f);
    }
}
