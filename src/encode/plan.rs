//! Plans one row of cells: which to skip, which glyph to draw each with, so the row costs the fewest bytes.
//!
//! A small beam search (Viterbi with the best few states kept per cell): the state after a cell is the
//! terminal's (fg, bg) and where the cursor is. Each cell can be drawn as `▀` (fg = top, bg = bottom),
//! `▄` (swapped), or — when both halves match — a space (bg only) or `█` (fg only); a cell the terminal
//! already shows may be skipped, paying a cursor move before the next drawn cell.

use super::cursor::{forward_cost, move_cost, Cursor};
use super::level::ColorLevel;
use super::palette::Code;
use super::sgr;

/// States kept per cell: 1 is greedy; 4 finds nearly all the savings at a modest cost.
pub(crate) const BEAM: usize = 4;

/// The beam the encoder uses unless told otherwise (2 keeps nearly all the savings of 4 at half the work).
pub(crate) const DEFAULT_BEAM: usize = 2;

/// A cursor column meaning "not on this row yet" (the first draw pays the move from elsewhere).
const NOWHERE: u16 = u16::MAX;

/// How a lagging cursor ranks in the beam: less than a real move (3 bytes), so trailing skips survive.
const LAG_PENALTY: u32 = 1;

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
    /// (first column, length) of each run of identical cells.
    runs: Vec<(u16, u16)>,
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
        // Runs of identical cells (same colours, same skippability) are one step: after the first
        // cell of a run the terminal's colours already fit, so the rest cost their glyphs only.
        self.runs.clear();
        let mut x0 = 0;
        for x in 1..=w {
            if x == w || cells[x] != cells[x0] || skippable[x] != skippable[x0] {
                self.runs.push((x0 as u16, (x - x0) as u16));
                x0 = x;
            }
        }
        let steps = self.runs.len();
        // Only the first `counts[step]` nodes of a step are ever read, so stale ones can stay.
        if self.nodes.len() < (steps + 1) * BEAM {
            self.nodes.resize((steps + 1) * BEAM, blank);
        }
        self.nodes[0] = blank;
        self.counts.clear();
        self.counts.resize(steps + 1, 0);
        self.counts[0] = 1;
        let entry = |x: usize| move_cost(start.cursor, start.origin_col + x as u16, start.row);
        let level = start.level;
        for (step, &(x0, len)) in self.runs.iter().enumerate() {
            let (x, end) = (usize::from(x0), usize::from(x0 + len));
            let cell = cells[x];
            let skip_ok = skippable[x];
            let uniform = cell[0] == cell[1];
            let options: [Choice; 2] = if uniform {
                [Choice::Space, Choice::Full]
            } else {
                [Choice::Upper, Choice::Lower]
            };
            // Parameter bytes of this cell's colours as fg and as bg, computed once per run.
            let fg_len = [
                sgr::param_len(level, cell[0], false),
                sgr::param_len(level, cell[1], false),
            ];
            let bg_len = [
                sgr::param_len(level, cell[0], true),
                sgr::param_len(level, cell[1], true),
            ];
            let len_of = |code: Code, lens: &[u32; 2]| lens[usize::from(code != cell[0])];
            let base = step * BEAM;
            let out = (step + 1) * BEAM;
            let next_entry = if skip_ok { entry(end) } else { 0 };
            let mut kept = 0usize;
            for i in 0..usize::from(self.counts[step]) {
                let p = self.nodes[base + i];
                let mv = if p.cursor == x as u16 {
                    0
                } else if p.cursor == NOWHERE {
                    entry(x)
                } else {
                    // Same row, moving right: `ESC[nC` (the emitted move is never longer).
                    forward_cost(x as u16 - p.cursor)
                };
                // A choice that needs no colour change dominates (switching later costs about
                // the same as switching now), which keeps the beam small and the loop fast.
                let mut drawn = [(Choice::Skip, 0u32, 0u32, 0u32); 2];
                for (slot, choice) in drawn.iter_mut().zip(options) {
                    let (fg, bg) = choice.colours(cell, (p.fg, p.bg));
                    // Branch-free: one parameter costs `ESC[`…`m` plus itself; two share them.
                    let (cf, cb) = (u32::from(fg != p.fg), u32::from(bg != p.bg));
                    let colour = cf * (3 + len_of(fg, &fg_len)) + cb * (3 + len_of(bg, &bg_len))
                        - 2 * (cf & cb);
                    *slot = (choice, fg, bg, colour);
                }
                let free = drawn.iter().position(|d| d.3 == 0);
                for (k, &(choice, fg, bg, colour)) in drawn.iter().enumerate() {
                    if free.is_some_and(|f| f != k) {
                        continue;
                    }
                    let cost = p.cost + mv + colour + choice.glyph().len() as u32 * u32::from(len);
                    let node = Node {
                        fg,
                        bg,
                        cursor: end as u16,
                        cost,
                        key: cost,
                        prev: i as u8,
                        choice,
                    };
                    kept = keep(&mut self.nodes[out..out + beam], kept, node);
                }
                if skip_ok {
                    let pending = if p.cursor == NOWHERE {
                        next_entry
                    } else {
                        LAG_PENALTY
                    };
                    let node = Node {
                        key: p.cost + pending,
                        prev: i as u8,
                        choice: Choice::Skip,
                        ..p
                    };
                    kept = keep(&mut self.nodes[out..out + beam], kept, node);
                }
            }
            self.counts[step + 1] = kept as u8;
        }
        // Best final state: no pending move matters at the row's end.
        let last = steps * BEAM;
        let mut best = 0;
        for i in 1..usize::from(self.counts[steps]) {
            if self.nodes[last + i].cost < self.nodes[last + best].cost {
                best = i;
            }
        }
        let mut i = best;
        for step in (0..steps).rev() {
            let node = self.nodes[(step + 1) * BEAM + i];
            let (x0, len) = self.runs[step];
            let (x0, len) = (usize::from(x0), usize::from(len));
            self.choices[x0..x0 + len].fill(node.choice);
            i = usize::from(node.prev);
        }
        &self.choices
    }
}

/// Inserts `node` into the sorted best-`kept` list `top` (capacity `top.len()`), replacing a node with
/// the same state if `node` is better; returns the new length.
#[inline]
fn keep(top: &mut [Node], kept: usize, node: Node) -> usize {
    let same = |a: &Node| a.fg == node.fg && a.bg == node.bg && a.cursor == node.cursor;
    let mut at = match top[..kept].iter().position(same) {
        Some(j) if top[j].key <= node.key => return kept,
        Some(j) => j,
        None if kept < top.len() => kept,
        None if node.key < top[kept - 1].key => kept - 1,
        None => return kept,
    };
    let len = if at == kept { kept + 1 } else { kept };
    top[at] = node;
    while at > 0 && top[at - 1].key > top[at].key {
        top.swap(at - 1, at);
        at -= 1;
    }
    len
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
