//! The colour ladder: how many colours the terminal can show, and how to guess it from the environment.

use std::fmt;
use std::str::FromStr;

/// Parts of a `TERM` that name a terminal drawing 24-bit colour whatever else the name says
/// (kitty says `xterm-kitty`, WezTerm `wezterm`, …).
pub const TRUECOLOR_TERMS: [&str; 9] = [
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

/// The `TERM` PuTTY sends by default (and other clients built like it): every emulator still
/// saying it draws the 256 xterm colours, so it is guessed as 256, not 16.
pub const PLAIN_XTERM: &str = "xterm";

/// Whether a (lower-case) `TERM` itself says 24-bit colour.
fn term_says_truecolor(term: &str) -> bool {
    term.ends_with("-direct") || TRUECOLOR_TERMS.iter().any(|t| term.contains(t))
}

/// Whether a `TERM` names how many colours its terminal draws (`*-256color`, `*-direct`, a
/// 24-bit terminal's own name, `dumb`); `xterm`, `linux`, `vt100` and `screen` do not, so a
/// level from them is a guess that the terminal's own answers may correct.
#[must_use]
pub fn term_names_colours(term: &str) -> bool {
    let term = term.to_ascii_lowercase();
    term_says_truecolor(&term) || term.contains("256color") || term == "dumb"
}

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
    /// Whether colours are drawn as mixes of palette entries (256 and 16 colours): the levels
    /// whose encoders read the dither phases renderers write.
    #[must_use]
    pub fn mixes(self) -> bool {
        matches!(self, ColorLevel::Ansi256 | ColorLevel::Ansi16)
    }

    /// Every level, best first (for benches and tests that cover the whole ladder).
    pub const ALL: [ColorLevel; 4] = [
        ColorLevel::TrueColor,
        ColorLevel::Ansi256,
        ColorLevel::Ansi16,
        ColorLevel::Mono,
    ];

    /// Guesses the level from `COLORTERM`, `TERM` and `NO_COLOR` (passed in so it is testable).
    ///
    /// `NO_COLOR` (non-empty) wins; `COLORTERM=truecolor|24bit`, a `*-direct` TERM or a terminal
    /// known to draw 24-bit colour whatever its `TERM` (`TRUECOLOR_TERMS`) gives 24-bit; a
    /// `*256color*` TERM or a plain `xterm` gives 256; `dumb` gives mono; anything else gives 16.
    #[must_use]
    pub fn detect(colorterm: Option<&str>, term: Option<&str>, no_color: Option<&str>) -> Self {
        if no_color.is_some_and(|v| !v.is_empty()) {
            return ColorLevel::Mono;
        }
        let colorterm = colorterm.unwrap_or("").to_ascii_lowercase();
        let term = term.unwrap_or("").to_ascii_lowercase();
        if colorterm == "truecolor" || colorterm == "24bit" || term_says_truecolor(&term) {
            ColorLevel::TrueColor
        } else if term.contains("256color") || term == PLAIN_XTERM {
            ColorLevel::Ansi256
        } else if term == "dumb" {
            ColorLevel::Mono
        } else {
            ColorLevel::Ansi16
        }
    }

    /// The level this process's environment asks for: [`ColorLevel::detect`] of `COLORTERM`,
    /// `TERM` and `NO_COLOR` (no terminal query, so it never waits or reads input).
    #[must_use]
    pub fn from_env() -> Self {
        let var = |name| std::env::var(name).ok();
        Self::detect(
            var("COLORTERM").as_deref(),
            var("TERM").as_deref(),
            var("NO_COLOR").as_deref(),
        )
    }

    /// The level after this one in the colour key's cycle: truecolor → 256 → 16 → mono → truecolor.
    #[must_use]
    pub fn cycled(self) -> Self {
        self.lower().unwrap_or(ColorLevel::TrueColor)
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

/// Why a colour level was chosen: shown next to it (`256 (TERM)`), so a player who sees the
/// wrong colours knows what to change.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ColourReason {
    /// `--colors` on the command line.
    Flag,
    /// `colors` in the config file.
    Config,
    /// `NO_COLOR` is set.
    NoColor,
    /// `COLORTERM` said 24-bit (locally, or sent by the SSH client as an env request).
    Colorterm,
    /// The terminal answered a query (XTGETTCAP `RGB`/`Tc`, or DECRQSS of a 24-bit SGR).
    TerminalSaid,
    /// The `TERM` name rule, from a `TERM` that names its colours (`*-256color`, `*-direct`,
    /// `dumb`, a 24-bit terminal's own name).
    Term,
    /// The `TERM` name rule, from a `TERM` that names no colours (`xterm`, `linux`, `vt100`,
    /// `screen`…) with `COLORTERM` silent: only a guess, so the terminal's answerback is
    /// worth asking for too. Shown as `TERM` all the same.
    TermGuess,
    /// The terminal said it is PuTTY (answerback `PuTTY` and VT102 device attributes), which
    /// draws 24-bit colour by default while sending `TERM=xterm`.
    Putty,
    /// The player cycled it with the colour key.
    Key,
    /// `--max-bandwidth --adapt-colors` stepped it down.
    Bandwidth,
    /// The SSH session's link carried too few frames at a richer level (or again enough).
    Link,
    /// A browser page, which draws every 24-bit colour.
    Browser,
}

impl ColourReason {
    /// The words shown in brackets after the level.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            ColourReason::Flag => "--colors",
            ColourReason::Config => "config",
            ColourReason::NoColor => "NO_COLOR",
            ColourReason::Colorterm => "COLORTERM",
            ColourReason::TerminalSaid => "terminal said so",
            ColourReason::Term | ColourReason::TermGuess => "TERM",
            ColourReason::Putty => "PuTTY",
            ColourReason::Key => "O key",
            ColourReason::Bandwidth => "bandwidth cap",
            ColourReason::Link => "link",
            ColourReason::Browser => "browser",
        }
    }
}

/// A colour level and how it was decided.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ColourChoice {
    /// The level chosen.
    pub level: ColorLevel,
    /// Why it was chosen (shown beside it).
    pub reason: ColourReason,
}

impl ColourChoice {
    /// The choice the environment alone gives (same rule as [`ColorLevel::detect`]), with why.
    #[must_use]
    pub fn from_env(colorterm: Option<&str>, term: Option<&str>, no_color: Option<&str>) -> Self {
        let level = ColorLevel::detect(colorterm, term, no_color);
        let reason = if no_color.is_some_and(|v| !v.is_empty()) {
            ColourReason::NoColor
        } else if matches!(
            colorterm.map(str::to_ascii_lowercase).as_deref(),
            Some("truecolor" | "24bit")
        ) {
            ColourReason::Colorterm
        } else if colorterm.unwrap_or("").is_empty() && !term_names_colours(term.unwrap_or("")) {
            ColourReason::TermGuess
        } else {
            ColourReason::Term
        };
        Self { level, reason }
    }

    /// A level fixed by `--colors`.
    #[must_use]
    pub fn flag(level: ColorLevel) -> Self {
        Self {
            level,
            reason: ColourReason::Flag,
        }
    }

    /// A level fixed by the config file's `colors`.
    #[must_use]
    pub fn config(level: ColorLevel) -> Self {
        Self {
            level,
            reason: ColourReason::Config,
        }
    }

    /// Whether asking the terminal could still change this choice: only a `TERM` guess below
    /// 24-bit can (an explicit flag, `NO_COLOR` and `COLORTERM` are the user's word).
    #[must_use]
    pub fn worth_asking(self) -> bool {
        matches!(self.reason, ColourReason::Term | ColourReason::TermGuess)
            && self.level != ColorLevel::TrueColor
    }

    /// Whether the terminal's answerback (ENQ) could change this choice: only where `TERM`
    /// names no colours and `COLORTERM` says nothing (elsewhere ENQ is not sent at all).
    #[must_use]
    pub fn worth_an_answerback(self) -> bool {
        self.reason == ColourReason::TermGuess && self.worth_asking()
    }

    /// This choice after the terminal's answer: `Some(true)` (it shows 24-bit colour) upgrades a
    /// `TERM` guess; no answer, or a negative one, leaves it as it was.
    #[must_use]
    pub fn with_answer(self, truecolor: Option<bool>) -> Self {
        if self.worth_asking() && truecolor == Some(true) {
            Self {
                level: ColorLevel::TrueColor,
                reason: ColourReason::TerminalSaid,
            }
        } else {
            self
        }
    }

    /// The next level in the colour key's cycle.
    #[must_use]
    pub fn cycled(self) -> Self {
        Self {
            level: self.level.cycled(),
            reason: ColourReason::Key,
        }
    }
}

impl fmt::Display for ColourChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ({})", self.level.name(), self.reason.label())
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
        assert_eq!(d(None, Some("xterm"), None), Ansi256);
        assert_eq!(d(None, Some("XTERM"), None), Ansi256);
        assert_eq!(d(None, Some("xterm-kitty"), None), TrueColor);
        assert_eq!(d(None, Some("alacritty"), None), TrueColor);
        assert_eq!(d(None, Some("xterm-color"), None), Ansi16);
        assert_eq!(d(None, Some("linux"), None), Ansi16);
        assert_eq!(d(None, Some("vt100"), None), Ansi16);
        assert_eq!(d(None, Some("screen"), None), Ansi16);
        assert_eq!(d(None, Some("putty"), None), Ansi16);
        assert_eq!(d(None, None, None), Ansi16);
        assert_eq!(d(None, Some("dumb"), None), Mono);
        assert_eq!(d(Some("truecolor"), Some("xterm"), Some("1")), Mono);
        assert_eq!(d(Some("truecolor"), None, Some("")), TrueColor);
    }

    #[test]
    fn choices_say_why() {
        use ColorLevel::*;
        let env = ColourChoice::from_env;
        let c = env(None, Some("xterm-256color"), None);
        assert_eq!(c.to_string(), "256 (TERM)");
        assert!(c.worth_asking());
        assert_eq!(
            c.with_answer(Some(true)).to_string(),
            "truecolor (terminal said so)"
        );
        assert_eq!(c.with_answer(Some(false)), c);
        assert_eq!(c.with_answer(None), c);
        let c = env(Some("truecolor"), Some("xterm-256color"), None);
        assert_eq!(c.to_string(), "truecolor (COLORTERM)");
        assert!(!c.worth_asking());
        let c = env(Some("truecolor"), Some("xterm"), Some("1"));
        assert_eq!(c.to_string(), "mono (NO_COLOR)");
        assert_eq!(c.with_answer(Some(true)).level, Mono);
        assert_eq!(
            ColourChoice::flag(Ansi16)
                .with_answer(Some(true))
                .to_string(),
            "16 (--colors)"
        );
        assert!(!env(None, Some("xterm-direct"), None).worth_asking());
    }

    #[test]
    fn only_a_term_that_names_no_colours_with_colorterm_silent_is_worth_an_answerback() {
        let env = ColourChoice::from_env;
        for term in ["xterm", "linux", "vt100", "screen", "putty", "vt220"] {
            let c = env(None, Some(term), None);
            assert_eq!(c.reason, ColourReason::TermGuess, "{term}");
            assert!(c.worth_an_answerback(), "{term}");
            assert!(
                env(Some(""), Some(term), None).worth_an_answerback(),
                "{term}"
            );
            // COLORTERM said something (not 24-bit): it is not silent.
            assert!(!env(Some("gnome-terminal"), Some(term), None).worth_an_answerback());
        }
        assert_eq!(env(None, Some("xterm"), None).to_string(), "256 (TERM)");
        assert_eq!(env(None, Some("linux"), None).to_string(), "16 (TERM)");
        for term in [
            "xterm-256color",
            "screen-256color",
            "xterm-direct",
            "xterm-kitty",
            "dumb",
        ] {
            let c = env(None, Some(term), None);
            assert_eq!(c.reason, ColourReason::Term, "{term}");
            assert!(!c.worth_an_answerback(), "{term}");
        }
        assert!(env(None, Some("xterm-256color"), None).worth_asking());
        assert!(!env(Some("truecolor"), Some("xterm"), None).worth_an_answerback());
        assert!(!env(None, Some("xterm"), Some("1")).worth_an_answerback());
        assert!(!ColourChoice::flag(ColorLevel::Ansi16).worth_an_answerback());
    }

    #[test]
    fn the_colour_key_cycles_from_the_detected_level() {
        let mut c = ColourChoice::from_env(None, Some("xterm-256color"), None);
        let mut seen = Vec::new();
        for _ in 0..5 {
            c = c.cycled();
            seen.push(c.level);
        }
        use ColorLevel::*;
        assert_eq!(seen, [Ansi16, Mono, TrueColor, Ansi256, Ansi16]);
        assert_eq!(c.to_string(), "16 (O key)");
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
