//! The text form of a frame that snapshots pin: the screen's glyphs as a grid a person reads,
//! then the style runs, one line each, naming their row and columns, so a one-cell colour change
//! is a one- or two-line diff that says where.
//!
//! ```text
//! ratatui-cells v1 12x2
//! "Tasks: 3    "
//! "> write     "
//! styles:
//! y0 x0-5 fg=cyan bold
//! y1 x0-6 fg=black bg=green reversed
//! ```
//!
//! - Each grid row is the row's glyphs between quotes (a wide character once, for both its
//!   columns). A row that would not read back cell for cell (a lone combining mark, a control
//!   character) is written in ASCII with `?` for each such cell, and the cell listed under
//!   `glyphs:` by its code points (`y3 x7 U+0065 U+0301`; `continuation` for a wide
//!   character's second column).
//! - A style run is `yROW xCOL` or `xFIRST-LAST`, then the non-default parts: `fg=`, `bg=`,
//!   `ul=` (underline colour) as `green`, `idx2` or `#00cd00`, and the attributes (`bold`,
//!   `dim`, `italic`, `underlined`, `slow_blink`, `rapid_blink`, `reversed`, `hidden`,
//!   `crossed_out`). Cells in no run have the default colours and no attributes.

use std::fmt::Write;

use crate::cell::TermCell;
use crate::error::Error;
use crate::frame::TermFrame;
use crate::glyph::{glyph_row, Glyph};
use crate::limits::MAX_FRAME;

use super::style::{apply_style, style_words, CONTINUATION};

/// First line of the cells text, before the size (`ratatui-cells v1 80x24`): the format's name
/// and version.
pub const HEADER: &str = "ratatui-cells v1";

/// Starts the style runs.
const STYLES: &str = "styles:";

/// Starts the glyphs the grid could not show.
const GLYPHS: &str = "glyphs:";

/// The grid row for `cells`, and the columns whose glyph is listed under `glyphs:` instead.
fn grid_row(cells: &[TermCell]) -> (String, Vec<usize>) {
    let row: String = cells.iter().map(|c| c.glyph.as_str()).collect();
    let glyphs: Vec<&Glyph> = cells.iter().map(|c| &c.glyph).collect();
    let readable =
        !row.chars().any(char::is_control) && glyph_row(&row).iter().eq(glyphs.iter().copied());
    if readable {
        return (row, Vec::new());
    }
    let mut listed = Vec::new();
    let row = cells
        .iter()
        .enumerate()
        .map(|(x, c)| {
            let s = c.glyph.as_str();
            if s.len() == 1 && s.bytes().all(|b| (0x20..0x7f).contains(&b)) {
                c.glyph.first_char()
            } else {
                listed.push(x);
                '?'
            }
        })
        .collect();
    (row, listed)
}

/// The cells text of anything that converts into a [`TermFrame`] (a ratatui `Buffer` or
/// `TestBackend`, owned or borrowed, or a frame): a size header, the glyph grid, then style runs
/// such as `y3 x0-11 fg=green bold` and any glyphs the grid could not show.
#[must_use]
pub fn cells_text(frame: impl Into<TermFrame>) -> String {
    write_frame(&frame.into())
}

/// Writes the frame's cells text.
fn write_frame(frame: &TermFrame) -> String {
    let mut out = format!("{HEADER} {}x{}\n", frame.cols, frame.rows);
    let mut listed = Vec::new();
    let row = |y: usize| &frame.cells[y * frame.cols..(y + 1) * frame.cols];
    for y in 0..frame.rows {
        let (text, xs) = grid_row(row(y));
        let _ = writeln!(out, "\"{text}\"");
        listed.extend(xs.into_iter().map(|x| (x, y)));
    }
    out.push_str(&style_runs(frame));
    if !listed.is_empty() {
        out.push_str(GLYPHS);
        out.push('\n');
        for (x, y) in listed {
            let glyph = &frame.cell(x, y).glyph;
            let code = if glyph.is_continuation() {
                CONTINUATION.to_string()
            } else {
                let points: Vec<String> = glyph
                    .as_str()
                    .chars()
                    .map(|c| format!("U+{:04X}", u32::from(c)))
                    .collect();
                points.join(" ")
            };
            let _ = writeln!(out, "y{y} x{x} {code}");
        }
    }
    out
}

/// The `styles:` section (empty when every cell is plain): one line per run of cells in a row
/// that share a style.
fn style_runs(frame: &TermFrame) -> String {
    let mut runs = String::new();
    for y in 0..frame.rows {
        let row = &frame.cells[y * frame.cols..(y + 1) * frame.cols];
        let mut x = 0;
        while x < row.len() {
            let end = x + row[x..]
                .iter()
                .take_while(|c| c.same_style(&row[x]))
                .count();
            if !row[x].is_plain_style() {
                let cols = if end - x == 1 {
                    format!("x{x}")
                } else {
                    format!("x{x}-{}", end - 1)
                };
                let _ = writeln!(runs, "y{y} {cols} {}", style_words(&row[x]));
            }
            x = end;
        }
    }
    if runs.is_empty() {
        runs
    } else {
        format!("{STYLES}\n{runs}")
    }
}

/// Reads `yROW xCOL` or `yROW xFIRST-LAST` at the start of a list line; the rest of the line.
fn place<'a>(line: &'a str, frame: &TermFrame) -> Option<(usize, usize, usize, &'a str)> {
    let (y, rest) = line.strip_prefix('y')?.split_once(" x")?;
    let (cols, rest) = rest.split_once(' ').unwrap_or((rest, ""));
    let (first, last) = cols.split_once('-').unwrap_or((cols, cols));
    let (y, first, last): (usize, usize, usize) =
        (y.parse().ok()?, first.parse().ok()?, last.parse().ok()?);
    (y < frame.rows && first <= last && last < frame.cols).then_some((y, first, last, rest))
}

/// A listed glyph: code points, or `continuation`.
fn listed_glyph(code: &str) -> Option<Glyph> {
    if code == CONTINUATION {
        return Some(Glyph::CONTINUATION);
    }
    let text: Option<String> = code
        .split(' ')
        .map(|p| char::from_u32(u32::from_str_radix(p.strip_prefix("U+")?, 16).ok()?))
        .collect();
    text.filter(|t| !t.is_empty()).map(|t| Glyph::new(&t))
}

/// The size the first line gives (`ratatui-cells v1 80x24`), within [`MAX_FRAME`].
fn read_header(header: &str) -> Result<(usize, usize), Error> {
    let size = header
        .strip_prefix(HEADER)
        .map(str::trim)
        .ok_or_else(|| Error::new(format!("line 1: expected '{HEADER} COLSxROWS'")))?;
    let bad = || Error::new("line 1: bad size");
    let (c, r) = size.split_once('x').ok_or_else(bad)?;
    let (cols, rows): (usize, usize) =
        (c.parse().map_err(|_| bad())?, r.parse().map_err(|_| bad())?);
    let (max_cols, max_rows) = MAX_FRAME;
    if cols > max_cols || rows > max_rows {
        return Err(Error::new(format!(
            "line 1: size {cols}x{rows} is over the limit of {max_cols}x{max_rows} cells"
        )));
    }
    Ok((cols, rows))
}

/// Reads cells text back into the frame it was written from; errors name the line.
///
/// # Errors
/// A first line that is not [`HEADER`] and a size within [`MAX_FRAME`], or a malformed row or
/// line.
pub fn from_cells_text(text: &str) -> Result<TermFrame, Error> {
    let mut lines = text.lines();
    let (cols, rows) = read_header(lines.next().unwrap_or_default())?;
    // Both are now small, so `cols * rows` cannot overflow.
    let mut cells = Vec::with_capacity(cols * rows);
    for y in 0..rows {
        let n = y + 2;
        let line = lines
            .next()
            .ok_or_else(|| Error::new(format!("line {n}: missing row {y}")))?;
        let row = line
            .strip_prefix('"')
            .and_then(|l| l.strip_suffix('"'))
            .ok_or_else(|| Error::new(format!("line {n}: a grid row is written between quotes")))?;
        let glyphs = glyph_row(row);
        if glyphs.len() != cols {
            return Err(Error::new(format!(
                "line {n}: {} cells, expected {cols}",
                glyphs.len()
            )));
        }
        cells.extend(glyphs.into_iter().map(|glyph| TermCell {
            glyph,
            ..TermCell::default()
        }));
    }
    let mut frame = TermFrame { cols, rows, cells };
    read_sections(&mut frame, lines, rows + 2)?;
    Ok(frame)
}

/// Reads the `styles:` and `glyphs:` sections into the frame; `first` is the number of the
/// first line given.
fn read_sections<'a>(
    frame: &mut TermFrame,
    lines: impl Iterator<Item = &'a str>,
    first: usize,
) -> Result<(), Error> {
    let cols = frame.cols;
    let mut section = "";
    // Each section lists cells in order, each once, so reading it is linear in the frame.
    let mut next = 0;
    for (i, line) in lines.enumerate() {
        let n = first + i;
        if line == STYLES || line == GLYPHS {
            section = line;
            next = 0;
            continue;
        }
        if line.is_empty() {
            // A blank line (an editor's or a snapshot file's last newline) says nothing.
            continue;
        }
        let bad = || Error::new(format!("line {n}: '{line}' is not a {section} line"));
        let (y, from, to, rest) = place(line, frame).ok_or_else(bad)?;
        if y * cols + from < next {
            return Err(Error::new(format!(
                "line {n}: cells are listed in order, each once (y{y} x{from} comes too late)"
            )));
        }
        next = y * cols + to + 1;
        match section {
            STYLES => {
                for x in from..=to {
                    apply_style(&mut frame.cells[y * cols + x], rest).ok_or_else(bad)?;
                }
            }
            GLYPHS if from == to => {
                frame.cells[y * cols + from].glyph = listed_glyph(rest).ok_or_else(bad)?;
            }
            _ => {
                return Err(Error::new(format!(
                    "line {n}: expected '{STYLES}' or '{GLYPHS}'"
                )))
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui_core::style::{Color, Modifier};

    fn row(glyphs: &[&str]) -> TermFrame {
        TermFrame {
            cols: glyphs.len(),
            rows: 1,
            cells: glyphs
                .iter()
                .map(|&g| TermCell {
                    glyph: Glyph::new(g),
                    ..TermCell::default()
                })
                .collect(),
        }
    }

    #[test]
    fn grid_then_style_runs() {
        let mut frame = row(&["a", "b", "c", "d"]);
        frame.cells[1].fg = Color::Green;
        frame.cells[2].fg = Color::Green;
        frame.cells[3].modifiers = Modifier::REVERSED | Modifier::BOLD;
        frame.cells[3].underline = Color::Indexed(200);
        let text = cells_text(&frame);
        assert_eq!(
            text,
            "ratatui-cells v1 4x1\n\"abcd\"\nstyles:\ny0 x1-2 fg=green\ny0 x3 ul=idx200 bold reversed\n"
        );
        assert_eq!(from_cells_text(&text).unwrap(), frame);
    }

    #[test]
    fn clusters_and_wide_characters_read_back() {
        let frame = row(&["e\u{301}", "👍🏽", "", " ", "界", "", "\""]);
        let text = cells_text(&frame);
        assert_eq!(text, "ratatui-cells v1 7x1\n\"e\u{301}👍🏽 界\"\"\n");
        assert_eq!(from_cells_text(&text).unwrap(), frame);
    }

    #[test]
    fn glyphs_the_grid_cannot_show_are_listed() {
        // A lone combining mark would join the cell before it; a wide character with no
        // continuation would take two columns; a newline would break the row.
        let frame = row(&["e", "\u{301}", "界", "\n", "x"]);
        let text = cells_text(&frame);
        assert_eq!(
            text,
            "ratatui-cells v1 5x1\n\"e???x\"\nglyphs:\ny0 x1 U+0301\ny0 x2 U+754C\ny0 x3 U+000A\n"
        );
        assert_eq!(from_cells_text(&text).unwrap(), frame);
    }

    #[test]
    fn malformed_lines_name_their_line() {
        assert_eq!(
            from_cells_text("ratatui-cells v1 2x1\n\"a\"\n")
                .unwrap_err()
                .to_string(),
            "line 2: 1 cells, expected 2"
        );
        assert_eq!(
            from_cells_text("ratatui-cells v1 2x1\n\"ab\"\nstyles:\ny0 x1-5 bold\n")
                .unwrap_err()
                .to_string(),
            "line 4: 'y0 x1-5 bold' is not a styles: line"
        );
        assert_eq!(
            from_cells_text("ratatui-cells v1 2x1\n\"ab\"\nstyles:\ny0 x1 fg=pink\n")
                .unwrap_err()
                .to_string(),
            "line 4: 'y0 x1 fg=pink' is not a styles: line"
        );
        assert_eq!(
            from_cells_text("ratatui-cells v1 2x1\n\"ab\"\nstyles:\ny0 x0-1 bold\ny0 x1 dim\n")
                .unwrap_err()
                .to_string(),
            "line 5: cells are listed in order, each once (y0 x1 comes too late)"
        );
        assert!(from_cells_text("nope").is_err());
        assert!(from_cells_text("ratatui-cells v1 2x1\nab\n").is_err());
    }

    #[test]
    fn frames_without_columns_keep_their_rows() {
        let frame = TermFrame {
            cols: 0,
            rows: 2,
            cells: Vec::new(),
        };
        let text = cells_text(&frame);
        assert_eq!(text, "ratatui-cells v1 0x2\n\"\"\n\"\"\n");
        assert_eq!(from_cells_text(&text).unwrap(), frame);
    }

    #[test]
    fn a_size_over_the_limit_is_refused() {
        assert_eq!(
            from_cells_text("ratatui-cells v1 17216961135462248175x1\n\n")
                .unwrap_err()
                .to_string(),
            "line 1: size 17216961135462248175x1 is over the limit of 4000x2000 cells"
        );
    }
}
