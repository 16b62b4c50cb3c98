//! Comparing two terminal frames cell by cell: strictly (every part of every cell, the
//! default), or by what the screen shows (opt-in, [`diff_looks`]).

use std::fmt::Write;

use ratatui_core::style::Color;

use crate::cell::TermCell;
use crate::colour::xterm_rgb;
use crate::format::cell_code;
use crate::frame::TermFrame;

/// How many differing cells a report's [`DiffReport::summary`] lists, one line each.
pub const LISTED_CELLS: usize = 50;

/// One cell that differs between the two frames.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CellDiff {
    /// Column.
    pub x: usize,
    /// Row.
    pub y: usize,
    /// The cell in the first frame.
    pub a: TermCell,
    /// The cell in the second frame.
    pub b: TermCell,
    /// Largest channel difference of the two colours in xterm's default palette (255 when only
    /// one has a colour; 0 when only the kind differs, as `Green` and `Indexed(2)`).
    pub colour_delta: u8,
    /// Which parts differ, comma-separated: `glyph`, `fg`, `bg`, `underline colour`,
    /// `attributes` (in the compared form: see [`diff_by`]).
    pub changed: String,
}

/// The outcome of a comparison: equal, different sizes, or the differing cells.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DiffReport {
    /// Size of the first frame (cols, rows).
    pub size_a: (usize, usize),
    /// Size of the second frame (cols, rows).
    pub size_b: (usize, usize),
    /// Every cell that differs.
    pub differing: Vec<CellDiff>,
    /// The largest colour channel difference among them.
    pub max_colour_delta: u8,
}

fn channel_delta(a: Color, b: Color) -> u8 {
    match (xterm_rgb(a), xterm_rgb(b)) {
        (Some(p), Some(q)) => p
            .iter()
            .zip(q)
            .map(|(x, y)| x.abs_diff(y))
            .max()
            .unwrap_or(0),
        (None, None) => 0,
        _ => 255,
    }
}

/// Compares every part of every cell: grapheme, foreground and background as named (the
/// default foreground is not the default background), underline colour, each attribute. A
/// cell that looks the same but was drawn differently (`▀` against `▄` with the colours
/// swapped, a space with another foreground) differs. Frames of different sizes differ
/// entirely.
#[must_use]
pub fn diff(a: &TermFrame, b: &TermFrame) -> DiffReport {
    diff_by(a, b, TermCell::clone)
}

/// Compares what the screen shows ([`TermCell::appearance`]): `▀` a/b equals `▄` b/a, a
/// space equals `█` with the roles swapped, a space's foreground does not count, and the
/// default foreground and background count as one colour. Attributes and underline colours
/// still count. Opt-in: [`diff`] is the default.
#[must_use]
pub fn diff_looks(a: &TermFrame, b: &TermFrame) -> DiffReport {
    diff_by(a, b, TermCell::appearance)
}

/// Compares cells after mapping each through `look` (its canonical form: cells with equal
/// forms count as equal). The parts reported as changed are those of the two forms when
/// neither cell has attributes or an underline colour, else of the cells as they are (an
/// underline added to `█` is a change of attributes, not of glyph). [`diff`] and
/// [`diff_looks`] are this with the identity and with [`TermCell::appearance`]; a program
/// with block characters of its own (quadrants, sextants) passes a form that knows them.
#[must_use]
pub fn diff_by(a: &TermFrame, b: &TermFrame, look: impl Fn(&TermCell) -> TermCell) -> DiffReport {
    let mut report = DiffReport {
        size_a: (a.cols, a.rows),
        size_b: (b.cols, b.rows),
        differing: Vec::new(),
        max_colour_delta: 0,
    };
    if report.size_a != report.size_b {
        return report;
    }
    for (i, (ca, cb)) in a.cells.iter().zip(&b.cells).enumerate() {
        let (la, lb) = (look(ca), look(cb));
        if la == lb {
            continue;
        }
        let (pa, pb) = if ca.is_unadorned() && cb.is_unadorned() {
            (la, lb)
        } else {
            (ca.clone(), cb.clone())
        };
        let colour_delta = channel_delta(pa.fg, pb.fg).max(channel_delta(pa.bg, pb.bg));
        report.max_colour_delta = report.max_colour_delta.max(colour_delta);
        report.differing.push(CellDiff {
            x: i % a.cols,
            y: i / a.cols,
            a: ca.clone(),
            b: cb.clone(),
            colour_delta,
            changed: parts_changed(&pa, &pb),
        });
    }
    report
}

/// The parts that differ between two cells, comma-separated.
fn parts_changed(a: &TermCell, b: &TermCell) -> String {
    let parts = [
        (a.glyph != b.glyph, "glyph"),
        (a.fg != b.fg, "fg"),
        (a.bg != b.bg, "bg"),
        (a.underline != b.underline, "underline colour"),
        (a.modifiers != b.modifiers, "attributes"),
    ];
    let changed: Vec<&str> = parts.iter().filter(|p| p.0).map(|p| p.1).collect();
    changed.join(", ")
}

impl DiffReport {
    /// Whether the frames are equal (in the comparison that made the report).
    #[must_use]
    pub fn is_equal(&self) -> bool {
        self.size_a == self.size_b && self.differing.is_empty()
    }

    /// Lines for a person or a CI log: the count, the largest colour change, then the first
    /// [`LISTED_CELLS`] differing cells, each with what changed and both values.
    #[must_use]
    pub fn summary(&self) -> String {
        if self.size_a != self.size_b {
            return format!(
                "sizes differ: {}x{} vs {}x{} cells\n",
                self.size_a.0, self.size_a.1, self.size_b.0, self.size_b.1
            );
        }
        let total = self.size_a.0 * self.size_a.1;
        let n = self.differing.len();
        let pct = if total == 0 {
            0.0
        } else {
            100.0 * n as f64 / total as f64
        };
        let mut s = format!(
            "{}x{} cells, {n} differ ({pct:.2}%), max colour delta {}\n",
            self.size_a.0, self.size_a.1, self.max_colour_delta
        );
        for d in self.differing.iter().take(LISTED_CELLS) {
            let _ = writeln!(
                s,
                "  cell ({},{}) {}: {} -> {}",
                d.x,
                d.y,
                d.changed,
                cell_code(&d.a),
                cell_code(&d.b)
            );
        }
        if n > LISTED_CELLS {
            let _ = writeln!(s, "  … and {} more", n - LISTED_CELLS);
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(colours: &[(u8, u8)]) -> TermFrame {
        TermFrame {
            cols: colours.len(),
            rows: 1,
            cells: colours
                .iter()
                .map(|&(u, l)| TermCell::new('▀', Color::Rgb(u, u, u), Color::Rgb(l, l, l)))
                .collect(),
        }
    }

    #[test]
    fn counts_differing_cells_and_the_largest_delta() {
        let r = diff(
            &frame(&[(0, 0), (10, 10), (5, 5)]),
            &frame(&[(0, 0), (10, 40), (6, 5)]),
        );
        assert_eq!(r.differing.len(), 2);
        assert_eq!(r.max_colour_delta, 30);
        assert!(!r.is_equal());
        assert!(r
            .summary()
            .starts_with("3x1 cells, 2 differ (66.67%), max colour delta 30\n"));
    }

    #[test]
    fn equal_frames_and_size_mismatch() {
        assert!(diff(&frame(&[(1, 2)]), &frame(&[(1, 2)])).is_equal());
        let r = diff(&frame(&[(1, 2)]), &frame(&[(1, 2), (3, 4)]));
        assert!(!r.is_equal());
        assert_eq!(r.summary(), "sizes differ: 1x1 vs 2x1 cells\n");
    }

    #[test]
    fn the_summary_names_the_cell_the_change_and_both_values() {
        use ratatui_core::style::Modifier;
        let a = frame(&[(1, 2), (3, 4)]);
        let mut b = a.clone();
        b.cells[1].modifiers = Modifier::BOLD;
        b.cells[1].fg = Color::Green;
        let r = diff(&a, &b);
        assert_eq!(
            r.summary(),
            "2x1 cells, 1 differ (50.00%), max colour delta 202\n  \
             cell (1,0) fg, attributes: \"▀\" fg=#030303 bg=#040404 -> \"▀\" fg=green bg=#040404 bold\n"
        );
    }
}

#[cfg(test)]
mod strictness {
    use super::*;
    use crate::glyph::Glyph;

    fn one(cell: TermCell) -> TermFrame {
        TermFrame {
            cols: 1,
            rows: 1,
            cells: vec![cell],
        }
    }

    #[test]
    fn a_swapped_half_block_differs_strictly_and_looks_the_same() {
        let (a, b) = (Color::Rgb(1, 2, 3), Color::Indexed(40));
        let up = one(TermCell::new('▀', a, b));
        let low = one(TermCell::new('▄', b, a));
        assert!(!diff(&up, &low).is_equal());
        assert!(diff_looks(&up, &low).is_equal());
    }

    #[test]
    fn more_than_fifty_differences_list_fifty_and_count_the_rest() {
        let a = TermFrame::blank(60, 1);
        let mut b = a.clone();
        for c in &mut b.cells {
            c.glyph = Glyph::from('x');
        }
        let summary = diff(&a, &b).summary();
        assert!(
            summary.starts_with("60x1 cells, 60 differ (100.00%)"),
            "{summary}"
        );
        assert_eq!(
            summary.lines().filter(|l| l.starts_with("  cell ")).count(),
            50
        );
        assert!(summary.ends_with("  … and 10 more\n"), "{summary}");
    }
}
