//! Cells in halfcast's colours: building a cell from pixels, and a cell's colours as pixels.

use ratatui::style::Color;

use crate::color::Rgb;
use crate::encode::palette::xterm_rgb;
use crate::termframe::{named_colour, Glyph, TermCell};

/// The RGB a ratatui colour shows as in xterm's palette (`None` = the terminal's default):
/// for pictures and colour distances only, since a user's palette may differ.
#[must_use]
pub fn ratatui_rgb(c: Color) -> Option<Rgb> {
    match c {
        Color::Reset => None,
        Color::Rgb(r, g, b) => Some(Rgb::new(r, g, b)),
        Color::Indexed(i) => Some(xterm_rgb(i)),
        named => (0..16)
            .find(|&n| named_colour(n) == Some(named))
            .map(xterm_rgb),
    }
}

/// A 24-bit colour (`None` = the terminal's default) as a ratatui colour.
#[must_use]
pub fn rgb_colour(c: Option<Rgb>) -> Color {
    c.map_or(Color::Reset, |c| Color::Rgb(c.r, c.g, c.b))
}

/// A [`TermCell`] in halfcast's pixel colours (`use halfcast::termframe::CellRgb` to call these
/// on a cell).
pub trait CellRgb {
    /// A plain cell of 24-bit colours (`None` = the terminal's default): how pixel views are
    /// drawn.
    fn rgb(glyph: impl Into<Glyph>, fg: Option<Rgb>, bg: Option<Rgb>) -> TermCell;
    /// The foreground as xterm's RGB (`None` = default): for pictures and colour distances.
    fn fg_rgb(&self) -> Option<Rgb>;
    /// The background as xterm's RGB (`None` = default): for pictures and colour distances.
    fn bg_rgb(&self) -> Option<Rgb>;
}

impl CellRgb for TermCell {
    fn rgb(glyph: impl Into<Glyph>, fg: Option<Rgb>, bg: Option<Rgb>) -> TermCell {
        TermCell::new(glyph, rgb_colour(fg), rgb_colour(bg))
    }

    fn fg_rgb(&self) -> Option<Rgb> {
        ratatui_rgb(self.fg)
    }

    fn bg_rgb(&self) -> Option<Rgb> {
        ratatui_rgb(self.bg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn named_and_indexed_show_as_the_same_xterm_rgb() {
        assert_eq!(ratatui_rgb(Color::Green), ratatui_rgb(Color::Indexed(2)));
        assert_eq!(ratatui_rgb(Color::Green), Some(Rgb::new(0, 205, 0)));
        let cell = TermCell::rgb('▀', Some(Rgb::new(1, 2, 3)), None);
        assert_eq!(
            (cell.fg_rgb(), cell.bg_rgb()),
            (Some(Rgb::new(1, 2, 3)), None)
        );
    }
}
