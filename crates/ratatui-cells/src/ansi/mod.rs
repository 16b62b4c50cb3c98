//! Reading the bytes a terminal receives back into cells: one pass of a VT parser (`vte`) over
//! the crate's own grid ([`Screen`]), at a given size or at the size the bytes draw into.

mod grid;
mod pen;
mod perform;
mod screen;

pub use screen::Screen;

use crate::frame::TermFrame;
use crate::limits::{too_large, MAX_FRAME};

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

/// Reads ANSI bytes on a screen sized by what they draw (the furthest row and column they
/// write), never over [`MAX_FRAME`] (what lies beyond is cut off). A screen one row taller is
/// used, so a newline after the last row does not scroll it away.
fn model(fixed: &[u8], cols: usize, rows: usize) -> TermFrame {
    let (cols, rows) = (cols.clamp(1, MAX_FRAME.0), rows.clamp(1, MAX_FRAME.1));
    // Both within MAX_FRAME, so they fit a u16.
    let mut screen = Screen::new(cols as u16, rows as u16 + 1);
    screen.process(fixed);
    screen.frame_part(cols, rows)
}

/// Replays ANSI bytes and reads back every cell, the screen sized by what the bytes draw, but
/// never over [`MAX_FRAME`] (what lies beyond is cut off). A bare `\n` is taken as a new line
/// (as a tty's output processing would make it).
#[must_use]
pub fn from_ansi(bytes: &[u8]) -> TermFrame {
    let fixed = with_carriage_returns(bytes);
    let (rows, cols) = extent(&fixed);
    model(&fixed, cols, rows)
}

/// What a terminal of `cols` × `rows` shows after these bytes: the real size, whatever the
/// bytes draw, with each grapheme cluster whole in one cell (skin tones, flags, ZWJ sequences,
/// keycaps, combining marks, CJK), laid out with ratatui's widths, both colours, the underline
/// colour and all nine attributes, read in one pass. Colours 0–15 read as the named colours
/// whichever way they were sent (`ESC[32m` and `ESC[38;5;2m` select the same palette entry). A
/// bare `\n` is taken as a new line, as a tty's output processing would make it.
#[must_use]
pub fn from_ansi_sized(bytes: &[u8], cols: u16, rows: u16) -> TermFrame {
    let mut screen = Screen::new(cols, rows);
    screen.process(&with_carriage_returns(bytes));
    screen.frame()
}

/// [`from_ansi`] that refuses a stream drawing beyond [`MAX_FRAME`] instead of cutting it.
///
/// # Errors
/// The size the stream draws into, when over the limit.
pub fn try_from_ansi(bytes: &[u8]) -> Result<TermFrame, crate::Error> {
    let fixed = with_carriage_returns(bytes);
    let (rows, cols) = extent(&fixed);
    if cols > MAX_FRAME.0 || rows > MAX_FRAME.1 {
        return Err(too_large("ANSI frame", cols, rows));
    }
    Ok(model(&fixed, cols, rows))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::TermCell;
    use ratatui_core::style::{Color, Modifier};

    #[test]
    fn truecolor_half_blocks_read_back() {
        let f = from_ansi(
            "\x1b[38;2;1;2;3m\x1b[48;2;4;5;6m▀▀\x1b[0m\n\x1b[38;5;196m▄ \x1b[0m\n".as_bytes(),
        );
        assert_eq!((f.cols, f.rows), (2, 2));
        assert_eq!(f.cell(1, 0).fg, Color::Rgb(1, 2, 3));
        assert_eq!(f.cell(1, 0).bg, Color::Rgb(4, 5, 6));
        assert_eq!(f.cell(0, 1).fg, Color::Indexed(196));
        assert_eq!(f.cell(1, 1).glyph, ' ');
    }

    #[test]
    fn a_cursor_far_away_is_refused_or_cut_to_the_limit() {
        assert_eq!(
            try_from_ansi(b"\x1b[65535;65535Hx")
                .unwrap_err()
                .to_string(),
            "ANSI frame is 65535x65535 cells; the limit is 4000x2000"
        );
        let huge = b"\x1b[99999999999999999999999;18446744073709551615H\x1b[18446744073709551615Cx";
        assert!(try_from_ansi(huge).is_err());
        let cut = from_ansi(b"\x1b[3000;5Hx");
        assert_eq!((cut.cols, cut.rows), (5, 2000));
    }

    #[test]
    fn moves_without_a_number_move_by_one() {
        let f = try_from_ansi(b"\x1b[?2026h\x1b[2J\x1b[Hab\x1b[B\x1b[Cc\x1b[?2026l").unwrap();
        assert_eq!((f.cols, f.rows), (4, 2));
        assert_eq!(f.cell(3, 1).glyph, 'c');
    }

    #[test]
    fn a_sized_read_is_the_whole_screen_with_attributes() {
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

    fn row(f: &TermFrame, y: usize) -> String {
        (0..f.cols)
            .map(|x| f.cell(x, y).glyph.to_string())
            .collect()
    }

    #[test]
    fn a_scrolling_region_moves_only_its_rows() {
        let f = from_ansi_sized(b"a\r\nb\r\nc\r\nd\x1b[2;3r\x1b[3;1H\n\x1b[r", 1, 4);
        assert_eq!((0..4).map(|y| row(&f, y)).collect::<String>(), "ac d");
        let f = from_ansi_sized(b"a\r\nb\r\nc\x1b[2;3r\x1b[2;1H\x1bM", 1, 3);
        assert_eq!((0..3).map(|y| row(&f, y)).collect::<String>(), "a b");
    }

    #[test]
    fn erasing_inserting_and_deleting_cells() {
        let f = from_ansi_sized(b"abcdef\x1b[1;3H\x1b[44m\x1b[K", 6, 1);
        assert_eq!(row(&f, 0), "ab    ");
        assert_eq!(
            (f.cell(1, 0).bg, f.cell(2, 0).bg),
            (Color::Reset, Color::Blue)
        );
        let f = from_ansi_sized(b"abcdef\x1b[1;2H\x1b[2P\x1b[1;1H\x1b[@", 6, 1);
        assert_eq!(row(&f, 0), " adef ");
        let f = from_ansi_sized(b"abcdef\x1b[1;2H\x1b[3X", 6, 1);
        assert_eq!(row(&f, 0), "a   ef");
    }

    #[test]
    fn text_wraps_at_the_edge_unless_autowrap_is_off() {
        let f = from_ansi_sized(b"abcde", 3, 2);
        assert_eq!((row(&f, 0), row(&f, 1)), ("abc".into(), "de ".into()));
        let f = from_ansi_sized(b"\x1b[?7labcde", 3, 2);
        assert_eq!((row(&f, 0), row(&f, 1)), ("abe".into(), "   ".into()));
    }

    #[test]
    fn half_of_a_wide_character_overwritten_erases_the_other_half() {
        let f = from_ansi_sized("界x\x1b[1;2Hy".as_bytes(), 4, 1);
        assert_eq!(row(&f, 0), " yx ");
        let f = from_ansi_sized("ab\x1b[1;1H界".as_bytes(), 3, 1);
        assert_eq!(f.cell(0, 0).glyph, "界");
        assert!(f.cell(1, 0).glyph.is_continuation());
    }

    #[test]
    fn every_attribute_and_colour_form_reads_in_one_pass() {
        let f = from_ansi_sized(
            b"\x1b[1;2;3;4;5;7;8;9m\x1b[38:2::1:2:3;48:5:200;58:2:4:5:6ma\x1b[0;6;4:3;58;5;9;21mb\x1b[4:0;59;22;25mc",
            3,
            1,
        );
        let a = f.cell(0, 0);
        assert_eq!(a.modifiers, Modifier::all() - Modifier::RAPID_BLINK);
        assert_eq!(
            (a.fg, a.bg, a.underline),
            (
                Color::Rgb(1, 2, 3),
                Color::Indexed(200),
                Color::Rgb(4, 5, 6)
            )
        );
        let b = f.cell(1, 0);
        assert_eq!(
            (b.modifiers, b.underline),
            (
                Modifier::RAPID_BLINK | Modifier::UNDERLINED,
                Color::LightRed
            )
        );
        let c = f.cell(2, 0);
        assert_eq!(
            (c.modifiers, c.underline),
            (Modifier::empty(), Color::Reset)
        );
        assert_eq!(
            *f.cell(2, 0),
            TermCell {
                glyph: 'c'.into(),
                ..TermCell::default()
            }
        );
    }
}
