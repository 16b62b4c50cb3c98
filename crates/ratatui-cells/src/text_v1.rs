//! The first cells text form, `halfcast-cells v1`, still read so older files diff: one line per
//! row of `GLYPH` + fg hex + `/` + bg hex cells (`~~~~~~` = default), 24-bit colours only and no
//! attributes. Nothing writes it any more.

use ratatui_core::style::Color;

use crate::cell::TermCell;
use crate::frame::TermFrame;

/// First line of the first cells text form.
pub const CELLS_HEADER_V1: &str = "halfcast-cells v1";

/// Characters from one cell's start to the next: 14 for the cell, 1 space.
const CELL_STRIDE: usize = 15;

/// How the terminal's default colour was written.
const DEFAULT: &str = "~~~~~~";

fn parse_colour(s: &str) -> Option<Color> {
    if s == DEFAULT {
        return Some(Color::Reset);
    }
    if s.len() != 6 || !s.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    let v = u32::from_str_radix(s, 16).ok()?;
    Some(Color::Rgb((v >> 16) as u8, (v >> 8) as u8, v as u8))
}

/// Reads a `halfcast-cells v1` file (cells written before attributes were kept); errors name the line.
///
/// # Errors
/// A header that is not `halfcast-cells v1 COLSxROWS`, or a malformed row or cell.
pub fn from_cells_text_v1(text: &str) -> Result<TermFrame, String> {
    let mut lines = text.lines();
    let (cols, rows) =
        crate::text::cells_header(lines.next().unwrap_or_default(), CELLS_HEADER_V1)?;
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
            cells.push(TermCell::new(
                glyph,
                parse_colour(&fg).ok_or_else(bad)?,
                parse_colour(&bg).ok_or_else(bad)?,
            ));
        }
    }
    Ok(TermFrame { cols, rows, cells })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn v1_reads_with_default_colours() {
        let frame =
            from_cells_text_v1("halfcast-cells v1 2x1\n▀a0b0c0/101010  ~~~~~~/~~~~~~\n").unwrap();
        assert_eq!(
            frame.cells,
            [
                TermCell::new('▀', Color::Rgb(0xa0, 0xb0, 0xc0), Color::Rgb(16, 16, 16)),
                TermCell::default(),
            ]
        );
    }

    #[test]
    fn malformed_rows_name_their_line() {
        assert_eq!(
            from_cells_text_v1("halfcast-cells v1 2x1\n▀000000/000000\n").unwrap_err(),
            "line 2: 1 cells, expected 2"
        );
    }

    #[test]
    fn a_size_whose_row_length_would_wrap_is_refused() {
        // 17216961135462248175 × 15 wraps to 1 in 64 bits: an empty row once matched it.
        assert_eq!(
            from_cells_text_v1("halfcast-cells v1 17216961135462248175x1\n\n").unwrap_err(),
            "line 1: size 17216961135462248175x1 is over the limit of 4000x2000 cells"
        );
        assert!(from_cells_text_v1("halfcast-cells v1 4001x1\n").is_err());
    }
}
