//! What each control character and escape sequence does to the grid: the `vte` parser calls
//! these as it reads the bytes.

use vte::{Params, Perform};

use super::grid::Grid;

/// Parameter `i` (0 when absent).
fn param(params: &Params, i: usize) -> usize {
    params
        .iter()
        .nth(i)
        .and_then(|p| p.first())
        .map_or(0, |&n| usize::from(n))
}

/// Parameter `i` as a count or a 1-based position (absent or 0 mean 1).
fn count(params: &Params, i: usize) -> usize {
    param(params, i).max(1)
}

impl Perform for Grid {
    fn print(&mut self, c: char) {
        Grid::print(self, c);
    }

    fn execute(&mut self, byte: u8) {
        match byte {
            b'\r' => self.move_to(0, self.y),
            b'\n' | 0x0b | 0x0c => self.line_feed(),
            0x08 => self.move_to(self.x.saturating_sub(1), self.y),
            b'\t' => self.move_to((self.x / 8 + 1) * 8, self.y),
            _ => {}
        }
    }

    fn csi_dispatch(&mut self, params: &Params, intermediates: &[u8], ignore: bool, action: char) {
        if ignore {
            return;
        }
        if !intermediates.is_empty() {
            if intermediates == b"?" {
                self.private_mode(params, action);
            }
            return;
        }
        let (x, y) = (self.x, self.y);
        match action {
            'm' => self.pen.apply(params),
            'H' | 'f' => self.move_to(count(params, 1) - 1, count(params, 0) - 1),
            'A' => self.move_to(x, y.saturating_sub(count(params, 0))),
            'B' | 'e' => self.move_to(x, y + count(params, 0)),
            'C' | 'a' => self.move_to(x + count(params, 0), y),
            'D' => self.move_to(x.saturating_sub(count(params, 0)), y),
            'E' => self.move_to(0, y + count(params, 0)),
            'F' => self.move_to(0, y.saturating_sub(count(params, 0))),
            'G' | '`' => self.move_to(count(params, 0) - 1, y),
            'd' => self.move_to(x, count(params, 0) - 1),
            'J' => self.erase_display(param(params, 0)),
            'K' => self.erase_line(param(params, 0)),
            'X' => {
                let at = self.cursor_index();
                self.erase(at, at + count(params, 0).min(self.cols - x));
            }
            '@' | 'P' => self.insert_or_delete_cells(count(params, 0), action == '@'),
            'L' | 'M' => self.insert_or_delete_rows(count(params, 0), action == 'L'),
            'S' => self.scroll_up(count(params, 0)),
            'T' => self.scroll_down(count(params, 0)),
            'r' => self.set_region(param(params, 0), param(params, 1)),
            's' => self.saved = (x, y, self.pen),
            'u' => self.restore(),
            _ => {}
        }
    }

    fn esc_dispatch(&mut self, intermediates: &[u8], _ignore: bool, byte: u8) {
        if !intermediates.is_empty() {
            return;
        }
        match byte {
            b'7' => self.saved = (self.x, self.y, self.pen),
            b'8' => self.restore(),
            b'D' => self.line_feed(),
            b'E' => {
                self.move_to(0, self.y);
                self.line_feed();
            }
            b'M' => self.reverse_index(),
            b'c' => self.reset(),
            _ => {}
        }
    }
}

impl Grid {
    /// ED: 0 from the cursor to the end, 1 from the start to the cursor, 2 and 3 everything.
    fn erase_display(&mut self, how: usize) {
        let at = self.cursor_index();
        match how {
            0 => self.erase(at, usize::MAX),
            1 => self.erase(0, at + 1),
            _ => self.erase(0, usize::MAX),
        }
    }

    /// EL: 0 from the cursor to the line's end, 1 from its start to the cursor, 2 the line.
    fn erase_line(&mut self, how: usize) {
        let (at, start) = (self.cursor_index(), self.y * self.cols);
        match how {
            0 => self.erase(at, start + self.cols),
            1 => self.erase(start, at + 1),
            _ => self.erase(start, start + self.cols),
        }
    }

    /// DECSTBM: the scrolling region (whole screen when absent), cursor home.
    fn set_region(&mut self, top: usize, bottom: usize) {
        let top = top.max(1) - 1;
        let bottom = if bottom == 0 {
            self.rows
        } else {
            bottom.min(self.rows)
        } - 1;
        if top < bottom {
            (self.top, self.bottom) = (top, bottom);
        }
        self.move_to(0, 0);
    }

    /// DECRC / SCORC: back to the saved cursor and pen.
    fn restore(&mut self) {
        let (x, y, pen) = self.saved;
        self.move_to(x, y);
        self.pen = pen;
    }

    /// DEC private modes: autowrap (7); the alternate screen (47, 1047, 1049) starts blank.
    fn private_mode(&mut self, params: &Params, action: char) {
        let on = match action {
            'h' => true,
            'l' => false,
            _ => return,
        };
        for p in params.iter() {
            match p.first() {
                Some(7) => self.autowrap = on,
                Some(47 | 1047 | 1049) => self.erase(0, usize::MAX),
                _ => {}
            }
        }
    }
}
