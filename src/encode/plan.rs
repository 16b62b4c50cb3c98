//! Plans one row of cells: which to skip, which glyph to draw each with, so the row costs the fewest bytes.
//!
//! A small beam search (Viterbi with the best few states kept per cell): the state after a cell is the
//! terminal's (fg, bg) and where the cursor is. Each cell can be drawn as `▀` (fg = top, bg = bottom),
//! `▄` (swapped), or — when both halves match — a space (bg only) or `█` (fg only); a cell the terminal
//! already shows may be skipped, paying a cursor move before the next drawn cell.

use super::cursor::{move_cost, Cursor};
use super::level::ColorLevel;
use super::palette::Code;
use super::sgr;

/// States kept per cell: 1 is greedy; 4 finds nearly all the savings at a modest cost.
pub(crate) const BEAM: usize = 4;

/// A cursor column meaning "not on this row yet" (the first draw pays the move from elsewhere).
const NOWHERE: u16 = u16::MAX;

/// How one cell is sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Choice {
    /// Not sent: the terminal already shows it.
    Skip,
    /// `▀` with fg = top, bg = bottom.
    Upper,
    /// `▄` with fg = bottom, bg = top.
    Lower,
    /// A space with bg = the cell's colour (fg untouched).
    Space,
    /// `█` with fg = the cell's colour (bg untouched).
    Full,
}

impl Choice {
    /// The UTF-8 bytes of the glyph.
    pub(crate) fn glyph(self) -> &'static [u8] {
        match self {
            Choice::Skip => b"",
            Choice::Upper => "▀".as_bytes(),
            Choice::Lower => "▄".as_bytes(),
            Choice::Space => b" ",
            Choice::Full => "█".as_bytes(),
        }
    }

    /// The (fg, bg) the terminal must have to draw cell `[top, bottom]` this way, from `prev`.
    #[inline]
    pub(crate) fn colours(self, cell: [Code; 2], prev: (Code, Code)) -> (Code, Code) {
        match self {
            Choice::Skip => prev,
            Choice::Upper => (cell[0], cell[1]),
            Choice::Lower => (cell[1], cell[0]),
            Choice::Space => (prev.0, cell[0]),
            Choice::Full => (cell[0], prev.1),
        }
    }
}

#[derive(Debug, Clone, Copy)]
struct Node {
    fg: Code,
    bg: Code,
    /// View column the cursor sits at, or [`NOWHERE`].
    cursor: u16,
    cost: u32,
    /// `cost` plus an estimate of a pending cursor move: what the beam ranks by.
    key: u32,
    prev: u8,
    choice: Choice,
}

/// Where the row sits and what the terminal looks like before it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RowStart {
    pub level: ColorLevel,
    /// The terminal's (fg, bg) before the row.
    pub colours: (Code, Code),
    /// The cursor before the row.
    pub cursor: Cursor,
    /// Terminal column of view column 0, and the terminal row of this row.
    pub origin_col: u16,
    pub row: u16,
}

/// Reusable scratch space for planning rows (no allocation per frame once warm).
#[derive(Debug, Default)]
pub(crate) struct RowPlanner {
    nodes: Vec<Node>,
    counts: Vec<u8>,
    choices: Vec<Choice>,
}

impl RowPlanner {
    /// Plans the row; returns the choice per cell (all `Skip` when nothing needs sending).
    ///
    /// `skippable[x]` says the terminal already shows cell x acceptably.
    pub(crate) fn plan(
        &mut self,
        start: &RowStart,
        cells: &[[Code; 2]],
        skippable: &[bool],
        beam: usize,
    ) -> &[Choice] {
        let w = cells.len();
        let beam = beam.clamp(1, BEAM);
        self.choices.clear();
        self.choices.resize(w, Choice::Skip);
        if skippable.iter().all(|&s| s) {
            return &self.choices;
        }
        let blank = Node {
            fg: start.colours.0,
            bg: start.colours.1,
            cursor: NOWHERE,
            cost: 0,
            key: 0,
            prev: 0,
            choice: Choice::Skip,
        };
        self.nodes.clear();
        self.nodes.resize((w + 1) * BEAM, blank);
        self.counts.clear();
        self.counts.resize(w + 1, 0);
        self.counts[0] = 1;
        let entry = |x: usize| move_cost(start.cursor, start.origin_col + x as u16, start.row);
        let mut cand = [blank; 3 * BEAM];
        for x in 0..w {
            let cell = cells[x];
            let uniform = cell[0] == cell[1];
            let options: [Choice; 2] = if uniform {
                [Choice::Space, Choice::Full]
            } else {
                [Choice::Upper, Choice::Lower]
            };
            let mut n = 0;
            let base = x * BEAM;
            let next_entry = if skippable[x] { entry(x + 1) } else { 0 };
            for i in 0..usize::from(self.counts[x]) {
                let p = self.nodes[base + i];
                let mv = if p.cursor == x as u16 {
                    0
                } else if p.cursor == NOWHERE {
                    entry(x)
                } else {
                    move_cost(
                        Cursor::At {
                            col: start.origin_col + p.cursor,
                            row: start.row,
                        },
                        start.origin_col + x as u16,
                        start.row,
                    )
                };
                for choice in options {
                    let (fg, bg) = choice.colours(cell, (p.fg, p.bg));
                    let cost = p.cost
                        + mv
                        + sgr::cost(start.level, (p.fg, p.bg), (fg, bg))
                        + choice.glyph().len() as u32;
                    cand[n] = Node {
                        fg,
                        bg,
                        cursor: x as u16 + 1,
                        cost,
                        key: cost,
                        prev: i as u8,
                        choice,
                    };
                    n += 1;
                }
                if skippable[x] {
                    let pending = if p.cursor == NOWHERE { next_entry } else { 3 };
                    cand[n] = Node {
                        key: p.cost + pending,
                        prev: i as u8,
                        choice: Choice::Skip,
                        ..p
                    };
                    n += 1;
                }
            }
            // Keep the best `beam` distinct states (colours, and whether the cursor is in place).
            let out = (x + 1) * BEAM;
            let mut kept = 0usize;
            cand[..n].sort_unstable_by_key(|c| c.key);
            for c in &cand[..n] {
                if kept == beam {
                    break;
                }
                let dup = self.nodes[out..out + kept]
                    .iter()
                    .any(|k| k.fg == c.fg && k.bg == c.bg && k.cursor == c.cursor);
                if !dup {
                    self.nodes[out + kept] = *c;
                    kept += 1;
                }
            }
            self.counts[x + 1] = kept as u8;
        }
        // Best final state: no pending move matters at the row's end.
        let last = w * BEAM;
        let mut best = 0;
        for i in 1..usize::from(self.counts[w]) {
            if self.nodes[last + i].cost < self.nodes[last + best].cost {
                best = i;
            }
        }
        let mut i = best;
        for x in (0..w).rev() {
            let node = self.nodes[(x + 1) * BEAM + i];
            self.choices[x] = node.choice;
            i = usize::from(node.prev);
        }
        &self.choices
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::encode::palette::UNKNOWN;

    fn start() -> RowStart {
        RowStart {
            level: ColorLevel::Ansi256,
            colours: (UNKNOWN, UNKNOWN),
            cursor: Cursor::Unknown,
            origin_col: 0,
            row: 0,
        }
    }

    #[test]
    fn glyph_choice_keeps_the_shared_colour_in_place() {
        let mut p = RowPlanner::default();
        // (A over B) then (B over C): ▀ then ▄ keeps B as bg.
        let cells = [[20, 30], [30, 40]];
        let c = p.plan(&start(), &cells, &[false, false], BEAM);
        assert_eq!(c, [Choice::Upper, Choice::Lower]);
    }

    #[test]
    fn uniform_cells_use_space_or_full_block_without_a_colour_change() {
        let mut p = RowPlanner::default();
        let cells = [[20, 30], [30, 30], [20, 20]];
        let c = p.plan(&start(), &cells, &[false; 3], BEAM);
        assert_eq!(c, [Choice::Upper, Choice::Space, Choice::Full]);
    }

    #[test]
    fn unchanged_runs_are_skipped_when_a_move_is_cheaper() {
        let mut p = RowPlanner::default();
        let cells = [[20, 30], [50, 60], [70, 80], [90, 100], [20, 30]];
        let skip = [false, true, true, true, false];
        let c = p.plan(&start(), &cells, &skip, BEAM);
        assert_eq!(c[1..4], [Choice::Skip; 3]);
        let none = p.plan(&start(), &cells, &[true; 5], BEAM);
        assert!(none.iter().all(|&c| c == Choice::Skip));
    }
}
