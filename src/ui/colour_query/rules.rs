//! Which colour level a terminal gets: the environment's guess first, then what the terminal
//! said of itself. One rule set for the local game and the SSH server.
//!
//! In order: `--colors` / the config file, `NO_COLOR`, `COLORTERM`, then (when those leave a
//! `TERM` guess below 24-bit) the terminal's answers: a 24-bit XTGETTCAP or DECRQSS reply, or
//! PuTTY's answerback with its VT102 device attributes; else the `TERM` guess
//! ([`ColorLevel::detect`]: a plain `xterm` is 256).

use super::{Answers, PUTTY_ANSWERBACK};
use crate::encode::{ColorLevel, ColourChoice, ColourReason};

/// PuTTY's DA1 reply parameters (`ESC [ ? 6 c`: a VT102).
pub const PUTTY_DEVICE: &str = "6";

/// The choice the environment gives before asking: [`ColourChoice::from_env`], with an empty
/// `TERM` (an SSH client that sent none) taken as `dumb`.
#[must_use]
pub fn guess(colorterm: Option<&str>, term: Option<&str>, no_color: Option<&str>) -> ColourChoice {
    let term = term.map(|t| if t.is_empty() { "dumb" } else { t });
    ColourChoice::from_env(colorterm, term, no_color)
}

/// Whether these answers are PuTTY's: its default answerback together with DA1 `?6c` (a PuTTY
/// whose answerback was changed is not recognised, and falls back to the next rule).
#[must_use]
pub fn is_putty(answers: &Answers) -> bool {
    answers.answerback.as_deref() == Some(PUTTY_ANSWERBACK)
        && answers.device.as_deref() == Some(PUTTY_DEVICE)
}

/// `choice` after the terminal's answers: a 24-bit reply upgrades a `TERM` guess ("terminal
/// said so"); else PuTTY (which draws 24-bit colour by default) upgrades a guess from a `TERM`
/// that names no colours; else the guess stands.
#[must_use]
pub fn decide(choice: ColourChoice, answers: &Answers) -> ColourChoice {
    let said = choice.with_answer(answers.truecolor);
    if said != choice {
        return said;
    }
    if choice.worth_an_answerback() && is_putty(answers) {
        return ColourChoice {
            level: ColorLevel::TrueColor,
            reason: ColourReason::Putty,
        };
    }
    choice
}

#[cfg(test)]
mod tests {
    use super::*;

    fn answers(
        truecolor: Option<bool>,
        device: Option<&str>,
        answerback: Option<&[u8]>,
    ) -> Answers {
        Answers {
            truecolor,
            device: device.map(str::to_owned),
            answerback: answerback.map(<[u8]>::to_vec),
        }
    }

    /// The level shown for a client with `term` (no `COLORTERM`) and these answers.
    fn shown(term: &str, a: &Answers) -> String {
        decide(guess(None, Some(term), None), a).to_string()
    }

    const PUTTY: &[u8] = b"PuTTY";

    #[test]
    fn putty_by_its_answers_gets_truecolor() {
        let a = answers(None, Some("6"), Some(PUTTY));
        assert!(is_putty(&a));
        assert_eq!(shown("xterm", &a), "truecolor (PuTTY)");
        // Whatever TERM names no colours: PuTTY set to say vt100, or linux.
        assert_eq!(shown("vt100", &a), "truecolor (PuTTY)");
        assert_eq!(shown("putty", &a), "truecolor (PuTTY)");
    }

    #[test]
    fn half_of_putty_is_not_putty() {
        for a in [
            answers(None, Some("6"), Some(b"KiTTY")),
            answers(None, Some("6"), Some(b"")),
            answers(None, Some("6"), Some(b"putty")),
            answers(None, Some("6"), Some(b"PuTTY\r")),
            answers(None, Some("6"), None),
            answers(None, Some("62;22"), Some(PUTTY)),
            answers(None, Some("1;2"), Some(PUTTY)),
            answers(None, None, Some(PUTTY)),
            Answers::default(),
        ] {
            assert!(!is_putty(&a), "{a:?}");
            assert_eq!(shown("xterm", &a), "256 (TERM)", "{a:?}");
            assert_eq!(shown("linux", &a), "16 (TERM)", "{a:?}");
            assert_eq!(shown("vt100", &a), "16 (TERM)", "{a:?}");
            assert_eq!(shown("screen", &a), "16 (TERM)", "{a:?}");
        }
    }

    #[test]
    fn a_24_bit_reply_still_says_so_first() {
        // A real xterm answers the queries: truecolor, as before.
        let a = answers(Some(true), Some("64;1;2;6;22"), Some(b""));
        assert_eq!(shown("xterm", &a), "truecolor (terminal said so)");
        assert_eq!(
            shown("xterm", &answers(Some(true), Some("6"), Some(PUTTY))),
            "truecolor (terminal said so)"
        );
        // A negative reply leaves the guess.
        assert_eq!(
            shown("xterm", &answers(Some(false), Some("6"), Some(b""))),
            "256 (TERM)"
        );
    }

    #[test]
    fn a_term_that_names_its_colours_or_the_users_word_is_not_second_guessed_by_an_answerback() {
        let a = answers(None, Some("6"), Some(PUTTY));
        assert_eq!(shown("xterm-256color", &a), "256 (TERM)");
        assert_eq!(shown("dumb", &a), "mono (TERM)");
        assert_eq!(shown("", &a), "mono (TERM)");
        let c = guess(Some("truecolor"), Some("xterm"), None);
        assert_eq!(decide(c, &a).to_string(), "truecolor (COLORTERM)");
        let c = guess(None, Some("xterm"), Some("1"));
        assert_eq!(decide(c, &a).to_string(), "mono (NO_COLOR)");
        let c = ColourChoice::flag(ColorLevel::Ansi16);
        assert_eq!(decide(c, &a).to_string(), "16 (--colors)");
        let c = ColourChoice::config(ColorLevel::Ansi256);
        assert_eq!(decide(c, &a).to_string(), "256 (config)");
        // COLORTERM said something, though not 24-bit: its terminal is not guessed at.
        let c = guess(Some("gnome-terminal"), Some("xterm"), None);
        assert_eq!(decide(c, &a).to_string(), "256 (TERM)");
    }

    #[test]
    fn with_no_answers_the_term_rule_stands() {
        let none = Answers::default();
        for (term, level) in [
            ("xterm", "256 (TERM)"),
            ("xterm-256color", "256 (TERM)"),
            ("screen-256color", "256 (TERM)"),
            ("tmux-256color", "256 (TERM)"),
            ("xterm-direct", "truecolor (TERM)"),
            ("xterm-kitty", "truecolor (TERM)"),
            ("alacritty", "truecolor (TERM)"),
            ("foot", "truecolor (TERM)"),
            ("wezterm", "truecolor (TERM)"),
            ("xterm-ghostty", "truecolor (TERM)"),
            ("linux", "16 (TERM)"),
            ("vt100", "16 (TERM)"),
            ("vt220", "16 (TERM)"),
            ("screen", "16 (TERM)"),
            ("xterm-color", "16 (TERM)"),
            ("dumb", "mono (TERM)"),
            ("", "mono (TERM)"),
        ] {
            assert_eq!(shown(term, &none), level, "{term}");
        }
    }
}
