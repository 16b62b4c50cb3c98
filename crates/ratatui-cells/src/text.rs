//! The text form of a frame that snapshots pin: the screen's glyphs as a grid a person reads,
//! then the style runs, one line each, naming their row and columns, so a one-cell colour change
//! is a one- or two-line diff that says where.
//!
//! ```text
//! halfcast-cells v2 12x2
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

use ratatui_core::style::{Color, Modifier};
use unicode_segmentation::UnicodeSegmentation;

use crate::cell::TermCell;
use crate::colour::{colour_name, parse_colour_name};
use crate::frame::TermFrame;
use crate::glyph::{width_of, Glyph};
use crate::limits::MAX_FRAME;

/// First line of the cells text form; carries the version and the size.
pub const CELLS_HEADER: &str = "halfcast-cells v2";

/// Starts the style runs.
const STYLES: &str = "styles:";

/// Starts the glyphs the grid could not show.
const GLYPHS: &str = "glyphs:";

/// Written for a wide character's second column in the `glyphs:` list.
const CONTINUATION: &str = "continuation";

/// Each attribute and its word in the text form.
const MODIFIER_WORDS: [(Modifier, &str); 9] = [
    (Modifier::BOLD, "bold"),
    (Modifier::DIM, "dim"),
    (Modifier::ITALIC, "italic"),
    (Modifier::UNDERLINED, "underlined"),
    (Modifier::SLOW_BLINK, "slow_blink"),
    (Modifier::RAPID_BLINK, "rapid_blink"),
    (Modifier::REVERSED, "reversed"),
    (Modifier::HIDDEN, "hidden"),
    (Modifier::CROSSED_OUT, "crossed_out"),
];

/// A cell's style as the text form writes it: `fg=green bg=#101010 bold` (empty when plain).
#[must_use]
pub fn style_words(c: &TermCell) -> String {
    let mut words = Vec::new();
    for (name, colour) in [("fg", c.fg), ("bg", c.bg), ("ul", c.underline)] {
        if colour != Color::Reset {
            words.push(format!("{name}={}", colour_name(colour)));
        }
    }
    for (m, word) in MODIFIER_WORDS {
        if c.modifiers.contains(m) {
            words.push(word.to_string());
        }
    }
    words.join(" ")
}

/// One cell for a person: the glyph quoted (escaped when invisible), then its style.
#[must_use]
pub fn cell_code(c: &TermCell) -> String {
    let style = style_words(c);
    let glyph = if c.glyph.is_continuation() {
        CONTINUATION.to_string()
    } else {
        format!("{:?}", c.glyph.as_str())
    };
    if style.is_empty() {
        glyph
    } else {
        format!("{glyph} {style}")
    }
}

/// Reads one grid row's glyphs: a cell per grapheme cluster, plus a continuation cell for each
/// extra column a wide one takes.
pub(crate) fn read_grid_row(row: &str) -> Vec<Glyph> {
    let mut glyphs = Vec::new();
    for g in row.graphemes(true) {
        glyphs.push(Glyph::new(g));
        for _ in 1..width_of(g) {
            glyphs.push(Glyph::CONTINUATION);
        }
    }
    glyphs
}

/// The grid row for `cells`, and the columns whose glyph is listed under `glyphs:` instead.
fn grid_row(cells: &[TermCell]) -> (String, Vec<usize>) {
    let row: String = cells.iter().map(|c| c.glyph.as_str()).collect();
    let glyphs: Vec<&Glyph> = cells.iter().map(|c| &c.glyph).collect();
    let readable =
        !row.chars().any(char::is_control) && read_grid_row(&row).iter().eq(glyphs.iter().copied());
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

/// The text form snapshots pin, of anything that converts into a [`TermFrame`] (a ratatui
/// `Buffer`, owned or borrowed, or a frame): a size header, the glyph grid, then style runs
/// such as `y3 x0-11 fg=green bold`.
#[must_use]
pub fn cells_text(frame: impl Into<TermFrame>) -> String {
    to_cells_text(&frame.into())
}

/// Writes the frame's text form: the header with the size, the glyph grid, the style runs and
/// any glyphs the grid could not show.
#[must_use]
pub fn to_cells_text(frame: &TermFrame) -> String {
    let mut out = format!("{CELLS_HEADER} {}x{}\n", frame.cols, frame.rows);
    let mut listed = Vec::new();
    let row = |y: usize| &frame.cells[y * frame.cols..(y + 1) * frame.cols];
    for y in 0..frame.rows {
        let (text, xs) = grid_row(row(y));
        let _ = writeln!(out, "\"{text}\"");
        listed.extend(xs.into_iter().map(|x| (x, y)));
    }
    let mut runs = String::new();
    for y in 0..frame.rows {
        let row = row(y);
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
    if !runs.is_empty() {
        out.push_str(STYLES);
        out.push('\n');
        out.push_str(&runs);
    }
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

/// Reads `yROW xCOL` or `yROW xFIRST-LAST` at the start of a list line; the rest of the line.
fn place<'a>(line: &'a str, frame: &TermFrame) -> Option<(usize, usize, usize, &'a str)> {
    let (y, rest) = line.strip_prefix('y')?.split_once(" x")?;
    let (cols, rest) = rest.split_once(' ').unwrap_or((rest, ""));
    let (first, last) = cols.split_once('-').unwrap_or((cols, cols));
    let (y, first, last): (usize, usize, usize) =
        (y.parse().ok()?, first.parse().ok()?, last.parse().ok()?);
    (y < frame.rows && first <= last && last < frame.cols).then_some((y, first, last, rest))
}

/// Applies a style run's words to a cell.
fn apply_style(cell: &mut TermCell, words: &str) -> Option<()> {
    for word in words.split(' ').filter(|w| !w.is_empty()) {
        if let Some((part, colour)) = word.split_once('=') {
            let colour = parse_colour_name(colour)?;
            match part {
                "fg" => cell.fg = colour,
                "bg" => cell.bg = colour,
                "ul" => cell.underline = colour,
                _ => return None,
            }
        } else {
            let (m, _) = MODIFIER_WORDS.iter().find(|(_, w)| *w == word)?;
            cell.modifiers |= *m;
        }
    }
    Some(())
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

/// The size a cells text's first line gives after `magic` (`halfcast-cells v2 80x24`), within
/// [`MAX_FRAME`]; shared by both versions' readers.
pub(crate) fn cells_header(header: &str, magic: &str) -> Result<(usize, usize), String> {
    let size = header
        .strip_prefix(magic)
        .map(str::trim)
        .ok_or_else(|| format!("line 1: expected '{magic} COLSxROWS'"))?;
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

/// Reads the cells text form back (this version or `halfcast-cells v1`); errors name the line.
///
/// # Errors
/// A header that is not `halfcast-cells v2 COLSxROWS` (or v1), or a malformed row or line.
pub fn from_cells_text(text: &str) -> Result<TermFrame, String> {
    if text.starts_with(crate::text_v1::CELLS_HEADER_V1) {
        return crate::text_v1::from_cells_text_v1(text);
    }
    let mut lines = text.lines();
    let (cols, rows) = cells_header(lines.next().unwrap_or_default(), CELLS_HEADER)?;
    // Both are now small, so `cols * rows` cannot overflow.
    let mut cells = Vec::with_capacity(cols * rows);
    for y in 0..rows {
        let n = y + 2;
        let line = lines
            .next()
            .ok_or_else(|| format!("line {n}: missing row {y}"))?;
        let row = line
            .strip_prefix('"')
            .and_then(|l| l.strip_suffix('"'))
            .ok_or_else(|| format!("line {n}: a grid row is written between quotes"))?;
        let glyphs = read_grid_row(row);
        if glyphs.len() != cols {
            return Err(format!("line {n}: {} cells, expected {cols}", glyphs.len()));
        }
        cells.extend(glyphs.into_iter().map(|glyph| TermCell {
            glyph,
            ..TermCell::default()
        }));
    }
    let mut frame = TermFrame { cols, rows, cells };
    let mut section = "";
    // Each section lists cells in order, each once, so reading it is linear in the frame.
    let mut next = 0;
    for (i, line) in lines.enumerate() {
        let n = rows + 2 + i;
        if line == STYLES || line == GLYPHS {
            section = line;
            next = 0;
            continue;
        }
        if line.is_empty() {
            // A blank line (an editor's or a snapshot file's last newline) says nothing.
            continue;
        }
        let bad = || format!("line {n}: '{line}' is not a {section} line");
        let (y, first, last, rest) = place(line, &frame).ok_or_else(bad)?;
        if y * cols + first < next {
            return Err(format!(
                "line {n}: cells are listed in order, each once (y{y} x{first} comes too late)"
            ));
        }
        next = y * cols + last + 1;
        match section {
            STYLES => {
                for x in first..=last {
                    apply_style(&mut frame.cells[y * cols + x], rest).ok_or_else(bad)?;
                }
            }
            GLYPHS if first == last => {
                frame.cells[y * cols + first].glyph = listed_glyph(rest).ok_or_else(bad)?;
            }
            _ => return Err(format!("line {n}: expected '{STYLES}' or '{GLYPHS}'")),
        }
    }
    Ok(frame)
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let text = to_cells_text(&frame);
        assert_eq!(
            text,
            "halfcast-cells v2 4x1\n\"abcd\"\nstyles:\ny0 x1-2 fg=green\ny0 x3 ul=idx200 bold reversed\n"
        );
        assert_eq!(from_cells_text(&text).unwrap(), frame);
    }

    #[test]
    fn clusters_and_wide_characters_read_back() {
        let frame = row(&["e\u{301}", "👍🏽", "", " ", "界", "", "\""]);
        let text = to_cells_text(&frame);
        assert_eq!(text, "halfcast-cells v2 7x1\n\"e\u{301}👍🏽 界\"\"\n");
        assert_eq!(from_cells_text(&text).unwrap(), frame);
    }

    #[test]
    fn glyphs_the_grid_cannot_show_are_listed() {
        // A lone combining mark would join the cell before it; a wide character with no
        // continuation would take two columns; a newline would break the row.
        let frame = row(&["e", "\u{301}", "界", "\n", "x"]);
        let text = to_cells_text(&frame);
        assert_eq!(
            text,
            "halfcast-cells v2 5x1\n\"e???x\"\nglyphs:\ny0 x1 U+0301\ny0 x2 U+754C\ny0 x3 U+000A\n"
        );
        assert_eq!(from_cells_text(&text).unwrap(), frame);
    }

    #[test]
    fn malformed_lines_name_their_line() {
        assert_eq!(
            from_cells_text("halfcast-cells v2 2x1\n\"a\"\n").unwrap_err(),
            "line 2: 1 cells, expected 2"
        );
        assert_eq!(
            from_cells_text("halfcast-cells v2 2x1\n\"ab\"\nstyles:\ny0 x1-5 bold\n").unwrap_err(),
            "line 4: 'y0 x1-5 bold' is not a styles: line"
        );
        assert_eq!(
            from_cells_text("halfcast-cells v2 2x1\n\"ab\"\nstyles:\ny0 x1 fg=pink\n").unwrap_err(),
            "line 4: 'y0 x1 fg=pink' is not a styles: line"
        );
        assert_eq!(
            from_cells_text("halfcast-cells v2 2x1\n\"ab\"\nstyles:\ny0 x0-1 bold\ny0 x1 dim\n")
                .unwrap_err(),
            "line 5: cells are listed in order, each once (y0 x1 comes too late)"
        );
        assert!(from_cells_text("nope").is_err());
        assert!(from_cells_text("halfcast-cells v2 2x1\nab\n").is_err());
    }

    #[test]
    fn frames_without_columns_keep_their_rows() {
        let frame = TermFrame {
            cols: 0,
            rows: 2,
            cells: Vec::new(),
        };
        let text = to_cells_text(&frame);
        assert_eq!(text, "halfcast-cells v2 0x2\n\"\"\n\"\"\n");
        assert_eq!(from_cells_text(&text).unwrap(), frame);
    }

    #[test]
    fn a_size_over_the_limit_is_refused() {
        assert_eq!(
            from_cells_text("halfcast-cells v2 17216961135462248175x1\n\n").unwrap_err(),
            "line 1: size 17216961135462248175x1 is over the limit of 4000x2000 cells"
        );
    }
}
