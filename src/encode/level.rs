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
    /// The `TERM` name rule (nothing better was known).
    Term,
    /// The player cycled it with the colour key.
    Key,
    /// `--max-bandwidth --adapt-colors` stepped it down.
    Bandwidth,
    /// The SSH session's link carried too few frames at a richer level (or again enough).
    Link,
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
            ColourReason::Term => "TERM",
            ColourReason::Key => "O key",
            ColourReason::Bandwidth => "bandwidth cap",
            ColourReason::Link => "link",
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
        self.reason == ColourReason::Term && self.level != ColorLevel::TrueColor
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
        assert_eq!(d(None, Some("xterm"), None), Ansi16);
        assert_eq!(d(None, Some("linux"), None), Ansi16);
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
