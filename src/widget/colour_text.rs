//! A text form of a terminal buffer that keeps colours, for snapshot tests of half-block frames.
//!
//! ratatui's own text form shows glyphs only, which for a `▀` frame is a wall of identical
//! characters; this one writes every cell as glyph + foreground + background.

use std::fmt::Write;

use ratatui::buffer::Buffer;
use ratatui::style::Color;

/// `rrggbb` for 24-bit colours, `-` for the terminal default, the colour's name otherwise.
#[must_use]
pub fn colour_code(c: Color) -> String {
    match c {
        Color::Rgb(r, g, b) => format!("{r:02x}{g:02x}{b:02x}"),
        Color::Reset => "-".to_owned(),
        other => format!("{other:?}"),
    }
}

/// One line per buffer row; cells as `glyph fg/bg`, runs of equal cells as `×n`.
#[must_use]
pub fn to_colour_text(buf: &Buffer) -> String {
    let area = buf.area;
    let mut out = String::new();
    for y in area.top()..area.bottom() {
        let mut cells: Vec<String> = Vec::new();
        let mut counts: Vec<usize> = Vec::new();
        for x in area.left()..area.right() {
            let c = &buf[(x, y)];
            let token = format!("{}{}/{}", c.symbol(), colour_code(c.fg), colour_code(c.bg));
            if cells.last() == Some(&token) {
                *counts.last_mut().expect("pushed together") += 1;
            } else {
                cells.push(token);
                counts.push(1);
            }
        }
        for (i, (t, n)) in cells.iter().zip(&counts).enumerate() {
            if i > 0 {
                out.push(' ');
            }
            out.push_str(t);
            if *n > 1 {
                let _ = write!(out, "×{n}");
            }
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::layout::Rect;

    #[test]
    fn runs_and_colours_are_written() {
        let mut buf = Buffer::empty(Rect::new(0, 0, 4, 1));
        buf[(0, 0)]
            .set_symbol("▀")
            .set_fg(Color::Rgb(255, 0, 16))
            .set_bg(Color::Rgb(0, 0, 0));
        assert_eq!(to_colour_text(&buf), "▀ff0010/000000  -/-×3\n");
    }
}
