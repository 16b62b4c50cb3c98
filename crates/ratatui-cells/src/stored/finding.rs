//! What a failed comparison of a stored cells snapshot found, and how it is told: the cell
//! diff printed ahead of insta's summary, and one line for the failure at the test's line.

use crate::cell::TermCell;
use crate::compare::{diff, DiffReport};
use crate::error::Error;
use crate::format::{from_cells_text, snapshot_body, FrameFormat};

/// What the comparison found when the stored snapshot did not match.
#[derive(Debug)]
pub(crate) enum Finding {
    /// The stored cells text shows other cells (or, rarely, the same cells written otherwise).
    Cells(DiffReport),
    /// The stored snapshot is one of ratatui's forms, to be migrated: which form, a report
    /// comparing what that form keeps (only the glyphs, for a `TestBackend`'s `Display`), and
    /// how many cells the new snapshot gives a style the form could not hold.
    Migrate(FrameFormat, DiffReport, usize),
    /// The stored snapshot does not read as a frame.
    Unreadable(Error),
}

/// What the stored text shows against the new cells text, when they differ.
pub(crate) fn find(stored: &str, new: &str) -> Finding {
    let actual = match from_cells_text(new) {
        Ok(frame) => frame,
        Err(e) => return Finding::Unreadable(e),
    };
    match snapshot_body(stored) {
        Ok((frame, FrameFormat::Cells)) => Finding::Cells(diff(&frame, &actual)),
        Ok((frame, FrameFormat::BackendDisplay)) => {
            let styled = actual.cells.iter().filter(|c| !c.is_plain_style()).count();
            let mut glyphs_only = actual;
            for cell in &mut glyphs_only.cells {
                *cell = TermCell {
                    glyph: cell.glyph.clone(),
                    ..TermCell::default()
                };
            }
            let report = diff(&frame, &glyphs_only);
            Finding::Migrate(FrameFormat::BackendDisplay, report, styled)
        }
        Ok((frame, format)) => Finding::Migrate(format, diff(&frame, &actual), 0),
        Err(e) => Finding::Unreadable(e),
    }
}

impl Finding {
    /// The cell diff and what it means, printed before insta's summary.
    pub(crate) fn describe(&self) -> String {
        match self {
            Finding::Cells(report) if report.is_equal() => {
                "cells snapshot: the stored cells text shows the same cells, written otherwise; \
             accepting the new snapshot rewrites it"
                    .to_string()
            }
            Finding::Cells(report) => {
                format!(
                    "cells snapshot differs (stored -> new):\n{}",
                    report.summary()
                )
            }
            Finding::Migrate(format, report, styled) => {
                let form = form_name(*format);
                let what = if report.is_equal() {
                    format!("it shows the same {}", kept(*format))
                } else {
                    format!(
                        "its {} differ (stored -> new):\n{}",
                        kept(*format),
                        report.summary()
                    )
                };
                let adds = if *styled > 0 {
                    format!(
                        " (the cells text adds the styles of {styled} cells the form leaves out)"
                    )
                } else {
                    String::new()
                };
                format!(
                "cells snapshot: the stored snapshot is {form}; accepting the new one migrates it \
                 to cells text{adds}; {what}"
            )
            }
            Finding::Unreadable(e) => format!(
            "cells snapshot: the stored snapshot does not read as a screen ({e}); accepting the \
             new one replaces it"
        ),
        }
    }

    /// One line for the panic message.
    pub(crate) fn headline(&self) -> String {
        let first = |report: &crate::compare::DiffReport| {
            report
                .summary()
                .lines()
                .take(2)
                .collect::<Vec<_>>()
                .join("; ")
        };
        match self {
            Finding::Cells(report) if !report.is_equal() => {
                format!("the cells differ (cell diff above): {}", first(report))
            }
            Finding::Migrate(format, report, _) if !report.is_equal() => format!(
                "stored as {}, whose {} differ (cell diff above): {}",
                form_name(*format),
                kept(*format),
                first(report)
            ),
            Finding::Migrate(format, _, _) => format!(
                "stored as {}, showing the same {}: accept to migrate it to cells text",
                form_name(*format),
                kept(*format)
            ),
            Finding::Cells(_) => "the same cells, written otherwise: accept to rewrite".into(),
            Finding::Unreadable(e) => {
                format!("the stored snapshot does not read as a screen ({e})")
            }
        }
    }
}

/// A form of stored snapshot, for a person.
fn form_name(format: FrameFormat) -> &'static str {
    match format {
        FrameFormat::BufferDebug => "a ratatui Buffer's Debug form",
        FrameFormat::BackendDisplay => "a ratatui TestBackend's Display form (glyphs only)",
        _ => "another form",
    }
}

/// What a form keeps of a cell.
fn kept(format: FrameFormat) -> &'static str {
    match format {
        FrameFormat::BackendDisplay => "glyphs",
        _ => "cells",
    }
}
