//! A cell's style in words (`fg=green ul=idx3 bold reversed`), written in style runs and read
//! back from them, and one cell for a person (what a cell diff prints).

use ratatui_core::style::{Color, Modifier};

use crate::cell::TermCell;
use crate::colour::{colour_name, parse_colour_name};

/// Written for a wide character's second column.
pub(crate) const CONTINUATION: &str = "continuation";

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

/// A cell's style as the cells text writes it: `fg=green bg=#101010 bold` (empty when plain).
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

/// One cell for a person, as a cell diff prints it: the glyph quoted (escaped when
/// invisible), then its style words.
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

/// Applies a style run's words to a cell; `None` for a word that is not a style.
pub(crate) fn apply_style(cell: &mut TermCell, words: &str) -> Option<()> {
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
