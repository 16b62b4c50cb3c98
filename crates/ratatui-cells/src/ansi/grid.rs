//! The terminal's cell grid and cursor, and the operations the escape sequences perform on
//! them: printing grapheme clusters (joined across `print` calls, laid out with ratatui's
//! widths), line feeds and scrolling, erasing, inserting and deleting.

use unicode_segmentation::UnicodeSegmentation;

use super::pen::Pen;
use crate::cell::TermCell;
use crate::frame::TermFrame;
use crate::glyph::{width_of, Glyph};

/// A terminal screen: cells, cursor, pen and the modes that change where glyphs land.
#[derive(Debug, Clone)]
pub(crate) struct Grid {
    pub(crate) cols: usize,
    pub(crate) rows: usize,
    cells: Vec<TermCell>,
    pub(crate) x: usize,
    pub(crate) y: usize,
    pub(crate) pen: Pen,
    /// The cursor is past the last column: the next glyph goes to the next line first.
    pending_wrap: bool,
    /// The column of the last cluster printed on row `y`, while nothing moved the cursor since:
    /// a following character that joins its cluster (a combining mark, a skin tone, the second
    /// half of a flag) is added to it.
    last: Option<usize>,
    pub(crate) saved: (usize, usize, Pen),
    /// The scrolling region, first and last row (inclusive).
    pub(crate) top: usize,
    pub(crate) bottom: usize,
    pub(crate) autowrap: bool,
}

impl Grid {
    /// A blank screen of `cols` × `rows` (each at least 1), the cursor at the top left.
    pub(crate) fn new(cols: usize, rows: usize) -> Self {
        let (cols, rows) = (cols.max(1), rows.max(1));
        Self {
            cols,
            rows,
            cells: vec![TermCell::default(); cols * rows],
            x: 0,
            y: 0,
            pen: Pen::default(),
            pending_wrap: false,
            last: None,
            saved: (0, 0, Pen::default()),
            top: 0,
            bottom: rows - 1,
            autowrap: true,
        }
    }

    /// The top-left `cols` × `rows` cells as a frame.
    pub(crate) fn frame(&self, cols: usize, rows: usize) -> TermFrame {
        let (cols, rows) = (cols.min(self.cols), rows.min(self.rows));
        let cells = (0..rows)
            .flat_map(|y| {
                self.cells[y * self.cols..y * self.cols + cols]
                    .iter()
                    .cloned()
            })
            .collect();
        TermFrame { cols, rows, cells }
    }

    /// A cell the pen would erase to: a space in the pen's background (as xterm erases).
    fn blank(&self) -> TermCell {
        TermCell {
            bg: self.pen.bg,
            ..TermCell::default()
        }
    }

    fn at(&self, x: usize, y: usize) -> usize {
        y * self.cols + x
    }

    /// Moves the cursor (clamped to the screen); the next glyph starts a new cluster.
    pub(crate) fn move_to(&mut self, x: usize, y: usize) {
        self.x = x.min(self.cols - 1);
        self.y = y.min(self.rows - 1);
        self.pending_wrap = false;
        self.last = None;
    }

    /// Prints one character: joined to the last cluster when it continues it, else a new
    /// cluster at the cursor.
    pub(crate) fn print(&mut self, c: char) {
        if let Some(lx) = self.last {
            let at = self.at(lx, self.y);
            let mut joined = String::from(self.cells[at].glyph.as_str());
            joined.push(c);
            if joined.graphemes(true).nth(1).is_none() {
                let style = self.cells[at].clone();
                let old = self.cells[at].glyph.width().max(1);
                let width = width_of(&joined).max(1);
                for k in lx + width..(lx + old).min(self.cols) {
                    let blank = self.blank();
                    let i = self.at(k, self.y);
                    self.cells[i] = blank;
                }
                self.put(lx, Glyph::new(&joined), width, &style);
                self.advance(lx, width);
                return;
            }
        }
        let mut buf = [0; 4];
        let s: &str = c.encode_utf8(&mut buf);
        let width = width_of(s);
        if width == 0 {
            // A mark with nothing before it to join: it shows on its own, in one column.
            return self.print_new(s, 1);
        }
        self.print_new(s, width);
    }

    /// Prints a new cluster of `width` columns at the cursor, wrapping first when pending (or
    /// when a wide glyph does not fit the rest of the line).
    fn print_new(&mut self, s: &str, width: usize) {
        if self.pending_wrap || (self.autowrap && self.x > 0 && self.x + width > self.cols) {
            if self.autowrap {
                self.x = 0;
                self.line_feed();
            }
            self.pending_wrap = false;
        }
        let style = TermCell {
            glyph: Glyph::default(),
            fg: self.pen.fg,
            bg: self.pen.bg,
            underline: self.pen.underline,
            modifiers: self.pen.modifiers,
        };
        let x = self.x;
        self.put(x, Glyph::new(s), width, &style);
        self.advance(x, width);
    }

    /// Puts the cursor after a cluster at `x` of `width` columns.
    fn advance(&mut self, x: usize, width: usize) {
        self.last = Some(x);
        let next = x + width;
        if next >= self.cols {
            self.x = self.cols - 1;
            self.pending_wrap = self.autowrap;
        } else {
            self.x = next;
            self.pending_wrap = false;
        }
    }

    /// Writes `glyph` at `x` in `style`, and continuations in its style over the other columns
    /// it covers; a wide glyph it partly overwrites is erased, as terminals do.
    fn put(&mut self, x: usize, glyph: Glyph, width: usize, style: &TermCell) {
        let end = (x + width).min(self.cols);
        let row = self.y * self.cols;
        if self.cells[row + x].glyph.is_continuation() {
            let mut lead = x;
            while lead > 0 && self.cells[row + lead].glyph.is_continuation() {
                lead -= 1;
            }
            for k in lead..x {
                self.cells[row + k] = self.blank();
            }
        }
        let mut k = end;
        while k < self.cols && self.cells[row + k].glyph.is_continuation() {
            self.cells[row + k] = self.blank();
            k += 1;
        }
        self.cells[row + x] = TermCell {
            glyph,
            ..style.clone()
        };
        for k in x + 1..end {
            self.cells[row + k] = TermCell {
                glyph: Glyph::CONTINUATION,
                ..style.clone()
            };
        }
    }

    /// Line feed: down a row, scrolling the region when at its bottom.
    pub(crate) fn line_feed(&mut self) {
        self.pending_wrap = false;
        self.last = None;
        if self.y == self.bottom {
            self.scroll_up(1);
        } else if self.y + 1 < self.rows {
            self.y += 1;
        }
    }

    /// Reverse index: up a row, scrolling the region down when at its top.
    pub(crate) fn reverse_index(&mut self) {
        self.pending_wrap = false;
        self.last = None;
        if self.y == self.top {
            self.scroll_down(1);
        } else if self.y > 0 {
            self.y -= 1;
        }
    }

    /// Moves rows `first..=last` up by `n`, blank rows coming in at `last`.
    fn shift_up(&mut self, first: usize, last: usize, n: usize) {
        self.last = None;
        let n = n.min(last + 1 - first);
        let (a, b, c) = (
            self.at(0, first),
            self.at(0, first + n),
            self.at(0, last + 1),
        );
        self.cells[a..c].rotate_left(b - a);
        let blank = self.blank();
        self.cells[c - n * self.cols..c].fill(blank);
    }

    /// Moves rows `first..=last` down by `n`, blank rows coming in at `first`.
    fn shift_down(&mut self, first: usize, last: usize, n: usize) {
        self.last = None;
        let n = n.min(last + 1 - first);
        let (a, c) = (self.at(0, first), self.at(0, last + 1));
        self.cells[a..c].rotate_right(n * self.cols);
        let blank = self.blank();
        self.cells[a..a + n * self.cols].fill(blank);
    }

    /// Scrolls the region up `n` rows (SU, and a line feed at its bottom).
    pub(crate) fn scroll_up(&mut self, n: usize) {
        self.shift_up(self.top, self.bottom, n);
    }

    /// Scrolls the region down `n` rows (SD, and a reverse index at its top).
    pub(crate) fn scroll_down(&mut self, n: usize) {
        self.shift_down(self.top, self.bottom, n);
    }

    /// Inserts (IL) or deletes (DL) `n` rows at the cursor's, within the scrolling region.
    pub(crate) fn insert_or_delete_rows(&mut self, n: usize, insert: bool) {
        if self.y < self.top || self.y > self.bottom {
            return;
        }
        if insert {
            self.shift_down(self.y, self.bottom, n);
        } else {
            self.shift_up(self.y, self.bottom, n);
        }
        self.move_to(0, self.y);
    }

    /// Inserts (ICH) or deletes (DCH) `n` cells at the cursor, shifting the rest of its row.
    pub(crate) fn insert_or_delete_cells(&mut self, n: usize, insert: bool) {
        let (a, c) = (self.at(self.x, self.y), self.at(0, self.y + 1));
        let n = n.min(c - a);
        if insert {
            self.cells[a..c].rotate_right(n);
            let blank = self.blank();
            self.cells[a..a + n].fill(blank);
        } else {
            self.cells[a..c].rotate_left(n);
            let blank = self.blank();
            self.cells[c - n..c].fill(blank);
        }
        self.last = None;
    }

    /// Erases cells `from..to` of the screen (row-major indices, clamped).
    pub(crate) fn erase(&mut self, from: usize, to: usize) {
        let to = to.min(self.cells.len());
        let blank = self.blank();
        if from < to {
            self.cells[from..to].fill(blank);
        }
        self.last = None;
    }

    /// The cursor's cell index.
    pub(crate) fn cursor_index(&self) -> usize {
        self.at(self.x, self.y)
    }

    /// Forgets everything: blank screen, home cursor, default pen and modes (RIS).
    pub(crate) fn reset(&mut self) {
        *self = Grid::new(self.cols, self.rows);
    }
}
