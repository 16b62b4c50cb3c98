//! How many colours a client's terminal shows, guessed from its `TERM` and cycled with a key.
//!
//! STAND-IN: the encoder branch (`src/encode/`) brings the project's colour ladder; when it is
//! merged, replace this enum with the encoder's and keep only [`from_term`] here if it has none.

/// The colour levels a session can render at, richest first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorLevel {
    Truecolor,
    Ansi256,
    Ansi16,
    Mono,
}

impl ColorLevel {
    /// The next level down, wrapping to truecolor (the session's colour key).
    #[must_use]
    pub fn next(self) -> Self {
        match self {
            Self::Truecolor => Self::Ansi256,
            Self::Ansi256 => Self::Ansi16,
            Self::Ansi16 => Self::Mono,
            Self::Mono => Self::Truecolor,
        }
    }

    /// Short name for the status line and logs.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Truecolor => "truecolor",
            Self::Ansi256 => "256",
            Self::Ansi16 => "16",
            Self::Mono => "mono",
        }
    }
}

/// The level a terminal advertising `term` (and optionally `COLORTERM`) can show.
#[must_use]
pub fn from_term(term: &str, colorterm: Option<&str>) -> ColorLevel {
    let term = term.to_ascii_lowercase();
    if matches!(colorterm, Some(c) if c.eq_ignore_ascii_case("truecolor") || c.eq_ignore_ascii_case("24bit"))
    {
        return ColorLevel::Truecolor;
    }
    let truecolor_terms = [
        "direct",
        "truecolor",
        "24bit",
        "kitty",
        "alacritty",
        "wezterm",
        "foot",
        "ghostty",
        "iterm",
        "contour",
    ];
    if truecolor_terms.iter().any(|t| term.contains(t)) {
        ColorLevel::Truecolor
    } else if term.contains("256") {
        ColorLevel::Ansi256
    } else if term.is_empty() || term == "dumb" {
        ColorLevel::Mono
    } else {
        ColorLevel::Ansi16
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn term_names_map_to_levels() {
        assert_eq!(from_term("xterm-kitty", None), ColorLevel::Truecolor);
        assert_eq!(from_term("xterm-256color", None), ColorLevel::Ansi256);
        assert_eq!(
            from_term("xterm-256color", Some("truecolor")),
            ColorLevel::Truecolor
        );
        assert_eq!(from_term("xterm", None), ColorLevel::Ansi16);
        assert_eq!(from_term("dumb", None), ColorLevel::Mono);
        assert_eq!(ColorLevel::Mono.next(), ColorLevel::Truecolor);
    }
}
