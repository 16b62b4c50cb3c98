//! One-line equality assertions between two frames, failing at the caller's line with the cell
//! diff.

use crate::compare::{diff, diff_looks, DiffReport};
use crate::frame::TermFrame;

/// Asserts two frames are the same in every part of every cell (glyph, colours as named, the
/// default foreground apart from the default background, underline colour, each attribute):
/// anything [`crate::cells_text`] shows. Takes anything that converts into a [`TermFrame`]
/// (a ratatui `Buffer`, owned or borrowed, or a frame).
///
/// # Panics
/// When they differ: the number of differing cells, then the first 50, each with its position,
/// what changed and both values; the panic points at the caller's line.
#[track_caller]
pub fn assert_frames_eq(expected: impl Into<TermFrame>, actual: impl Into<TermFrame>) {
    let report = diff(&expected.into(), &actual.into());
    fail_on(&report, "frames differ");
}

/// Asserts two frames look the same on screen ([`crate::compare::diff_looks`]): `▀` in a/b equals `▄`
/// in b/a, a space equals `█` with the colours swapped, a space's foreground and the
/// difference between the default foreground and background do not count. For a backend or an
/// encoder free to pick among equivalent glyphs; [`assert_frames_eq`] is the default.
///
/// # Panics
/// As [`assert_frames_eq`], for the cells that look different.
#[track_caller]
pub fn assert_frames_look_same(expected: impl Into<TermFrame>, actual: impl Into<TermFrame>) {
    let report = diff_looks(&expected.into(), &actual.into());
    fail_on(&report, "frames look different");
}

/// Panics with the report's summary unless it is equal.
#[track_caller]
fn fail_on(report: &DiffReport, what: &str) {
    if !report.is_equal() {
        panic!("{what} (expected -> actual):\n{}", report.summary());
    }
}
