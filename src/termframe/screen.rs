//! Reading a `vt100` terminal model's screen (a test's own `vt100::Parser`) into cells.

use ratatui::style::{Color, Modifier};

use crate::termframe::{named_colour, Glyph, TermCell, TermFrame};

/// Reads the top-left `cols` × `rows` cells of a `vt100` screen, colours 0–15 as named. The
/// model keeps only bold, italic, underline and reverse video, and splits some grapheme
/// clusters (a skin tone, a flag) over cells of their own; [`super::from_ansi_sized`], which
/// reads the bytes themselves, keeps everything.
#[must_use]
pub fn from_screen(screen: &vt100::Screen, cols: usize, rows: usize) -> TermFrame {
    let colour = |c: vt100::Color| match c {
        vt100::Color::Default => Color::Reset,
        vt100::Color::Idx(n) => named_colour(n).unwrap_or(Color::Indexed(n)),
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
                    glyph: Glyph::CONTINUATION,
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
                    Glyph::default()
                } else {
                    Glyph::new(&contents)
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

/// A `vt100` parser's whole screen ([`from_screen`] at its size).
#[must_use]
pub fn from_parser(parser: &vt100::Parser) -> TermFrame {
    let (rows, cols) = parser.screen().size();
    from_screen(parser.screen(), usize::from(cols), usize::from(rows))
}
