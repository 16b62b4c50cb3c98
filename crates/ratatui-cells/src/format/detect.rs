//! Reading a frame from text of any form this crate knows, recognised by content: the cells
//! text, a ratatui `Buffer`'s `Debug` form (what `insta::assert_debug_snapshot!(buffer)` pins),
//! either of those or a `TestBackend`'s `Display` (`insta::assert_snapshot!(terminal.backend())`)
//! inside an insta `.snap` file, ANSI bytes, or plain text.

use crate::ansi::try_from_ansi;
use crate::cell::TermCell;
use crate::error::Error;
use crate::frame::TermFrame;
use crate::glyph::{glyph_row, Glyph};
use crate::limits::{too_large, MAX_FRAME};

use super::backend_display::{from_backend_display, is_backend_display};
use super::buffer_debug::{from_buffer_debug, BUFFER_DEBUG_HEADER};
use super::cells_text::{from_cells_text, HEADER};

/// How a ratatui `TestBackend`'s `Debug` form starts, and the field holding its buffer.
const BACKEND_DEBUG_HEADER: &str = "TestBackend {";
const BACKEND_BUFFER_FIELD: &str = "buffer: Buffer {";

/// What kind of frame text was read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum FrameFormat {
    /// ANSI escape sequences, read through [`crate::ansi::Screen`].
    Ansi,
    /// The cells text (glyph grid and style runs).
    Cells,
    /// A ratatui `Buffer`'s `Debug` form, alone or inside a `TestBackend`'s.
    BufferDebug,
    /// A ratatui `TestBackend`'s `Display` form (glyphs only), read inside an insta snapshot.
    BackendDisplay,
    /// Plain text, one grapheme cluster per cell.
    Text,
}

/// Reads a frame from a file's bytes, whichever form it holds (an insta `.snap` file's header
/// is skipped).
///
/// # Errors
/// Bytes that are not UTF-8 text, a broken cells text or `Debug` form, an insta snapshot of
/// something else, a frame over [`MAX_FRAME`].
pub fn parse_frame(bytes: &[u8]) -> Result<(TermFrame, FrameFormat), Error> {
    let text = std::str::from_utf8(bytes).map_err(|_| Error::new("not UTF-8 text"))?;
    if let Some(body) = insta_body(text) {
        return snapshot_body(body);
    }
    if let Some(frame) = frame_text(text) {
        return frame;
    }
    if text.contains('\x1b') {
        return Ok((try_from_ansi(text.as_bytes())?, FrameFormat::Ansi));
    }
    plain_text(text).map(|f| (f, FrameFormat::Text))
}

/// Plain text: one row per line, one cell per grapheme cluster (two for a wide one).
fn plain_text(text: &str) -> Result<TermFrame, Error> {
    let rows = text.lines().count();
    // Characters bound the columns (a cluster or a wide character is at most one per char),
    // so an oversized text is refused before any row is read into cells.
    let widest = text.lines().map(|l| l.chars().count()).max().unwrap_or(0);
    if widest > 2 * MAX_FRAME.0 || rows > MAX_FRAME.1 {
        return Err(too_large("text frame", widest, rows));
    }
    let lines: Vec<Vec<Glyph>> = text.lines().map(glyph_row).collect();
    let cols = lines.iter().map(Vec::len).max().unwrap_or(0);
    if cols > MAX_FRAME.0 {
        return Err(too_large("text frame", cols, rows));
    }
    let cells = lines
        .into_iter()
        .flat_map(|l| {
            let mut glyphs = l.into_iter();
            (0..cols).map(move |_| TermCell {
                glyph: glyphs.next().unwrap_or_default(),
                ..TermCell::default()
            })
        })
        .collect();
    Ok(TermFrame { cols, rows, cells })
}

/// The contents of an insta `.snap` file (the header between its `---` lines removed), when
/// `text` is one.
pub(crate) fn insta_body(text: &str) -> Option<&str> {
    let rest = text.strip_prefix("---\n")?;
    let end = rest.find("\n---\n")?;
    Some(&rest[end + 5..])
}

/// Reads the contents of an insta snapshot (its header removed) as a frame: cells text, a
/// `Buffer`'s `Debug` or a `TestBackend`'s `Display`.
///
/// # Errors
/// Contents in none of those forms, or a broken one.
pub(crate) fn snapshot_body(body: &str) -> Result<(TermFrame, FrameFormat), Error> {
    if let Some(frame) = frame_text(body) {
        return frame;
    }
    if is_backend_display(body) {
        return from_backend_display(body).map(|f| (f, FrameFormat::BackendDisplay));
    }
    Err(Error::new(
        "an insta snapshot whose contents are not a frame (cells text, a ratatui Buffer's Debug \
         form or a TestBackend's Display form)",
    ))
}

/// Reads `text` as one of the frame forms that announce themselves (cells text, a ratatui
/// buffer's `Debug`); `None` for any other text.
fn frame_text(text: &str) -> Option<Result<(TermFrame, FrameFormat), Error>> {
    if text.starts_with(HEADER) {
        return Some(from_cells_text(text).map(|f| (f, FrameFormat::Cells)));
    }
    if text.starts_with(BUFFER_DEBUG_HEADER) {
        return Some(from_buffer_debug(text).map(|f| (f, FrameFormat::BufferDebug)));
    }
    // `insta::assert_debug_snapshot!(terminal.backend())`: the buffer's `Debug` inside.
    if let Some(at) = text
        .strip_prefix(BACKEND_DEBUG_HEADER)
        .and_then(|rest| rest.find(BACKEND_BUFFER_FIELD))
    {
        let buffer = &text[BACKEND_DEBUG_HEADER.len() + at + "buffer: ".len()..];
        return Some(from_buffer_debug(buffer).map(|f| (f, FrameFormat::BufferDebug)));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn oversized_text_frames_are_refused() {
        let tall = "x\n".repeat(2001);
        assert_eq!(
            parse_frame(tall.as_bytes()).unwrap_err().to_string(),
            "text frame is 1x2001 cells; the limit is 4000x2000"
        );
    }

    #[test]
    fn insta_snapshots_read_without_their_header() {
        let snap = "---\nsource: tests/x.rs\nexpression: cells_text(&buf)\n---\nratatui-cells v1 2x1\n\"ok\"\nstyles:\ny0 x0-1 bold\n";
        let (f, format) = parse_frame(snap.as_bytes()).unwrap();
        assert_eq!((f.cols, f.rows, format), (2, 1, FrameFormat::Cells));
        assert_eq!(f.cell(1, 0).modifiers, ratatui_core::style::Modifier::BOLD);
        let other = "---\nsource: tests/x.rs\n---\n{\"json\": 1}\n";
        assert_eq!(
            parse_frame(other.as_bytes()).unwrap_err().to_string(),
            "an insta snapshot whose contents are not a frame (cells text, a ratatui Buffer's \
             Debug form or a TestBackend's Display form)"
        );
        let display =
            "---\nsource: tests/x.rs\nexpression: terminal.backend()\n---\n\"ok\"\n\"  \"\n";
        let (f, format) = parse_frame(display.as_bytes()).unwrap();
        assert_eq!(
            (f.cols, f.rows, format),
            (2, 2, FrameFormat::BackendDisplay)
        );
    }
}
