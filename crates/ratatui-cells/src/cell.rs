//! One terminal cell as a person sees it: the grapheme, both colours, the underline colour and
//! every attribute, each kept exactly as named.

use ratatui_core::style::{Color, Modifier};

use crate::glyph::Glyph;

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
    /// A cell showing `glyph` in `fg` on `bg`, no attributes: the short way to build an
    /// expected cell.
    #[must_use]
    pub fn new(glyph: impl Into<Glyph>, fg: Color, bg: Color) -> Self {
        Self {
            glyph: glyph.into(),
            fg,
            bg,
            ..Self::default()
        }
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

    /// Whether the cell has no attributes and no underline colour: the only cells whose glyph
    /// may be traded for an equivalent one without changing what the screen shows.
    #[must_use]
    pub fn is_unadorned(&self) -> bool {
        self.modifiers.is_empty() && self.underline == Color::Reset
    }
}
