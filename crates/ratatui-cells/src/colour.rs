//! The colours a cell keeps, exactly as the app or the terminal named them (ratatui's
//! [`Color`]: the terminal default, the 16 named colours, the 256 indexed ones, 24-bit RGB), and
//! how the cells text writes them.

use ratatui_core::style::Color;

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

/// The 16 ANSI colours as xterm shows them by default.
const ANSI16: [[u8; 3]; 16] = [
    [0, 0, 0],
    [205, 0, 0],
    [0, 205, 0],
    [205, 205, 0],
    [0, 0, 238],
    [205, 0, 205],
    [0, 205, 205],
    [229, 229, 229],
    [127, 127, 127],
    [255, 0, 0],
    [0, 255, 0],
    [255, 255, 0],
    [92, 92, 255],
    [255, 0, 255],
    [0, 255, 255],
    [255, 255, 255],
];

/// The six channel levels of the 256-colour palette's 6×6×6 cube.
const CUBE_LEVELS: [u8; 6] = [0, 95, 135, 175, 215, 255];

/// The RGB of palette index `i` in xterm's default palette (the 16 colours, the cube, the greys).
fn palette_rgb(i: u8) -> [u8; 3] {
    match i {
        0..=15 => ANSI16[usize::from(i)],
        16..=231 => {
            let n = usize::from(i - 16);
            [
                CUBE_LEVELS[n / 36],
                CUBE_LEVELS[(n / 6) % 6],
                CUBE_LEVELS[n % 6],
            ]
        }
        _ => {
            let g = 8 + 10 * (i - 232);
            [g, g, g]
        }
    }
}

/// The RGB a ratatui colour shows as in xterm's default palette (`None` = the terminal's
/// default): for colour distances in diff reports only, since a user's palette may differ.
#[must_use]
pub fn xterm_rgb(c: Color) -> Option<[u8; 3]> {
    match c {
        Color::Reset => None,
        Color::Rgb(r, g, b) => Some([r, g, b]),
        Color::Indexed(i) => Some(palette_rgb(i)),
        named => named_index(named).map(palette_rgb),
    }
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
        // The same xterm RGB, for colour distances only.
        assert_eq!(xterm_rgb(Color::Green), xterm_rgb(Color::Indexed(2)));
        assert_eq!(xterm_rgb(Color::Green), Some([0, 205, 0]));
        assert_eq!(parse_colour_name("#12345"), None);
        assert_eq!(parse_colour_name("idx256"), None);
    }
}
