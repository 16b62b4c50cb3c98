//! Reading frames back from files: PNG (half-block cells), ANSI (through a terminal model),
//! the cells text form, or plain text.

use std::path::Path;

use super::ratatui_debug::{from_buffer_debug, BUFFER_DEBUG_HEADER};
#[cfg(any(test, feature = "vt100"))]
use super::sgr_passes::{main_pass, mentions, rewrite, underline_as_foreground, ATTRIBUTE_PASSES};
use super::text::read_grid_row;
use super::text_v1::CELLS_HEADER_V1;
use super::{from_cells_text, TermCell, TermFrame, CELLS_HEADER};
use crate::color::Rgb;
use crate::render::framebuffer::Framebuffer;

/// What kind of frame file was read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameFormat {
    /// A PNG of COLS × 2·ROWS pixels.
    Png,
    /// ANSI escape sequences, read through a terminal model.
    Ansi,
    /// halfcast's cells text (glyph grid and style runs).
    Cells,
    /// A ratatui `Buffer`'s `Debug` form (what `insta::assert_debug_snapshot!(buffer)` pins).
    BufferDebug,
    /// Plain text, one character per cell.
    Text,
}

/// Largest frame read back, in cells: `render`'s own limit, so every frame it writes loads.
/// Sizes found in a file are checked against it before anything is allocated.
pub const MAX_FRAME: (usize, usize) = (4000, 2000);

/// Most bytes a frame file may hold (a 4000×2000 frame of distinct colours does not fit, but
/// anything a person diffs does). Only regular files are read: a FIFO or `/dev/zero` is refused.
pub const MAX_FRAME_BYTES: u64 = 64 << 20;

/// The error for a frame larger than [`MAX_FRAME`].
fn too_large(what: &str, cols: usize, rows: usize) -> String {
    let (mc, mr) = MAX_FRAME;
    format!("{what} is {cols}x{rows} cells; the limit is {mc}x{mr}")
}

/// Reads a frame file of any supported kind, recognised by content, not by name.
///
/// # Errors
/// An unreadable or oversized file, a FIFO or device, a broken PNG or cells text, a frame over [`MAX_FRAME`],
/// with the path in the message.
pub fn load(path: &Path) -> Result<(TermFrame, FrameFormat), String> {
    let bytes = crate::input_file::read_regular_capped(path, MAX_FRAME_BYTES)
        .map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    parse_frame(&bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// Parses a frame file's bytes (what [`load`] does after reading; the fuzz targets call it).
///
/// # Errors
/// A broken PNG or cells text, a frame over [`MAX_FRAME`], bytes that are not UTF-8 text.
pub fn parse_frame(bytes: &[u8]) -> Result<(TermFrame, FrameFormat), String> {
    if bytes.starts_with(b"\x89PNG") {
        let (mc, mr) = MAX_FRAME;
        let img = crate::texture::decode::decode_within(bytes, mc as u32, 2 * mr as u32)?.to_rgb8();
        let (w, h) = (img.width() as usize, img.height() as usize);
        if h % 2 != 0 {
            return Err(format!(
                "PNG height {h} is odd; frames are COLS x 2*ROWS pixels"
            ));
        }
        let mut fb = Framebuffer::new(w, h);
        for (x, y, p) in img.enumerate_pixels() {
            fb.set(x as usize, y as usize, Rgb::new(p[0], p[1], p[2]));
        }
        return Ok((TermFrame::from_framebuffer(&fb), FrameFormat::Png));
    }
    let text = std::str::from_utf8(bytes).map_err(|_| "not a PNG and not UTF-8 text")?;
    if let Some(body) = insta_body(text) {
        return frame_text(body).unwrap_or_else(|| {
            Err(
                "an insta snapshot whose contents are not a frame (halfcast cells text or a \
                 ratatui Buffer's Debug form)"
                    .into(),
            )
        });
    }
    if let Some(frame) = frame_text(text) {
        return frame;
    }
    if text.contains('\x1b') {
        #[cfg(any(test, feature = "vt100"))]
        return Ok((try_from_ansi(text.as_bytes())?, FrameFormat::Ansi));
        #[cfg(not(any(test, feature = "vt100")))]
        return Err("reading ANSI frames needs halfcast's `vt100` feature".into());
    }
    let rows = text.lines().count();
    // Characters bound the columns (a cluster or a wide character is at most one per char),
    // so an oversized text is refused before any row is read into cells.
    let widest = text.lines().map(|l| l.chars().count()).max().unwrap_or(0);
    if widest > 2 * MAX_FRAME.0 || rows > MAX_FRAME.1 {
        return Err(too_large("text frame", widest, rows));
    }
    let lines: Vec<Vec<super::Glyph>> = text.lines().map(read_grid_row).collect();
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
    Ok((TermFrame { cols, rows, cells }, FrameFormat::Text))
}

/// The contents of an insta `.snap` file (the header between its `---` lines removed), when
/// `text` is one.
fn insta_body(text: &str) -> Option<&str> {
    let rest = text.strip_prefix("---\n")?;
    let end = rest.find("\n---\n")?;
    Some(&rest[end + 5..])
}

/// Reads `text` as one of the frame forms that announce themselves (halfcast cells text, a
/// ratatui buffer's `Debug`); `None` for any other text.
fn frame_text(text: &str) -> Option<Result<(TermFrame, FrameFormat), String>> {
    if text.starts_with(CELLS_HEADER) || text.starts_with(CELLS_HEADER_V1) {
        return Some(from_cells_text(text).map(|f| (f, FrameFormat::Cells)));
    }
    if text.starts_with(BUFFER_DEBUG_HEADER) {
        return Some(from_buffer_debug(text).map(|f| (f, FrameFormat::BufferDebug)));
    }
    None
}

#[cfg(any(test, feature = "vt100"))]
/// The screen size a byte stream draws into: the furthest row and column it writes.
/// Counts saturate, so any numbers in the stream give an answer (checked by the caller).
fn extent(bytes: &[u8]) -> (usize, usize) {
    let (mut row, mut col, mut rows, mut cols) = (0usize, 0usize, 0usize, 0usize);
    let text = String::from_utf8_lossy(bytes);
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\x1b' if chars.peek() == Some(&'[') => {
                chars.next();
                let mut params = String::new();
                let mut last = None;
                for c in chars.by_ref() {
                    if ('\x40'..='\x7e').contains(&c) {
                        last = Some(c);
                        break;
                    }
                    if params.len() < 64 {
                        params.push(c);
                    }
                }
                let nums: Vec<usize> = params
                    .split(';')
                    .map(|p| {
                        let p = p.trim_start_matches('?');
                        // Empty or not a number: the default. All digits but too big: huge.
                        if p.is_empty() || !p.bytes().all(|b| b.is_ascii_digit()) {
                            0
                        } else {
                            p.parse().unwrap_or(usize::MAX)
                        }
                    })
                    .collect();
                let n = |k: usize| nums.get(k).copied().filter(|&v| v > 0).unwrap_or(1);
                match last {
                    Some('H' | 'f') => {
                        row = n(0) - 1;
                        col = n(1) - 1;
                    }
                    Some('C') => col = col.saturating_add(n(0)),
                    Some('B') => row = row.saturating_add(n(0)),
                    Some('G') => col = n(0) - 1,
                    _ => {}
                }
            }
            '\x1b' => {
                // ESC and the one character after it (`ESC 7`, `ESC (`…) draw nothing.
                chars.next();
            }
            '\r' => col = 0,
            '\n' => row = row.saturating_add(1),
            c if !c.is_control() => {
                col = col.saturating_add(1);
                cols = cols.max(col);
                rows = rows.max(row.saturating_add(1));
            }
            _ => {}
        }
    }
    (rows, cols)
}

#[cfg(any(test, feature = "vt100"))]
/// A bare `\n` taken as a new line (as a tty's output processing would make it).
fn with_carriage_returns(bytes: &[u8]) -> Vec<u8> {
    let mut fixed = Vec::with_capacity(bytes.len() + 256);
    let mut prev = 0u8;
    for &b in bytes {
        if b == b'\n' && prev != b'\r' {
            fixed.push(b'\r');
        }
        fixed.push(b);
        prev = b;
    }
    fixed
}

#[cfg(any(test, feature = "vt100"))]
/// Replays ANSI bytes through a terminal model `cols` × `rows` (at most [`MAX_FRAME`]).
fn model(fixed: &[u8], cols: usize, rows: usize) -> TermFrame {
    let (cols, rows) = (cols.clamp(1, MAX_FRAME.0), rows.clamp(1, MAX_FRAME.1));
    // A row more than is read, so a newline after the last row does not scroll it away.
    read_through_model(fixed, (cols as u16, rows as u16 + 1), (cols, rows))
}

#[cfg(any(test, feature = "vt100"))]
/// Reads the top-left `read` cells of a vt100 terminal of `size` (cols, rows) after `fixed`,
/// with every attribute: the main reading, then one more for each lost attribute or the
/// underline colour that the stream uses at all (see `sgr_passes`).
fn read_through_model(fixed: &[u8], size: (u16, u16), read: (usize, usize)) -> TermFrame {
    use ratatui::style::Modifier;
    let screen = |pass| {
        let mut parser = vt100::Parser::new(size.1, size.0, 0);
        parser.process(&rewrite(fixed, pass));
        from_screen(parser.screen(), read.0, read.1)
    };
    let mut frame = screen(main_pass);
    for (modifier, on, pass) in ATTRIBUTE_PASSES {
        if mentions(fixed, on) {
            for (cell, seen) in frame.cells.iter_mut().zip(screen(pass).cells) {
                if seen.modifiers.contains(Modifier::BOLD) {
                    cell.modifiers |= modifier;
                }
            }
        }
    }
    if mentions(fixed, b"58") || mentions(fixed, b"59") {
        for (cell, seen) in frame
            .cells
            .iter_mut()
            .zip(screen(underline_as_foreground).cells)
        {
            cell.underline = seen.fg;
        }
    }
    frame
}

#[cfg(any(test, feature = "vt100"))]
/// Replays ANSI bytes through a terminal model (vt100) and reads back every cell, the screen
/// sized by what the bytes draw, but never over [`MAX_FRAME`] (what lies beyond is cut off).
/// A bare `\n` is taken as a new line (as a tty's output processing would make it).
#[must_use]
pub fn from_ansi(bytes: &[u8]) -> TermFrame {
    let fixed = with_carriage_returns(bytes);
    let (rows, cols) = extent(&fixed);
    model(&fixed, cols, rows)
}

#[cfg(any(test, feature = "vt100"))]
/// What a terminal of `cols` × `rows` shows after these bytes (through the vt100 model): the
/// real size, whatever the bytes draw, with each cell's grapheme, colours, underline colour and
/// all nine attributes. The model itself keeps only bold, italic, underline and reverse video,
/// so the bytes are read again once for each other attribute and for the underline colour that
/// they use, with it sent as one the model keeps. Colours 0–15 read as named colours whichever
/// way they were sent (`ESC[32m` and `ESC[38;5;2m` select the same palette entry). A bare `\n`
/// is taken as a new line, as a tty's output processing would make it. The model gives an
/// emoji's skin-tone modifier columns of its own, so a row holding `👍🏽` reads shifted from
/// there on.
#[must_use]
pub fn from_ansi_sized(bytes: &[u8], cols: u16, rows: u16) -> TermFrame {
    let (cols, rows) = (cols.max(1), rows.max(1));
    let fixed = with_carriage_returns(bytes);
    read_through_model(&fixed, (cols, rows), (usize::from(cols), usize::from(rows)))
}

#[cfg(any(test, feature = "vt100"))]
/// [`from_ansi`] that refuses a stream drawing beyond [`MAX_FRAME`] instead of cutting it.
///
/// # Errors
/// The size the stream draws into, when over the limit.
pub fn try_from_ansi(bytes: &[u8]) -> Result<TermFrame, String> {
    let fixed = with_carriage_returns(bytes);
    let (rows, cols) = extent(&fixed);
    if cols > MAX_FRAME.0 || rows > MAX_FRAME.1 {
        return Err(too_large("ANSI frame", cols, rows));
    }
    Ok(model(&fixed, cols, rows))
}

#[cfg(any(test, feature = "vt100"))]
/// Reads the top-left `cols` × `rows` cells of a terminal model's screen, colours 0–15 as
/// named. A screen holds only the attributes the model keeps (bold, italic, underline, reverse
/// video); [`from_ansi_sized`], which has the bytes, reads all of them.
#[must_use]
pub fn from_screen(screen: &vt100::Screen, cols: usize, rows: usize) -> TermFrame {
    use ratatui::style::{Color, Modifier};
    let colour = |c: vt100::Color| match c {
        vt100::Color::Default => Color::Reset,
        vt100::Color::Idx(n) => super::named_colour(n).unwrap_or(Color::Indexed(n)),
        vt100::Color::Rgb(r, g, b) => Color::Rgb(r, g, b),
    };
    let mut cells = Vec::with_capacity(rows * cols);
    for y in 0..rows {
        for x in 0..cols {
            let Some(cell) = screen.cell(y as u16, x as u16) else {
                cells.push(TermCell::default());
                continue;
            };
            if cell.is_wide_continuation() && x > 0 {
                // The wide character's second column, in its style (as from_buffer reads it).
                let lead: &TermCell = &cells[cells.len() - 1];
                cells.push(TermCell {
                    glyph: super::Glyph::CONTINUATION,
                    ..lead.clone()
                });
                continue;
            }
            let contents = cell.contents();
            let mut modifiers = Modifier::empty();
            for (on, m) in [
                (cell.bold(), Modifier::BOLD),
                (cell.italic(), Modifier::ITALIC),
                (cell.underline(), Modifier::UNDERLINED),
                (cell.inverse(), Modifier::REVERSED),
            ] {
                if on {
                    modifiers |= m;
                }
            }
            cells.push(TermCell {
                glyph: if contents.is_empty() {
                    super::Glyph::default()
                } else {
                    super::Glyph::new(&contents)
                },
                fg: colour(cell.fgcolor()),
                bg: colour(cell.bgcolor()),
                underline: Color::Reset,
                modifiers,
            });
        }
    }
    TermFrame { cols, rows, cells }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn truecolor_half_blocks_read_back() {
        let f = from_ansi(
            "\x1b[38;2;1;2;3m\x1b[48;2;4;5;6m▀▀\x1b[0m\n\x1b[38;5;196m▄ \x1b[0m\n".as_bytes(),
        );
        assert_eq!((f.cols, f.rows), (2, 2));
        assert_eq!(f.cell(1, 0).fg_rgb(), Some(Rgb::new(1, 2, 3)));
        assert_eq!(f.cell(1, 0).bg_rgb(), Some(Rgb::new(4, 5, 6)));
        assert_eq!(f.cell(0, 1).fg, ratatui::style::Color::Indexed(196));
        assert_eq!(f.cell(1, 1).glyph, ' ');
    }

    #[test]
    fn a_cursor_far_away_is_refused_or_cut_to_the_limit() {
        assert_eq!(
            try_from_ansi(b"\x1b[65535;65535Hx").unwrap_err(),
            "ANSI frame is 65535x65535 cells; the limit is 4000x2000"
        );
        let huge = b"\x1b[99999999999999999999999;18446744073709551615H\x1b[18446744073709551615Cx";
        assert!(try_from_ansi(huge).is_err());
        let cut = from_ansi(b"\x1b[3000;5Hx");
        assert_eq!((cut.cols, cut.rows), (5, 2000));
    }

    #[test]
    fn oversized_text_frames_are_refused() {
        let tall = "x\n".repeat(2001);
        assert_eq!(
            parse_frame(tall.as_bytes()).unwrap_err(),
            "text frame is 1x2001 cells; the limit is 4000x2000"
        );
    }

    #[test]
    fn insta_snapshots_read_without_their_header() {
        let snap = "---\nsource: tests/x.rs\nexpression: cells_text(&buf)\n---\nhalfcast-cells v2 2x1\n\"ok\"\nstyles:\ny0 x0-1 bold\n";
        let (f, format) = parse_frame(snap.as_bytes()).unwrap();
        assert_eq!((f.cols, f.rows, format), (2, 1, FrameFormat::Cells));
        assert_eq!(f.cell(1, 0).modifiers, ratatui::style::Modifier::BOLD);
        let other = "---\nsource: tests/x.rs\n---\n{\"json\": 1}\n";
        assert_eq!(
            parse_frame(other.as_bytes()).unwrap_err(),
            "an insta snapshot whose contents are not a frame (halfcast cells text or a ratatui \
             Buffer's Debug form)"
        );
    }

    #[test]
    fn moves_without_a_number_move_by_one() {
        let f = try_from_ansi(b"\x1b[?2026h\x1b[2J\x1b[Hab\x1b[B\x1b[Cc\x1b[?2026l").unwrap();
        assert_eq!((f.cols, f.rows), (4, 2));
        assert_eq!(f.cell(3, 1).glyph, 'c');
    }

    #[test]
    fn a_sized_read_is_the_whole_screen_with_attributes() {
        use ratatui::style::{Color, Modifier};
        let f = from_ansi_sized(
            b"\x1b[1;7;32mhel\x1b[0;38;5;2ml\x1b[38;5;100;2;9;58;5;200mo\x1b[22;1m!",
            20,
            5,
        );
        assert_eq!((f.cols, f.rows), (20, 5));
        assert_eq!(f.cell(0, 0).modifiers, Modifier::BOLD | Modifier::REVERSED);
        assert_eq!(f.cell(0, 0).fg, Color::Green);
        assert_eq!(f.cell(3, 0).fg, Color::Green);
        assert_eq!(f.cell(4, 0).fg, Color::Indexed(100));
        assert_eq!(
            f.cell(4, 0).modifiers,
            Modifier::DIM | Modifier::CROSSED_OUT
        );
        assert_eq!(f.cell(4, 0).underline, Color::Indexed(200));
        assert_eq!(
            f.cell(5, 0).modifiers,
            Modifier::BOLD | Modifier::CROSSED_OUT
        );
        assert_eq!(*f.cell(19, 4), TermCell::default());
        let wide = from_ansi_sized("\x1b[44m界e\u{301}".as_bytes(), 4, 1);
        assert_eq!(wide.cell(0, 0).glyph, "界");
        assert!(wide.cell(1, 0).glyph.is_continuation());
        assert_eq!(wide.cell(1, 0).bg, Color::Blue);
        assert_eq!(wide.cell(2, 0).glyph, "e\u{301}");
    }

    #[test]
    fn cursor_positioned_frames_size_themselves() {
        let f = from_ansi(b"\x1b[3;5Hab\x1b[1;1Hc");
        assert_eq!((f.cols, f.rows), (6, 3));
        assert_eq!(f.cell(5, 2).glyph, 'b');
    }
}
