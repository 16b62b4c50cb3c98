//! Reading a ratatui `TestBackend`'s `Display` form back into cells: what
//! `insta::assert_snapshot!(terminal.backend())` pins. It holds the glyphs only (one quoted
//! row per line, a wide character once), so every cell reads in the default style.

use crate::cell::TermCell;
use crate::error::Error;
use crate::frame::TermFrame;
use crate::glyph::glyph_row;
use crate::limits::MAX_FRAME;

/// What `TestBackend`'s `Display` appends to a row with cells under a wide character.
const HIDDEN: &str = "\" Hidden by multi-width symbols: ";

/// The glyphs between a row's quotes, when `line` is a `Display` row.
fn row_text(line: &str) -> Option<&str> {
    let rest = line.strip_prefix('"')?;
    match rest.rfind(HIDDEN) {
        Some(end) => Some(&rest[..end]),
        None => rest.strip_suffix('"'),
    }
}

/// Whether `text` has the shape of a `TestBackend`'s `Display`: one or more lines, each a
/// quoted row.
pub(crate) fn is_backend_display(text: &str) -> bool {
    let mut lines = text.lines().peekable();
    lines.peek().is_some() && lines.all(|l| row_text(l).is_some())
}

/// Reads a ratatui `TestBackend`'s `Display` form: the glyphs of each row, every cell in the
/// default style (the form keeps no colours or attributes).
///
/// # Errors
/// A line that is not a quoted row, rows of different widths, a size over [`MAX_FRAME`].
pub fn from_backend_display(text: &str) -> Result<TermFrame, Error> {
    let rows = text.lines().count();
    if rows > MAX_FRAME.1 {
        return Err(Error::new(format!(
            "ratatui TestBackend display is {rows} rows; the limit is {}",
            MAX_FRAME.1
        )));
    }
    let mut cols = None;
    let mut cells = Vec::new();
    for (y, line) in text.lines().enumerate() {
        let row = row_text(line).ok_or_else(|| {
            Error::new(format!(
                "not a ratatui TestBackend's Display form: line {} is not a quoted row",
                y + 1
            ))
        })?;
        let glyphs = glyph_row(row);
        let width = *cols.get_or_insert(glyphs.len());
        if glyphs.len() != width || width > MAX_FRAME.0 {
            return Err(Error::new(format!(
                "not a ratatui TestBackend's Display form: line {} is {} cells, not {width}",
                y + 1,
                glyphs.len()
            )));
        }
        cells.extend(glyphs.into_iter().map(|glyph| TermCell {
            glyph,
            ..TermCell::default()
        }));
    }
    Ok(TermFrame {
        cols: cols.unwrap_or(0),
        rows,
        cells,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui_core::backend::TestBackend;
    use ratatui_core::buffer::Buffer;
    use ratatui_core::layout::Rect;
    use ratatui_core::style::{Color, Style};

    #[test]
    fn a_backends_display_reads_back_as_its_glyphs() {
        let mut backend = TestBackend::new(9, 2);
        let mut buffer = Buffer::empty(Rect::new(0, 0, 9, 2));
        buffer.set_string(0, 0, "界 \"e\u{301}\" 👍🏽", Style::new().fg(Color::Red));
        buffer.set_string(0, 1, "1\u{fe0f}\u{20e3}🇯🇵ok", Style::new());
        ratatui_core::backend::Backend::draw(
            &mut backend,
            buffer.content().iter().enumerate().map(|(i, c)| {
                let (x, y) = buffer.pos_of(i);
                (x, y, c)
            }),
        )
        .unwrap();
        let text = backend.to_string();
        assert!(text.contains("Hidden by multi-width symbols"), "{text}");
        assert!(is_backend_display(&text));
        let back = from_backend_display(&text).unwrap();
        let mut want = TermFrame::from(&buffer);
        for cell in &mut want.cells {
            *cell = TermCell {
                glyph: cell.glyph.clone(),
                ..TermCell::default()
            };
        }
        assert_eq!(back, want);
    }

    #[test]
    fn other_text_is_not_a_display() {
        assert!(!is_backend_display(""));
        assert!(!is_backend_display("\"ab\"\nplain\n"));
        assert_eq!(
            from_backend_display("\"ab\"\n\"abc\"\n")
                .unwrap_err()
                .to_string(),
            "not a ratatui TestBackend's Display form: line 2 is 3 cells, not 2"
        );
    }
}
