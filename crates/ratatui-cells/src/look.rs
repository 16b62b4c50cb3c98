//! What a cell looks like on screen, for the opt-in loose comparison: `▀` in colours a/b and `▄`
//! in b/a, or a space and `█` with the roles swapped, draw the same picture.

use ratatui_core::style::Color;

use crate::cell::TermCell;
use crate::glyph::Glyph;

impl TermCell {
    /// The visible content in a canonical form, so `▀` fg=a bg=b equals `▄` fg=b bg=a and a
    /// space equals `█` with swapped roles (the foreground of a space is not seen, and the
    /// terminal's default foreground and background count as one colour, `Reset`). Only for
    /// cells without attributes or underline colour ([`TermCell::is_unadorned`]): an underline
    /// or a reversal shows which glyph was drawn, so such cells are their own form.
    #[must_use]
    pub fn appearance(&self) -> TermCell {
        if !self.is_unadorned() {
            return self.clone();
        }
        let glyph = self.glyph.as_str();
        let mut chars = glyph.chars();
        let (Some(g), None) = (chars.next(), chars.next()) else {
            return self.clone();
        };
        let (up, low): (Color, Color) = match g {
            '▀' => (self.fg, self.bg),
            '▄' => (self.bg, self.fg),
            ' ' => (self.bg, self.bg),
            '█' => (self.fg, self.fg),
            _ => return self.clone(),
        };
        Self {
            glyph: Glyph::from('▀'),
            fg: up,
            bg: low,
            ..Self::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui_core::style::Modifier;

    #[test]
    fn equivalent_glyphs_look_the_same() {
        let (a, b) = (Color::Rgb(1, 2, 3), Color::Rgb(4, 5, 6));
        let up = TermCell::new('▀', a, b);
        let low = TermCell::new('▄', b, a);
        assert_eq!(up.appearance(), low.appearance());
        let space = TermCell::new(' ', Color::Reset, a);
        let full = TermCell::new('█', a, b);
        assert_eq!(space.appearance(), full.appearance());
    }

    #[test]
    fn attributes_keep_the_glyph_drawn() {
        let (a, b) = (Color::Rgb(1, 2, 3), Color::Rgb(4, 5, 6));
        let mut up = TermCell::new('▀', a, b);
        let mut low = TermCell::new('▄', b, a);
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
