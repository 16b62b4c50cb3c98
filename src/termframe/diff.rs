//! Comparing two terminal frames cell by cell, for `halfcast diff` and snapshot tests.

use std::fmt::Write;

use super::text::cell_code;
use super::{TermCell, TermFrame};
use crate::color::Rgb;
use crate::render::framebuffer::Framebuffer;

/// One cell that looks different in the two frames.
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
    /// Largest channel difference of the upper/lower colours in xterm's RGB (255 when only one
    /// has a colour; 0 when only the kind differs, as `Green` and `Indexed(2)`).
    pub colour_delta: u8,
}

/// The outcome of a comparison: equal, different sizes, or the differing cells.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DiffReport {
    /// Size of the first frame (cols, rows).
    pub size_a: (usize, usize),
    /// Size of the second frame (cols, rows).
    pub size_b: (usize, usize),
    /// Every cell that looks different.
    pub differing: Vec<CellDiff>,
    /// The largest colour channel difference among them.
    pub max_colour_delta: u8,
}

fn channel_delta(a: Option<Rgb>, b: Option<Rgb>) -> u8 {
    match (a, b) {
        (Some(p), Some(q)) => {
            p.r.abs_diff(q.r)
                .max(p.g.abs_diff(q.g))
                .max(p.b.abs_diff(q.b))
        }
        (None, None) => 0,
        _ => 255,
    }
}

/// Two differing cells in the form their parts are compared in: canonical when neither has
/// attributes (so `▀` a/b against `▄` c/a is a change of one colour), else as they are (an
/// underline added to `█` is a change of attributes, not of glyph).
fn comparable(a: &TermCell, b: &TermCell) -> (TermCell, TermCell) {
    let plain =
        |c: &TermCell| c.modifiers.is_empty() && c.underline == ratatui::style::Color::Reset;
    if plain(a) && plain(b) {
        (a.appearance(), b.appearance())
    } else {
        (a.clone(), b.clone())
    }
}

/// Compares by appearance (so `▀` a/b equals `▄` b/a), every part of a cell counting:
/// grapheme, colours as named, underline colour, attributes. Frames of different sizes differ
/// entirely.
#[must_use]
pub fn diff(a: &TermFrame, b: &TermFrame) -> DiffReport {
    let mut report = DiffReport {
        size_a: (a.cols, a.rows),
        size_b: (b.cols, b.rows),
        differing: Vec::new(),
        max_colour_delta: 0,
    };
    if report.size_a != report.size_b {
        return report;
    }
    for y in 0..a.rows {
        for x in 0..a.cols {
            let (ca, cb) = (a.cell(x, y), b.cell(x, y));
            if ca.appearance() != cb.appearance() {
                let (la, lb) = comparable(ca, cb);
                let colour_delta = channel_delta(la.fg_rgb(), lb.fg_rgb())
                    .max(channel_delta(la.bg_rgb(), lb.bg_rgb()));
                report.max_colour_delta = report.max_colour_delta.max(colour_delta);
                report.differing.push(CellDiff {
                    x,
                    y,
                    a: ca.clone(),
                    b: cb.clone(),
                    colour_delta,
                });
            }
        }
    }
    report
}

impl CellDiff {
    /// Which parts of the cell changed: `glyph`, `fg`, `bg`, `underline colour`, `attributes`
    /// (comma-separated).
    #[must_use]
    pub fn what_changed(&self) -> String {
        let (a, b) = comparable(&self.a, &self.b);
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
}

impl DiffReport {
    /// Whether the frames look identical.
    #[must_use]
    pub fn is_equal(&self) -> bool {
        self.size_a == self.size_b && self.differing.is_empty()
    }

    /// A few lines for a person or a CI log: counts, the largest colour change, the first cells.
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
        for d in self.differing.iter().take(10) {
            let _ = writeln!(
                s,
                "  cell ({},{}) {}: {} -> {}",
                d.x,
                d.y,
                d.what_changed(),
                cell_code(&d.a),
                cell_code(&d.b)
            );
        }
        if n > 10 {
            let _ = writeln!(s, "  … and {} more", n - 10);
        }
        s
    }

    /// A picture of the change: B's pixels where cells differ (tinted magenta), A dimmed to grey elsewhere.
    #[must_use]
    pub fn highlight(&self, a: &TermFrame, b: &TermFrame) -> Framebuffer {
        let base = if self.size_a == self.size_b { b } else { a };
        let mut fb = base.to_framebuffer();
        let mut changed = vec![false; base.cols * base.rows];
        for d in &self.differing {
            changed[d.y * base.cols + d.x] = true;
        }
        let (cell_w, cell_h) = fb.glyphs().cell_size();
        for y in 0..fb.height() {
            for x in 0..fb.width() {
                let p = fb.get(x, y);
                let mark = changed[(y / cell_h) * base.cols + x / cell_w];
                fb.set(
                    x,
                    y,
                    if mark {
                        Rgb::new(p.r / 2 + 127, p.g / 3, p.b / 2 + 127)
                    } else {
                        let l = p.luma() / 3;
                        Rgb::new(l, l, l)
                    },
                );
            }
        }
        fb
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
                .map(|&(u, l)| TermCell::rgb('▀', Some(Rgb::new(u, u, u)), Some(Rgb::new(l, l, l))))
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
        use ratatui::style::{Color, Modifier};
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
