//! Plans one row of cells: which to skip, which glyph to draw each with, so the row costs the fewest bytes.
//!
//! A small beam search (Viterbi with the best few states kept per run of identical cells): the state
//! after a run is the terminal's (fg, bg) and where the cursor is. A run can be drawn as `▀`
//! (fg = top, bg = bottom), `▄` (swapped), or — when both halves match — spaces (bg only) or `█`
//! (fg only); a run the terminal already shows may be skipped, paying a cursor move before the next
//! drawn cell. For a row with nothing to skip and no uniform cells, two states per run (the last run
//! drawn `▀` or `▄`) are all there are, so a beam of two is exact there.

use super::cursor::{forward_cost, move_cost, write_move, Cursor};
use super::level::ColorLevel;
use super::palette::Code;
use super::sgr;

/// Most states kept per run: 1 is greedy; 4 finds nearly all the savings at a modest cost.
pub(crate) const BEAM: usize = 4;

/// The beam the encoder uses unless told otherwise (2 keeps nearly all the savings of 4 at half the work).
pub(crate) const DEFAULT_BEAM: usize = 2;

/// A cursor column meaning "not on this row yet" (the first draw pays the move from elsewhere).
const NOWHERE: u16 = u16::MAX;

/// How a lagging cursor ranks in the beam: less than a real move (3 bytes), so trailing skips survive.
const LAG_PENALTY: u32 = 1;

/// How one run of cells is sent.
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

/// A run of identical cells (same colours, same skippability) and how it is sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Span {
    /// First view column of the run.
    pub x: u16,
    pub len: u16,
    pub choice: Choice,
}

#[derive(Debug, Clone, Copy)]
struct Node {
    fg: Code,
    bg: Code,
    cost: u32,
    /// `cost` plus an estimate of a pending cursor move: what the beam ranks by.
    key: u32,
    /// View column the cursor sits at, or [`NOWHERE`].
    cursor: u16,
    prev: u8,
    choice: Choice,
}

const BLANK: Node = Node {
    fg: 0,
    bg: 0,
    cost: 0,
    key: 0,
    cursor: NOWHERE,
    prev: 0,
    choice: Choice::Skip,
};

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
    /// The beam after each run (`nodes[0]` is the row's start); the first `counts[i]` are valid.
    nodes: Vec<[Node; BEAM]>,
    counts: Vec<u8>,
    spans: Vec<Span>,
}

/// Bytes of the SGR that sets fg `f` and bg `g` from `p`; `lf`/`lg` are each one's cost alone
/// (`ESC[`…`m` included); both together share one `ESC[`…`m` (branch-free).
#[inline]
fn change(p: &Node, f: Code, g: Code, lf: u32, lg: u32) -> u32 {
    let (cf, cg) = (u32::from(f != p.fg), u32::from(g != p.bg));
    cf * lf + cg * lg - 2 * (cf & cg)
}

impl RowPlanner {
    /// Plans the row: its runs of identical cells, each with how it is sent (empty when nothing
    /// needs sending).
    ///
    /// `skippable[x]` says the terminal already shows cell x acceptably.
    pub(crate) fn plan(
        &mut self,
        start: &RowStart,
        cells: &[[Code; 2]],
        skippable: &[bool],
        beam: usize,
    ) -> &[Span] {
        let w = cells.len().min(skippable.len());
        let beam = beam.clamp(1, BEAM);
        self.spans.clear();
        if skippable[..w].iter().all(|&s| s) {
            return &self.spans;
        }
        self.runs(&cells[..w], &skippable[..w]);
        let steps = self.spans.len();
        if self.nodes.len() < steps + 1 {
            self.nodes.resize(steps + 1, [BLANK; BEAM]);
            self.counts.resize(steps + 1, 0);
        }
        self.nodes[0][0] = Node {
            fg: start.colours.0,
            bg: start.colours.1,
            ..BLANK
        };
        self.counts[0] = 1;
        for step in 0..steps {
            let span = self.spans[step];
            let x = usize::from(span.x);
            let (cell, skip_ok) = (cells[x], skippable[x]);
            let (done, next) = self.nodes.split_at_mut(step + 1);
            let prev = &done[step][..usize::from(self.counts[step])];
            let top = &mut next[0];
            self.counts[step + 1] = if cell[0] != cell[1] && !skip_ok && beam >= 2 {
                two_states(prev, top, start, span, cell)
            } else {
                beam_states(prev, &mut top[..beam], start, span, cell, skip_ok)
            };
        }
        // Best final state: no pending move matters at the row's end.
        let last = &self.nodes[steps][..usize::from(self.counts[steps])];
        let mut i = (0..last.len()).min_by_key(|&k| last[k].cost).unwrap_or(0);
        for step in (0..steps).rev() {
            let node = self.nodes[step + 1][i];
            self.spans[step].choice = node.choice;
            i = usize::from(node.prev);
        }
        &self.spans
    }

    /// Cuts the row into runs of identical cells (same colours, same skippability), each
    /// skipped until planned.
    #[inline(always)]
    fn runs(&mut self, cells: &[[Code; 2]], skippable: &[bool]) {
        let w = cells.len();
        let mut x0 = 0;
        for x in 1..=w {
            if x == w || cells[x] != cells[x0] || skippable[x] != skippable[x0] {
                self.spans.push(Span {
                    x: x0 as u16,
                    len: (x - x0) as u16,
                    choice: Choice::Skip,
                });
                x0 = x;
            }
        }
    }
}

/// Bytes of the cursor move from where `p` left it to view column `x` (none when it is there).
#[inline(always)]
fn move_from(p: &Node, x: u16, start: &RowStart) -> u32 {
    if p.cursor == x {
        0
    } else if p.cursor == NOWHERE {
        move_cost(start.cursor, start.origin_col + x, start.row)
    } else {
        // Same row, moving right: `ESC[nC` (the emitted move is never longer).
        forward_cost(x - p.cursor)
    }
}

/// The common case, exactly: a run of two colours the terminal does not show yet ends in one
/// of two states (drawn `▀` or `▄`), each reached best from one of the `prev` states. Writes
/// them to `top`, cheaper first, and returns their count.
#[inline(always)]
fn two_states(
    prev: &[Node],
    top: &mut [Node; BEAM],
    start: &RowStart,
    span: Span,
    cell: [Code; 2],
) -> u8 {
    let (t, b) = (cell[0], cell[1]);
    let n = u32::from(span.len);
    // Each colour's SGR alone (`ESC[`, the parameter, `m`), as fg and as bg.
    let (ft, bt) = sgr::alone_lens(start.level, t);
    let (fb, bb) = sgr::alone_lens(start.level, b);
    let mut upper = Node {
        fg: t,
        bg: b,
        cost: u32::MAX,
        cursor: span.x + span.len,
        choice: Choice::Upper,
        ..BLANK
    };
    let mut lower = Node {
        fg: b,
        bg: t,
        choice: Choice::Lower,
        ..upper
    };
    for (i, p) in prev.iter().enumerate() {
        let base = p.cost + move_from(p, span.x, start) + 3 * n;
        let (u, l) = (
            base + change(p, t, b, ft, bb),
            base + change(p, b, t, fb, bt),
        );
        if u < upper.cost {
            (upper.cost, upper.prev) = (u, i as u8);
        }
        if l < lower.cost {
            (lower.cost, lower.prev) = (l, i as u8);
        }
    }
    (upper.key, lower.key) = (upper.cost, lower.cost);
    if lower.cost < upper.cost {
        (top[0], top[1]) = (lower, upper);
    } else {
        (top[0], top[1]) = (upper, lower);
    }
    2
}

/// Any other run: every way to send it from each of the `prev` states (a space or a full
/// block for one colour, `▀` or `▄` for two, or skipping it when the terminal shows it
/// already), the best kept in `top` (the beam); returns how many were kept.
#[inline(always)]
fn beam_states(
    prev: &[Node],
    top: &mut [Node],
    start: &RowStart,
    span: Span,
    cell: [Code; 2],
    skip_ok: bool,
) -> u8 {
    let (t, b) = (cell[0], cell[1]);
    let (x, end) = (span.x, span.x + span.len);
    let n = u32::from(span.len);
    let (ft, bt) = sgr::alone_lens(start.level, t);
    let mut kept = 0;
    for (i, p) in prev.iter().enumerate() {
        let base = p.cost + move_from(p, x, start);
        let node = |fg, bg, cost, choice| Node {
            fg,
            bg,
            cost,
            key: cost,
            cursor: end,
            prev: i as u8,
            choice,
        };
        if t == b {
            let space = base + u32::from(t != p.bg) * bt + n;
            let full = base + u32::from(t != p.fg) * ft + 3 * n;
            kept = keep(top, kept, node(p.fg, t, space, Choice::Space));
            kept = keep(top, kept, node(t, p.bg, full, Choice::Full));
        } else {
            let (fb, bb) = sgr::alone_lens(start.level, b);
            let upper = base + change(p, t, b, ft, bb) + 3 * n;
            let lower = base + change(p, b, t, fb, bt) + 3 * n;
            kept = keep(top, kept, node(t, b, upper, Choice::Upper));
            kept = keep(top, kept, node(b, t, lower, Choice::Lower));
        }
        if skip_ok {
            let pending = if p.cursor == NOWHERE {
                move_cost(start.cursor, start.origin_col + end, start.row)
            } else {
                LAG_PENALTY
            };
            let skip = Node {
                key: p.cost + pending,
                prev: i as u8,
                choice: Choice::Skip,
                ..*p
            };
            kept = keep(top, kept, skip);
        }
    }
    kept as u8
}

/// Writes one planned run of a row (not a skipped one): the move to it, the colour change, the
/// glyphs. `cell` is the run's `[top, bottom]`; `at` is (terminal column of the row's column 0,
/// terminal row); `colours` and `cursor` are the terminal's before and are updated to after.
#[inline(always)]
pub(crate) fn write_span(
    out: &mut Vec<u8>,
    level: ColorLevel,
    span: &Span,
    cell: [Code; 2],
    at: (u16, u16),
    colours: &mut (Code, Code),
    cursor: &mut Cursor,
) {
    let (col, row) = (at.0 + span.x, at.1);
    write_move(out, *cursor, col, row);
    let next = span.choice.colours(cell, *colours);
    sgr::write(out, level, *colours, next);
    let len = usize::from(span.len);
    if span.choice == Choice::Space {
        // Runs are short: pushing beats a `memset` call.
        for _ in 0..len {
            out.push(b' ');
        }
    } else {
        let g = glyph3(span.choice);
        for _ in 0..len {
            out.extend_from_slice(&g);
        }
    }
    *colours = next;
    *cursor = Cursor::At {
        col: col + span.len,
        row,
    };
}

/// The three UTF-8 bytes of a block glyph, as a fixed-size array (copied without a memcpy call).
#[inline]
fn glyph3(choice: Choice) -> [u8; 3] {
    let g = choice.glyph();
    [g[0], g[1], g[2]]
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
            cursor: Cursor::At { col: 0, row: 0 },
            origin_col: 0,
            row: 0,
        }
    }

    /// Bytes of a row drawn in full with `choices` (one per cell): SGRs plus glyphs.
    fn bytes(cells: &[[Code; 2]], choices: &[Choice]) -> u32 {
        let mut colours = start().colours;
        let mut total = 0;
        for (&cell, &choice) in cells.iter().zip(choices) {
            let next = choice.colours(cell, colours);
            total += sgr::cost(ColorLevel::Ansi256, colours, next) + choice.glyph().len() as u32;
            colours = next;
        }
        total
    }

    fn per_cell(spans: &[Span]) -> Vec<Choice> {
        spans
            .iter()
            .flat_map(|s| std::iter::repeat_n(s.choice, usize::from(s.len)))
            .collect()
    }

    /// The cheapest full redraw of `cells`, by trying every glyph choice.
    fn brute_force(cells: &[[Code; 2]]) -> u32 {
        let mut best = u32::MAX;
        for mask in 0..1u32 << cells.len() {
            let choices: Vec<Choice> = cells
                .iter()
                .enumerate()
                .map(|(i, c)| match (c[0] == c[1], mask >> i & 1) {
                    (true, 0) => Choice::Space,
                    (true, _) => Choice::Full,
                    (false, 0) => Choice::Upper,
                    (false, _) => Choice::Lower,
                })
                .collect();
            best = best.min(bytes(cells, &choices));
        }
        best
    }

    #[test]
    fn glyph_choice_keeps_the_shared_colour_in_place() {
        let mut p = RowPlanner::default();
        // (A over B) then (B over C): ▀ then ▄ (or ▄ then ▀) keeps B in place: one change after the first.
        let cells = [[20, 30], [30, 40]];
        let c = per_cell(p.plan(&start(), &cells, &[false, false], BEAM));
        let first = c[0].colours(cells[0], start().colours);
        let second = c[1].colours(cells[1], first);
        assert!(first.0 == second.0 || first.1 == second.1, "{c:?}");
    }

    #[test]
    fn uniform_cells_use_space_or_full_block_without_a_colour_change() {
        let mut p = RowPlanner::default();
        let cells = [[20, 30], [30, 30], [20, 20]];
        let c = per_cell(p.plan(&start(), &cells, &[false; 3], BEAM));
        assert_eq!(bytes(&cells, &c), bytes(&cells[..1], &c[..1]) + 4, "{c:?}");
    }

    #[test]
    fn rows_without_uniform_cells_are_planned_optimally_and_uniform_ones_nearly() {
        let mut p = RowPlanner::default();
        let mut seed = 0x2545_f491_u32;
        let mut next = |n: u32| {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            seed % n
        };
        for round in 0..400 {
            let len = 1 + round % 9;
            let cells: Vec<[Code; 2]> = (0..len)
                .map(|_| {
                    let t = 16 + next(5) * 40;
                    let b = 16 + next(5) * 40;
                    [t, if round % 2 == 0 && t == b { t + 1 } else { b }]
                })
                .collect();
            let best = brute_force(&cells);
            for beam in [2, BEAM] {
                let got = bytes(
                    &cells,
                    &per_cell(p.plan(&start(), &cells, &vec![false; cells.len()], beam)),
                );
                if round % 2 == 0 {
                    assert_eq!(got, best, "{cells:?} beam {beam}");
                } else {
                    assert!(
                        got <= best + best / 10,
                        "{cells:?} beam {beam}: {got} vs {best}"
                    );
                }
            }
        }
    }

    #[test]
    fn unchanged_runs_are_skipped_when_a_move_is_cheaper() {
        let mut p = RowPlanner::default();
        let cells = [[20, 30], [50, 60], [70, 80], [90, 100], [20, 30]];
        let skip = [false, true, true, true, false];
        let c = per_cell(p.plan(&start(), &cells, &skip, BEAM));
        assert_eq!(c[1..4], [Choice::Skip; 3]);
        assert!(p.plan(&start(), &cells, &[true; 5], BEAM).is_empty());
    }
}
