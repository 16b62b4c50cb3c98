//! Cursor moves: where the terminal's cursor is, and the cheapest way to put it somewhere else.

use super::number::{digits, push_num};

/// Where the cursor is, 0-based terminal (column, row); `Unknown` when someone else drew since.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Cursor {
    Unknown,
    At { col: u16, row: u16 },
}

/// One way to move the cursor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Move {
    Stay,
    /// `ESC[nC`: forward on the same row.
    Forward(u16),
    /// `ESC[colG`: absolute column on the same row.
    Column(u16),
    /// `CR`, `lines`×`LF`, then forward to `col`: cheap when going down a few rows.
    Lines {
        lines: u16,
        col: u16,
    },
    /// `ESC[row;colH`: absolute.
    Position {
        col: u16,
        row: u16,
    },
}

/// Bytes of `ESC[nC` (nothing for n = 0).
#[inline]
pub(crate) fn forward_cost(n: u16) -> u32 {
    match n {
        0 => 0,
        1 => 3,
        _ => 3 + digits(u32::from(n)),
    }
}

fn cost_of(m: Move) -> u32 {
    match m {
        Move::Stay => 0,
        Move::Forward(n) => forward_cost(n),
        Move::Column(c) => {
            if c == 0 {
                1 // a bare CR
            } else {
                3 + digits(u32::from(c) + 1)
            }
        }
        Move::Lines { lines, col } => 1 + u32::from(lines) + forward_cost(col),
        Move::Position { col, row } => {
            let r = if row == 0 {
                0
            } else {
                digits(u32::from(row) + 1)
            };
            let c = if col == 0 {
                0
            } else {
                1 + digits(u32::from(col) + 1)
            };
            3 + r + c
        }
    }
}

/// The cheapest move from `from` to (col, row).
fn best(from: Cursor, col: u16, row: u16) -> Move {
    let mut best = Move::Position { col, row };
    let mut best_cost = cost_of(best);
    let mut consider = |m: Move| {
        let c = cost_of(m);
        if c < best_cost {
            best = m;
            best_cost = c;
        }
    };
    if let Cursor::At { col: c0, row: r0 } = from {
        if r0 == row {
            if c0 == col {
                return Move::Stay;
            }
            if col > c0 {
                consider(Move::Forward(col - c0));
            }
            consider(Move::Column(col));
        } else if row > r0 && row - r0 <= 8 {
            consider(Move::Lines {
                lines: row - r0,
                col,
            });
        }
    }
    best
}

/// Bytes of the cheapest move from `from` to (col, row).
#[inline]
pub(crate) fn move_cost(from: Cursor, col: u16, row: u16) -> u32 {
    cost_of(best(from, col, row))
}

/// Writes the cheapest move from `from` to (col, row).
#[inline]
pub(crate) fn write_move(out: &mut Vec<u8>, from: Cursor, col: u16, row: u16) {
    if from == (Cursor::At { col, row }) {
        return;
    }
    write_move_slow(out, from, col, row);
}

fn write_move_slow(out: &mut Vec<u8>, from: Cursor, col: u16, row: u16) {
    let forward = |out: &mut Vec<u8>, n: u16| match n {
        0 => {}
        1 => out.extend_from_slice(b"\x1b[C"),
        _ => {
            out.extend_from_slice(b"\x1b[");
            push_num(out, u32::from(n));
            out.push(b'C');
        }
    };
    match best(from, col, row) {
        Move::Stay => {}
        Move::Forward(n) => forward(out, n),
        Move::Column(0) => out.push(b'\r'),
        Move::Column(c) => {
            out.extend_from_slice(b"\x1b[");
            push_num(out, u32::from(c) + 1);
            out.push(b'G');
        }
        Move::Lines { lines, col } => {
            out.push(b'\r');
            out.extend(std::iter::repeat_n(b'\n', usize::from(lines)));
            forward(out, col);
        }
        Move::Position { col, row } => {
            out.extend_from_slice(b"\x1b[");
            if row > 0 {
                push_num(out, u32::from(row) + 1);
            }
            if col > 0 {
                out.push(b';');
                push_num(out, u32::from(col) + 1);
            }
            out.push(b'H');
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(from: Cursor, col: u16, row: u16, want: &str) {
        let mut v = Vec::new();
        write_move(&mut v, from, col, row);
        assert_eq!(String::from_utf8(v.clone()).unwrap(), want);
        assert_eq!(move_cost(from, col, row) as usize, v.len());
    }

    #[test]
    fn moves_pick_the_shortest_form() {
        check(Cursor::Unknown, 0, 0, "\x1b[H");
        check(Cursor::Unknown, 4, 0, "\x1b[;5H");
        check(Cursor::Unknown, 0, 9, "\x1b[10H");
        check(Cursor::Unknown, 11, 9, "\x1b[10;12H");
        check(Cursor::At { col: 3, row: 2 }, 3, 2, "");
        check(Cursor::At { col: 3, row: 2 }, 4, 2, "\x1b[C");
        check(Cursor::At { col: 3, row: 2 }, 40, 2, "\x1b[37C");
        check(Cursor::At { col: 30, row: 2 }, 0, 2, "\r");
        check(Cursor::At { col: 30, row: 2 }, 0, 3, "\r\n");
        check(Cursor::At { col: 30, row: 2 }, 2, 4, "\x1b[5;3H");
        check(Cursor::At { col: 30, row: 2 }, 0, 4, "\r\n\n");
        check(Cursor::At { col: 30, row: 2 }, 120, 40, "\x1b[41;121H");
    }

    #[test]
    fn every_move_lands_where_asked_in_a_terminal_model() {
        let mut p = vt100::Parser::new(50, 130, 0);
        let targets = [
            (0, 0),
            (5, 0),
            (129, 3),
            (0, 4),
            (7, 9),
            (3, 9),
            (100, 49),
            (1, 1),
        ];
        let mut from = Cursor::Unknown;
        for (col, row) in targets {
            let mut v = Vec::new();
            write_move(&mut v, from, col, row);
            p.process(&v);
            assert_eq!(p.screen().cursor_position(), (row, col));
            from = Cursor::At { col, row };
        }
    }
}
