//! One terminal cell as a person sees it: the grapheme, both colours, the underline colour and
//! every attribute, each kept exactly as named.

use ratatui::style::{Color, Modifier};

use super::colour::{ratatui_rgb, rgb_colour};
use super::glyph::Glyph;
use crate::color::Rgb;
use crate::encode::glyph_mask::mask_of;
use crate::render::glyphs::Glyphs;

/// One terminal cell as a person sees it. Colours are ratatui's [`Color`], kept as named
/// (`Green`, `Indexed(2)` and `Rgb(0, 205, 0)` are three different cells: a terminal shows named
/// and indexed colours in its own palette), `Color::Reset` is the terminal's default colour.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct TermCell {
    /// The grapheme cluster shown (empty for the second column of a wide character).
    pub glyph: Glyph,
    /// Foreground colour.
    pub fg: Color,
    /// Background colour.
    pub bg: Color,
    /// Underline colour (`Reset`: the foreground's).
    pub underline: Color,
    /// Bold, dim, italic, underlined, blinking, reversed, hidden, crossed out.
    pub modifiers: Modifier,
}

impl Default for TermCell {
    /// A blank cell: a space in the default colours, no attributes.
    fn default() -> Self {
        Self {
            glyph: Glyph::default(),
            fg: Color::Reset,
            bg: Color::Reset,
            underline: Color::Reset,
            modifiers: Modifier::empty(),
        }
    }
}

impl TermCell {
    /// A plain cell of 24-bit colours (`None` = the terminal's default): how pixel views are
    /// drawn.
    #[must_use]
    pub fn rgb(glyph: impl Into<Glyph>, fg: Option<Rgb>, bg: Option<Rgb>) -> Self {
        Self {
            glyph: glyph.into(),
            fg: rgb_colour(fg),
            bg: rgb_colour(bg),
            ..Self::default()
        }
    }

    /// The foreground as xterm's RGB (`None` = default): for pictures and colour distances.
    #[must_use]
    pub fn fg_rgb(&self) -> Option<Rgb> {
        ratatui_rgb(self.fg)
    }

    /// The background as xterm's RGB (`None` = default): for pictures and colour distances.
    #[must_use]
    pub fn bg_rgb(&self) -> Option<Rgb> {
        ratatui_rgb(self.bg)
    }

    /// Whether the cell has the plain style: default colours, no attributes.
    #[must_use]
    pub fn is_plain_style(&self) -> bool {
        self.same_style(&TermCell::default())
    }

    /// Whether two cells share colours, underline colour and attributes (glyphs aside).
    #[must_use]
    pub fn same_style(&self, other: &TermCell) -> bool {
        (self.fg, self.bg, self.underline, self.modifiers)
            == (other.fg, other.bg, other.underline, other.modifiers)
    }

    /// The visible content in a canonical form, so `▀` fg=a bg=b equals `▄` fg=b bg=a and a
    /// space equals `█` with swapped roles (as do a quadrant, sextant or octant mask and its
    /// complement). Only for cells without attributes: an underline or a reversal shows which
    /// glyph was drawn, so such cells are their own form.
    #[must_use]
    pub fn appearance(&self) -> TermCell {
        if !self.modifiers.is_empty() || self.underline != Color::Reset {
            return self.clone();
        }
        let glyph = self.glyph.as_str();
        let mut chars = glyph.chars();
        let (Some(g), None) = (chars.next(), chars.next()) else {
            return self.clone();
        };
        let (g, up, low) = match g {
            '▀' => ('▀', self.fg, self.bg),
            '▄' => ('▀', self.bg, self.fg),
            ' ' => ('▀', self.bg, self.bg),
            '█' => ('▀', self.fg, self.fg),
            g => glyph_appearance(g, self.fg, self.bg),
        };
        Self {
            glyph: Glyph::from(g),
            fg: up,
            bg: low,
            ..Self::default()
        }
    }
}

/// A quadrant, sextant or octant cell in canonical form: a mask and its complement with the
/// colours swapped draw the same picture, so the form whose first pixel is the background
/// stands for both (other glyphs as they are).
fn glyph_appearance(g: char, fg: Color, bg: Color) -> (char, Color, Color) {
    use crate::encode::glyph_mask::{full_mask, glyph};
    for set in [Glyphs::Octant, Glyphs::Sextant] {
        if let Some(m) = mask_of(set, g) {
            if m & 1 != 0 {
                return (glyph(set, !m & full_mask(set)), bg, fg);
            }
            return (g, fg, bg);
        }
    }
    (g, fg, bg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equivalent_glyphs_look_the_same() {
        let (a, b) = (Some(Rgb::new(1, 2, 3)), Some(Rgb::new(4, 5, 6)));
        let up = TermCell::rgb('▀', a, b);
        let low = TermCell::rgb('▄', b, a);
        assert_eq!(up.appearance(), low.appearance());
        let space = TermCell::rgb(' ', None, a);
        let full = TermCell::rgb('█', a, b);
        assert_eq!(space.appearance(), full.appearance());
    }

    #[test]
    fn attributes_keep_the_glyph_drawn() {
        let (a, b) = (Some(Rgb::new(1, 2, 3)), Some(Rgb::new(4, 5, 6)));
        let mut up = TermCell::rgb('▀', a, b);
        let mut low = TermCell::rgb('▄', b, a);
        up.modifiers = Modifier::UNDERLINED;
        low.modifiers = Modifier::UNDERLINED;
        assert_ne!(up.appearance(), low.appearance());
    }

    #[test]
    fn each_part_of_a_cell_counts() {
        let base = TermCell {
            glyph: Glyph::new("e\u{301}"),
            fg: Color::Green,
            ..TermCell::default()
        };
        let changes = [
            TermCell {
                glyph: Glyph::new("e\u{300}"),
                ..base.clone()
            },
            TermCell {
                fg: Color::Indexed(2),
                ..base.clone()
            },
            TermCell {
                fg: Color::Rgb(0, 205, 0),
                ..base.clone()
            },
            TermCell {
                underline: Color::Red,
                ..base.clone()
            },
        ];
        for c in changes {
            assert_ne!(c.appearance(), base.appearance(), "{c:?}");
        }
        for m in Modifier::all().iter() {
            let c = TermCell {
                modifiers: m,
                ..base.clone()
            };
            assert_ne!(c.appearance(), base.appearance(), "{m:?}");
        }
    }
}
