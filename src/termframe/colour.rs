//! The colours a cell keeps, exactly as the app or the terminal named them (ratatui's
//! [`Color`]: the terminal default, the 16 named colours, the 256 indexed ones, 24-bit RGB), and
//! how the cells text writes them.

use ratatui::style::Color;

use crate::color::Rgb;

/// The 16 named colours in ANSI index order, with the names the cells text gives them.
const NAMED: [(Color, &str); 16] = [
    (Color::Black, "black"),
    (Color::Red, "red"),
    (Color::Green, "green"),
    (Color::Yellow, "yellow"),
    (Color::Blue, "blue"),
    (Color::Magenta, "magenta"),
    (Color::Cyan, "cyan"),
    (Color::Gray, "gray"),
    (Color::DarkGray, "darkgray"),
    (Color::LightRed, "lightred"),
    (Color::LightGreen, "lightgreen"),
    (Color::LightYellow, "lightyellow"),
    (Color::LightBlue, "lightblue"),
    (Color::LightMagenta, "lightmagenta"),
    (Color::LightCyan, "lightcyan"),
    (Color::White, "white"),
];

/// The named colour at ANSI index `n` (0..16): what SGR 30–37 and 90–97 select, shown in the
/// terminal's own palette.
#[must_use]
pub fn named_colour(n: u8) -> Option<Color> {
    NAMED.get(usize::from(n)).map(|&(c, _)| c)
}

/// The ANSI index of a named colour, `None` for any other colour.
fn named_index(c: Color) -> Option<u8> {
    NAMED.iter().position(|&(n, _)| n == c).map(|i| i as u8)
}

/// The RGB a ratatui colour shows as in xterm's palette (`None` = the terminal's default):
/// for pictures and colour distances only, since a user's palette may differ.
#[must_use]
pub fn ratatui_rgb(c: Color) -> Option<Rgb> {
    match c {
        Color::Reset => None,
        Color::Rgb(r, g, b) => Some(Rgb::new(r, g, b)),
        Color::Indexed(i) => Some(crate::encode::palette::xterm_rgb(i)),
        named => named_index(named).map(crate::encode::palette::xterm_rgb),
    }
}

/// A 24-bit colour (`None` = the terminal's default) as a ratatui colour.
#[must_use]
pub fn rgb_colour(c: Option<Rgb>) -> Color {
    c.map_or(Color::Reset, |c| Color::Rgb(c.r, c.g, c.b))
}

/// A colour as the cells text writes it: `green`, `idx2`, `#00cd00` (`reset` for the default).
#[must_use]
pub fn colour_name(c: Color) -> String {
    match c {
        Color::Reset => "reset".into(),
        Color::Rgb(r, g, b) => format!("#{r:02x}{g:02x}{b:02x}"),
        Color::Indexed(i) => format!("idx{i}"),
        named => NAMED
            .iter()
            .find(|&&(n, _)| n == named)
            .map_or_else(|| "reset".into(), |&(_, name)| name.into()),
    }
}

/// Reads what [`colour_name`] writes.
#[must_use]
pub fn parse_colour_name(s: &str) -> Option<Color> {
    if s == "reset" {
        return Some(Color::Reset);
    }
    if let Some(hex) = s.strip_prefix('#') {
        if hex.len() != 6 || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
            return None;
        }
        let v = u32::from_str_radix(hex, 16).ok()?;
        return Some(Color::Rgb((v >> 16) as u8, (v >> 8) as u8, v as u8));
    }
    if let Some(i) = s.strip_prefix("idx") {
        return i.parse().ok().map(Color::Indexed);
    }
    NAMED.iter().find(|&&(_, name)| name == s).map(|&(c, _)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn named_indexed_and_rgb_stay_apart_and_read_back() {
        let colours = [
            Color::Green,
            Color::Indexed(2),
            Color::Rgb(0, 205, 0),
            Color::Reset,
        ];
        for c in colours {
            assert_eq!(parse_colour_name(&colour_name(c)), Some(c));
        }
        let names: Vec<String> = colours.iter().map(|&c| colour_name(c)).collect();
        assert_eq!(names, ["green", "idx2", "#00cd00", "reset"]);
        // The same xterm RGB, for pictures only.
        assert_eq!(ratatui_rgb(Color::Green), ratatui_rgb(Color::Indexed(2)));
        assert_eq!(parse_colour_name("#12345"), None);
        assert_eq!(parse_colour_name("idx256"), None);
    }
}
