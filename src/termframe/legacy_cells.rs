//! The cells text forms halfcast wrote before the format became ratatui-cells', still read so
//! older files and snapshots diff. Nothing writes them any more.
//!
//! - `halfcast-cells v2`: the ratatui-cells format under halfcast's first name; only the header
//!   differs, so it reads as ratatui-cells' cells text.
//! - `halfcast-cells v1`: one line per row of `GLYPH` + fg hex + `/` + bg hex cells (`~~~~~~` =
//!   default), 24-bit colours only and no attributes.

use ratatui::style::Color;
use ratatui_cells::format::{from_cells_text, HEADER};

use crate::termframe::{TermCell, TermFrame, MAX_FRAME};

/// First line of the first cells text form.
const CELLS_HEADER_V1: &str = "halfcast-cells v1";

/// First line of the second form: ratatui-cells' format under halfcast's first name.
const CELLS_HEADER_V2: &str = "halfcast-cells v2";

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

/// Reads `text` when it is one of halfcast's older cells text forms (after an insta header, if
/// any); `None` for any other text.
pub(super) fn read_legacy(text: &str) -> Option<Result<TermFrame, String>> {
    let body = text
        .strip_prefix("---\n")
        .and_then(|rest| rest.find("\n---\n").map(|end| &rest[end + 5..]))
        .unwrap_or(text);
    if let Some(rest) = body.strip_prefix(CELLS_HEADER_V2) {
        return Some(from_cells_text(&format!("{HEADER}{rest}")).map_err(|e| e.to_string()));
    }
    body.starts_with(CELLS_HEADER_V1)
        .then(|| from_cells_text_v1(body))
}

/// The size a `halfcast-cells v1` first line gives, within [`MAX_FRAME`].
fn v1_header(header: &str) -> Result<(usize, usize), String> {
    let size = header
        .strip_prefix(CELLS_HEADER_V1)
        .map(str::trim)
        .ok_or_else(|| format!("line 1: expected '{CELLS_HEADER_V1} COLSxROWS'"))?;
    let (c, r) = size.split_once('x').ok_or("line 1: bad size")?;
    let (cols, rows): (usize, usize) = (
        c.parse().map_err(|_| "line 1: bad size")?,
        r.parse().map_err(|_| "line 1: bad size")?,
    );
    let (max_cols, max_rows) = MAX_FRAME;
    if cols > max_cols || rows > max_rows {
        return Err(format!(
            "line 1: size {cols}x{rows} is over the limit of {max_cols}x{max_rows} cells"
        ));
    }
    Ok((cols, rows))
}

/// Reads a `halfcast-cells v1` file (cells written before attributes were kept); errors name
/// the line.
fn from_cells_text_v1(text: &str) -> Result<TermFrame, String> {
    let mut lines = text.lines();
    let (cols, rows) = v1_header(lines.next().unwrap_or_default())?;
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
    fn v2_reads_as_the_ratatui_cells_format() {
        let frame = read_legacy("halfcast-cells v2 2x1\n\"ok\"\nstyles:\ny0 x1 bold\n")
            .unwrap()
            .unwrap();
        assert_eq!(frame.cell(1, 0).modifiers, ratatui::style::Modifier::BOLD);
        let snap = "---\nsource: tests/x.rs\n---\nhalfcast-cells v2 1x1\n\"a\"\n";
        assert_eq!(read_legacy(snap).unwrap().unwrap().cell(0, 0).glyph, 'a');
        assert!(read_legacy("ratatui-cells v1 1x1\n\"a\"\n").is_none());
    }

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
