//! A terminal screen you feed bytes to: the `vte` parser driving the crate's own cell grid,
//! read in one pass, every attribute and the underline colour kept.

use super::grid::Grid;
use crate::frame::TermFrame;
use crate::limits::MAX_FRAME;

/// A terminal of a fixed size that reads ANSI bytes as a terminal would (cursor moves, erases,
/// scrolling regions, autowrap, SGR with every attribute, `38`/`48`/`58` colours in both
/// forms) into cells: each grapheme cluster in one cell, laid out with ratatui's widths, so
/// what a ratatui backend sent reads back as the buffer it drew. Feed it in pieces as they
/// arrive (a sequence split between two calls is read whole).
pub struct Screen {
    parser: vte::Parser,
    grid: Grid,
}

impl std::fmt::Debug for Screen {
    /// The size and the cursor (the cells are what [`Screen::frame`] gives).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Screen")
            .field("cols", &self.grid.cols)
            .field("rows", &self.grid.rows)
            .field("cursor", &(self.grid.x, self.grid.y))
            .finish_non_exhaustive()
    }
}

impl Screen {
    /// A blank screen of `cols` × `rows` (each at least 1, at most [`MAX_FRAME`]).
    #[must_use]
    pub fn new(cols: u16, rows: u16) -> Self {
        let cols = usize::from(cols).clamp(1, MAX_FRAME.0);
        let rows = usize::from(rows).clamp(1, MAX_FRAME.1);
        Self {
            parser: vte::Parser::new(),
            grid: Grid::new(cols, rows),
        }
    }

    /// Reads `bytes` (a line feed moves down only; a tty's output processing, which makes a
    /// bare `\n` a new line, is [`crate::from_ansi_sized`]'s).
    pub fn process(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.parser.advance(&mut self.grid, b);
        }
    }

    /// The whole screen as cells.
    #[must_use]
    pub fn frame(&self) -> TermFrame {
        self.grid.frame(self.grid.cols, self.grid.rows)
    }

    /// The top-left `cols` × `rows` cells (at most the screen).
    #[must_use]
    pub fn frame_part(&self, cols: usize, rows: usize) -> TermFrame {
        self.grid.frame(cols, rows)
    }

    /// Where the cursor is: (column, row), from 0.
    #[must_use]
    pub fn cursor(&self) -> (usize, usize) {
        (self.grid.x, self.grid.y)
    }
}

impl From<&Screen> for TermFrame {
    /// [`Screen::frame`]: the whole screen.
    fn from(screen: &Screen) -> Self {
        screen.frame()
    }
}
