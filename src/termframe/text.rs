//! The colour-aware text form of a frame: one line per row, every cell's glyph and colours,
//! readable in a code review diff (`▀a0b0c0/101010` = glyph, fg hex, bg hex; `~~~~~~` = default).
//! Every cell is exactly 14 characters and cells are joined by one space, so a space glyph is safe.

use std::fmt::Write;

use super::{TermCell, TermFrame};
use crate::color::Rgb;

/// First line of the cells text form; carries the version and the size.
pub const CELLS_HEADER: &str = "halfcast-cells v1";

/// Characters from one cell's start to the next: 14 for the cell, 1 space.
const CELL_STRIDE: usize = 15;

/// How the terminal's default colour is written.
const DEFAULT: &str = "~~~~~~";

fn colour(out: &mut String, c: Option<Rgb>) {
    match c {
        Some(c) => {
            let _ = write!(out, "{:02x}{:02x}{:02x}", c.r, c.g, c.b);
        }
        None => out.push_str(DEFAULT),
    }
}

/// One cell in the text form: glyph, fg hex, `/`, bg hex (14 characters).
#[must_use]
pub fn cell_code(c: &TermCell) -> String {
    let mut out = String::with_capacity(16);
    out.push(c.glyph);
    colour(&mut out, c.fg);
    out.push('/');
    colour(&mut out, c.bg);
    out
}

/// Writes `halfcast-cells v1 COLSxROWS`, then one line per row of space-separated cells.
#[must_use]
pub fn to_cells_text(frame: &TermFrame) -> String {
    let mut out = format!("{CELLS_HEADER} {}x{}\n", frame.cols, frame.rows);
    for y in 0..frame.rows {
        for x in 0..frame.cols {
            if x > 0 {
                out.push(' ');
            }
            out.push_str(&cell_code(frame.cell(x, y)));
        }
        out.push('\n');
    }
    out
}

fn parse_colour(s: &str) -> Option<Option<Rgb>> {
    if s == DEFAULT {
        return Some(None);
    }
    if s.len() != 6 || !s.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    let v = u32::from_str_radix(s, 16).ok()?;
    Some(Some(Rgb::new((v >> 16) as u8, (v >> 8) as u8, v as u8)))
}

/// Reads the cells text form back; errors name the line.
///
/// # Errors
/// A header that is not `halfcast-cells v1 COLSxROWS`, or a malformed row or cell.
pub fn from_cells_text(text: &str) -> Result<TermFrame, String> {
    let mut lines = text.lines();
    let header = lines.next().unwrap_or_default();
    let size = header
        .strip_prefix(CELLS_HEADER)
        .map(str::trim)
        .ok_or_else(|| format!("line 1: expected '{CELLS_HEADER} COLSxROWS'"))?;
    let (c, r) = size.split_once('x').ok_or("line 1: bad size")?;
    let (cols, rows): (usize, usize) = (
        c.parse().map_err(|_| "line 1: bad size")?,
        r.parse().map_err(|_| "line 1: bad size")?,
    );
    let (max_cols, max_rows) = super::MAX_FRAME;
    if cols > max_cols || rows > max_rows {
        return Err(format!(
            "line 1: size {cols}x{rows} is over the limit of {max_cols}x{max_rows} cells"
        ));
    }
    // Both are now small, so `cols * CELL_STRIDE` and `cols * rows` cannot overflow.
    let mut cells = Vec::with_capacity(cols * rows);
    for y in 0..rows {
        let line = lines
            .next()
            .ok_or_else(|| format!("line {}: missing row {y}", y + 2))?;
        let len = line.chars().count();
        if len + 1 != cols * CELL_STRIDE {
            let found = (len + 1) / CELL_STRIDE;
            return Err(format!("line {}: {found} cells, expected {cols}", y + 2));
        }
        let chars: Vec<char> = line.chars().collect();
        for x in 0..cols {
            let cell: String = chars[x * 15..x * 15 + 14].iter().collect();
            let bad = || format!("line {}: cell {x} '{cell}' is not GLYPH FG/BG", y + 2);
            let glyph = chars[x * 15];
            let (fg, bg) = (
                &chars[x * 15 + 1..x * 15 + 7],
                &chars[x * 15 + 8..x * 15 + 14],
            );
            if chars[x * 15 + 7] != '/' {
                return Err(bad());
            }
            let (fg, bg): (String, String) = (fg.iter().collect(), bg.iter().collect());
            cells.push(TermCell {
                glyph,
                fg: parse_colour(&fg).ok_or_else(bad)?,
                bg: parse_colour(&bg).ok_or_else(bad)?,
            });
        }
    }
    Ok(TermFrame { cols, rows, cells })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_with_default_colours() {
        let frame = TermFrame {
            cols: 2,
            rows: 1,
            cells: vec![
                TermCell {
                    glyph: '▀',
                    fg: Some(Rgb::new(0xa0, 0xb0, 0xc0)),
                    bg: Some(Rgb::new(16, 16, 16)),
                },
                TermCell {
                    glyph: ' ',
                    fg: None,
                    bg: None,
                },
            ],
        };
        let text = to_cells_text(&frame);
        assert_eq!(
            text,
            "halfcast-cells v1 2x1\n▀a0b0c0/101010  ~~~~~~/~~~~~~\n"
        );
        assert_eq!(from_cells_text(&text).unwrap(), frame);
    }

    #[test]
    fn malformed_rows_name_their_line() {
        assert_eq!(
            from_cells_text("halfcast-cells v1 2x1\n▀000000/000000\n").unwrap_err(),
            "line 2: 1 cells, expected 2"
        );
        assert!(from_cells_text("nope").is_err());
    }

    #[test]
    fn a_size_whose_row_length_would_wrap_is_refused() {
        // 17216961135462248175 × 15 wraps to 1 in 64 bits: an empty row once matched it.
        assert_eq!(
            from_cells_text("halfcast-cells v1 17216961135462248175x1\n\n").unwrap_err(),
            "line 1: size 17216961135462248175x1 is over the limit of 4000x2000 cells"
        );
        assert!(from_cells_text("halfcast-cells v1 4001x1\n").is_err());
    }
}
