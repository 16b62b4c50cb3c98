//! The colour ladder: how many colours the terminal can show, and how to guess it from the environment.

use std::fmt;
use std::str::FromStr;

/// How colours reach the terminal; each step down sends fewer bytes and works on more terminals.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ColorLevel {
    /// 24-bit `38;2;r;g;b` colours: exact.
    TrueColor,
    /// xterm colours 16–255 (6×6×6 cube + grey ramp), never the theme-dependent 0–15.
    Ansi256,
    /// The 16 ANSI colours (30–37, 90–97 / 40–47, 100–107).
    Ansi16,
    /// No colour at all: an ASCII shade ramp.
    Mono,
}

impl ColorLevel {
    /// Every level, best first (for benches and tests that cover the whole ladder).
    pub const ALL: [ColorLevel; 4] = [
        ColorLevel::TrueColor,
        ColorLevel::Ansi256,
        ColorLevel::Ansi16,
        ColorLevel::Mono,
    ];

    /// Guesses the level from `COLORTERM`, `TERM` and `NO_COLOR` (passed in so it is testable).
    ///
    /// `NO_COLOR` (non-empty) wins; `COLORTERM=truecolor|24bit` or a `*-direct` TERM gives 24-bit;
    /// a `*256color*` TERM gives 256; `dumb` gives mono; anything else gives 16.
    #[must_use]
    pub fn detect(colorterm: Option<&str>, term: Option<&str>, no_color: Option<&str>) -> Self {
        if no_color.is_some_and(|v| !v.is_empty()) {
            return ColorLevel::Mono;
        }
        let colorterm = colorterm.unwrap_or("").to_ascii_lowercase();
        let term = term.unwrap_or("").to_ascii_lowercase();
        if colorterm == "truecolor" || colorterm == "24bit" || term.ends_with("-direct") {
            ColorLevel::TrueColor
        } else if term.contains("256color") {
            ColorLevel::Ansi256
        } else if term == "dumb" {
            ColorLevel::Mono
        } else {
            ColorLevel::Ansi16
        }
    }

    /// The next rung down the ladder (what a bandwidth cap falls back to), `None` at mono.
    #[must_use]
    pub fn lower(self) -> Option<Self> {
        match self {
            ColorLevel::TrueColor => Some(ColorLevel::Ansi256),
            ColorLevel::Ansi256 => Some(ColorLevel::Ansi16),
            ColorLevel::Ansi16 => Some(ColorLevel::Mono),
            ColorLevel::Mono => None,
        }
    }

    /// The name used on the command line and in bench JSON.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            ColorLevel::TrueColor => "truecolor",
            ColorLevel::Ansi256 => "256",
            ColorLevel::Ansi16 => "16",
            ColorLevel::Mono => "mono",
        }
    }
}

impl fmt::Display for ColorLevel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ColorLevel {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "truecolor" | "24bit" | "24-bit" => Ok(ColorLevel::TrueColor),
            "256" => Ok(ColorLevel::Ansi256),
            "16" => Ok(ColorLevel::Ansi16),
            "mono" | "none" => Ok(ColorLevel::Mono),
            _ => Err(format!(
                "'{s}' is not a colour level (truecolor, 256, 16 or mono)"
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn detection_follows_the_usual_conventions() {
        use ColorLevel::*;
        let d = ColorLevel::detect;
        assert_eq!(
            d(Some("truecolor"), Some("xterm-256color"), None),
            TrueColor
        );
        assert_eq!(d(Some("24bit"), None, None), TrueColor);
        assert_eq!(d(None, Some("xterm-direct"), None), TrueColor);
        assert_eq!(d(None, Some("xterm-256color"), None), Ansi256);
        assert_eq!(d(None, Some("screen-256color"), None), Ansi256);
        assert_eq!(d(None, Some("xterm"), None), Ansi16);
        assert_eq!(d(None, Some("linux"), None), Ansi16);
        assert_eq!(d(None, None, None), Ansi16);
        assert_eq!(d(None, Some("dumb"), None), Mono);
        assert_eq!(d(Some("truecolor"), Some("xterm"), Some("1")), Mono);
        assert_eq!(d(Some("truecolor"), None, Some("")), TrueColor);
    }

    #[test]
    fn the_ladder_goes_down_to_mono() {
        let mut l = ColorLevel::TrueColor;
        let mut steps = vec![l];
        while let Some(n) = l.lower() {
            steps.push(n);
            l = n;
        }
        assert_eq!(steps, ColorLevel::ALL);
    }

    #[test]
    fn names_round_trip() {
        for l in ColorLevel::ALL {
            assert_eq!(l.name().parse::<ColorLevel>(), Ok(l));
        }
        assert!("lots".parse::<ColorLevel>().is_err());
    }
}
