//! Reading frames back from files: PNG (half-block cells), ANSI (through a terminal model),
//! the cells text form, or plain text.

use std::path::Path;

use super::{from_cells_text, TermCell, TermFrame, CELLS_HEADER};
use crate::color::Rgb;
use crate::encode::palette::xterm_rgb;
use crate::framebuffer::Framebuffer;

/// What kind of frame file was read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameFormat {
    Png,
    Ansi,
    Cells,
    Text,
}

/// Reads a frame file of any supported kind, recognised by content, not by name.
///
/// # Errors
/// An unreadable file, a broken PNG or cells text, with the path in the message.
pub fn load(path: &Path) -> Result<(TermFrame, FrameFormat), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    let named = |e: String| format!("{}: {e}", path.display());
    if bytes.starts_with(b"\x89PNG") {
        let fb = Framebuffer::from_image_bytes(&bytes).map_err(named)?;
        if fb.height() % 2 != 0 {
            return Err(named(format!(
                "PNG height {} is odd; frames are COLS x 2*ROWS pixels",
                fb.height()
            )));
        }
        return Ok((TermFrame::from_framebuffer(&fb), FrameFormat::Png));
    }
    let text =
        String::from_utf8(bytes).map_err(|_| named("not a PNG and not UTF-8 text".into()))?;
    if text.starts_with(CELLS_HEADER) {
        return Ok((from_cells_text(&text).map_err(named)?, FrameFormat::Cells));
    }
    if text.contains('\x1b') {
        return Ok((from_ansi(text.as_bytes()), FrameFormat::Ansi));
    }
    let lines: Vec<Vec<char>> = text.lines().map(|l| l.chars().collect()).collect();
    let cols = lines.iter().map(Vec::len).max().unwrap_or(0);
    let cells = lines
        .iter()
        .flat_map(|l| {
            (0..cols).map(move |x| TermCell {
                glyph: l.get(x).copied().unwrap_or(' '),
                fg: None,
                bg: None,
            })
        })
        .collect();
    Ok((
        TermFrame {
            cols,
            rows: lines.len(),
            cells,
        },
        FrameFormat::Text,
    ))
}

/// The screen size a byte stream draws into: the furthest row and column it writes.
fn extent(bytes: &[u8]) -> (usize, usize) {
    let (mut row, mut col, mut rows, mut cols) = (0usize, 0usize, 0usize, 0usize);
    let mut i = 0;
    let text = String::from_utf8_lossy(bytes);
    let chars: Vec<char> = text.chars().collect();
    while i < chars.len() {
        match chars[i] {
            '\x1b' if chars.get(i + 1) == Some(&'[') => {
                let start = i + 2;
                let mut j = start;
                while j < chars.len() && !('\x40'..='\x7e').contains(&chars[j]) {
                    j += 1;
                }
                let params: String = chars[start..j.min(chars.len())].iter().collect();
                let nums: Vec<usize> = params
                    .split(';')
                    .map(|p| p.trim_start_matches('?').parse().unwrap_or(0))
                    .collect();
                let n = |k: usize| nums.get(k).copied().filter(|&v| v > 0).unwrap_or(1);
                match chars.get(j) {
                    Some('H' | 'f') => {
                        row = n(0) - 1;
                        col = n(1) - 1;
                    }
                    Some('C') => col += n(0),
                    Some('B') => row += n(0),
                    Some('G') => col = n(0) - 1,
                    _ => {}
                }
                i = j + 1;
                continue;
            }
            '\x1b' => i += 1,
            '\r' => col = 0,
            '\n' => row += 1,
            c if !c.is_control() => {
                col += 1;
                cols = cols.max(col);
                rows = rows.max(row + 1);
            }
            _ => {}
        }
        i += 1;
    }
    (rows, cols)
}

/// Replays ANSI bytes through a terminal model (vt100) and reads back every cell.
/// A bare `\n` is taken as a new line (as a tty's output processing would make it).
#[must_use]
pub fn from_ansi(bytes: &[u8]) -> TermFrame {
    let mut fixed = Vec::with_capacity(bytes.len() + 256);
    let mut prev = 0u8;
    for &b in bytes {
        if b == b'\n' && prev != b'\r' {
            fixed.push(b'\r');
        }
        fixed.push(b);
        prev = b;
    }
    let (rows, cols) = extent(&fixed);
    let (rows, cols) = (
        rows.clamp(1, u16::MAX as usize),
        cols.clamp(1, u16::MAX as usize),
    );
    let mut parser = vt100::Parser::new(rows as u16 + 1, cols as u16, 0);
    parser.process(&fixed);
    from_screen(parser.screen(), cols, rows)
}

/// Reads the top-left `cols` × `rows` cells of a terminal model's screen.
#[must_use]
pub fn from_screen(screen: &vt100::Screen, cols: usize, rows: usize) -> TermFrame {
    let colour = |c: vt100::Color| match c {
        vt100::Color::Default => None,
        vt100::Color::Idx(n) => Some(xterm_rgb(n)),
        vt100::Color::Rgb(r, g, b) => Some(Rgb::new(r, g, b)),
    };
    let mut cells = Vec::with_capacity(rows * cols);
    for y in 0..rows {
        for x in 0..cols {
            let cell = screen.cell(y as u16, x as u16);
            let (glyph, fg, bg) = cell.map_or((' ', None, None), |c| {
                (
                    c.contents().chars().next().unwrap_or(' '),
                    colour(c.fgcolor()),
                    colour(c.bgcolor()),
                )
            });
            cells.push(TermCell { glyph, fg, bg });
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
        assert_eq!(f.cell(1, 0).fg, Some(Rgb::new(1, 2, 3)));
        assert_eq!(f.cell(1, 0).bg, Some(Rgb::new(4, 5, 6)));
        assert_eq!(f.cell(0, 1).fg, Some(Rgb::new(255, 0, 0)));
        assert_eq!(f.cell(1, 1).glyph, ' ');
    }

    #[test]
    fn cursor_positioned_frames_size_themselves() {
        let f = from_ansi(b"\x1b[3;5Hab\x1b[1;1Hc");
        assert_eq!((f.cols, f.rows), (6, 3));
        assert_eq!(f.cell(5, 2).glyph, 'b');
    }
}
