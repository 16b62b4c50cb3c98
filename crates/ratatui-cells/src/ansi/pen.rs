//! The pen a terminal draws the next glyph with, and how an SGR sequence changes it: every
//! attribute, the 16 named colours, indexed and 24-bit colours in both the `;` and the `:`
//! forms, and the underline colour (SGR 58/59).

use ratatui_core::style::{Color, Modifier};

use crate::colour::named_colour;

/// Colours and attributes for the next glyph.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Pen {
    pub(crate) fg: Color,
    pub(crate) bg: Color,
    pub(crate) underline: Color,
    pub(crate) modifiers: Modifier,
}

impl Default for Pen {
    /// The pen after `ESC[m`.
    fn default() -> Self {
        Self {
            fg: Color::Reset,
            bg: Color::Reset,
            underline: Color::Reset,
            modifiers: Modifier::empty(),
        }
    }
}

/// The attributes each SGR parameter switches on.
const ON: [(u16, Modifier); 10] = [
    (1, Modifier::BOLD),
    (2, Modifier::DIM),
    (3, Modifier::ITALIC),
    (4, Modifier::UNDERLINED),
    (5, Modifier::SLOW_BLINK),
    (6, Modifier::RAPID_BLINK),
    (7, Modifier::REVERSED),
    (8, Modifier::HIDDEN),
    (9, Modifier::CROSSED_OUT),
    // Double underline: ratatui has one underline attribute.
    (21, Modifier::UNDERLINED),
];

/// The attributes each SGR parameter switches off (22 ends bold and dim, 25 both blinks).
const OFF: [(u16, Modifier); 7] = [
    (22, Modifier::BOLD.union(Modifier::DIM)),
    (23, Modifier::ITALIC),
    (24, Modifier::UNDERLINED),
    (25, Modifier::SLOW_BLINK.union(Modifier::RAPID_BLINK)),
    (27, Modifier::REVERSED),
    (28, Modifier::HIDDEN),
    (29, Modifier::CROSSED_OUT),
];

/// Palette entry `n` as ratatui names it: 0–15 as the named colours (`ESC[32m`,
/// `ESC[38;5;2m` and ratatui's `Indexed(2)` and `Green` all select the same entry, and
/// crossterm sends `Green` as `38;5;2`), the rest as `Indexed`.
fn palette(n: u16) -> Option<Color> {
    let n = u8::try_from(n).ok()?;
    Some(named_colour(n).unwrap_or(Color::Indexed(n)))
}

/// The colour after `38`/`48`/`58`: in the colon form inside `param` (`38:5:n`,
/// `38:2::r:g:b`, `38:2:r:g:b`), else from the parameters that follow (`38;5;n`,
/// `38;2;r;g;b`), which are taken from `rest`.
fn extended<'a>(param: &[u16], rest: &mut impl Iterator<Item = &'a [u16]>) -> Option<Color> {
    let rgb = |c: &[u16]| -> Option<Color> {
        let v: Vec<u8> = c
            .iter()
            .map(|&x| u8::try_from(x).ok())
            .collect::<Option<_>>()?;
        Some(Color::Rgb(v[0], v[1], v[2]))
    };
    if param.len() > 1 {
        return match param[1] {
            5 => palette(*param.get(2)?),
            2 if param.len() >= 6 => rgb(&param[3..6]),
            2 if param.len() == 5 => rgb(&param[2..5]),
            _ => None,
        };
    }
    let mut next = || rest.next().and_then(|p| p.first().copied());
    match next()? {
        5 => palette(next()?),
        2 => {
            let (r, g, b) = (next()?, next()?, next()?);
            rgb(&[r, g, b])
        }
        _ => None,
    }
}

impl Pen {
    /// Applies one SGR sequence's parameters, in order.
    pub(crate) fn apply(&mut self, params: &vte::Params) {
        if params.is_empty() {
            *self = Pen::default();
            return;
        }
        let mut items = params.iter();
        while let Some(param) = items.next() {
            let code = param.first().copied().unwrap_or(0);
            match code {
                0 => *self = Pen::default(),
                4 if param.get(1) == Some(&0) => self.modifiers.remove(Modifier::UNDERLINED),
                30..=37 => self.fg = palette(code - 30).unwrap_or_default(),
                90..=97 => self.fg = palette(code - 90 + 8).unwrap_or_default(),
                40..=47 => self.bg = palette(code - 40).unwrap_or_default(),
                100..=107 => self.bg = palette(code - 100 + 8).unwrap_or_default(),
                39 => self.fg = Color::Reset,
                49 => self.bg = Color::Reset,
                59 => self.underline = Color::Reset,
                38 | 48 | 58 => {
                    if let Some(c) = extended(param, &mut items) {
                        match code {
                            38 => self.fg = c,
                            48 => self.bg = c,
                            _ => self.underline = c,
                        }
                    }
                }
                _ => {
                    if let Some(&(_, m)) = ON.iter().find(|(c, _)| *c == code) {
                        self.modifiers.insert(m);
                    } else if let Some(&(_, m)) = OFF.iter().find(|(c, _)| *c == code) {
                        self.modifiers.remove(m);
                    }
                }
            }
        }
    }
}
