//! Whether octants are known not to reach the player's screen: a rule over the few values a
//! session can read, with no I/O of its own. The local terminal passes its environment
//! (`TERM`, `TMUX`); an SSH session passes the pty request's terminal name and whatever
//! environment the client chose to send.
//!
//! tmux measures every character with its host's width table and drops the ones it does not
//! know: tmux 3.3a on Debian 12 (glibc 2.36, no Unicode 16) drops U+1CD00–1CDE5, so every row
//! of an octant view shifts left. Sextants and quadrants pass. A pane cannot learn which table
//! its tmux server uses, so any tmux counts; so does a multiplexer whose `TERM` says `screen`
//! (tmux's own default before `tmux-256color`, and GNU screen's).

/// The values the rule reads; each edge fills in what it can know (`None`: not known).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TermEnv<'a> {
    /// `TERM` locally; over SSH, the terminal name of the client's pty request.
    pub term: Option<&'a str>,
    /// `TMUX`, which tmux sets in every pane (over SSH only if the client sends it).
    pub tmux: Option<&'a str>,
}

/// What sits between halfcast and the terminal and drops octant characters.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum OctantDropper {
    /// `TMUX` is set, or `TERM` starts with `tmux`.
    Tmux,
    /// `TERM` starts with `screen` (tmux or GNU screen: the name cannot tell them apart).
    Multiplexer,
}

impl OctantDropper {
    /// How the status line names it.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            OctantDropper::Tmux => "tmux",
            OctantDropper::Multiplexer => "screen/tmux",
        }
    }
}

/// What drops octants on this session's way to the screen, when `env` shows one.
#[must_use]
pub fn octant_dropper(env: TermEnv<'_>) -> Option<OctantDropper> {
    if env.tmux.is_some_and(|t| !t.trim().is_empty()) {
        return Some(OctantDropper::Tmux);
    }
    let term = env.term.unwrap_or_default().trim().to_ascii_lowercase();
    if term.starts_with("tmux") {
        Some(OctantDropper::Tmux)
    } else if term.starts_with("screen") {
        Some(OctantDropper::Multiplexer)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(term: Option<&'a str>, tmux: Option<&'a str>) -> TermEnv<'a> {
        TermEnv { term, tmux }
    }

    #[test]
    fn tmux_is_seen_by_its_variable_whatever_term_says() {
        let tmux = Some("/tmp/tmux-1000/default,4242,0");
        for term in [None, Some("xterm-256color"), Some("xterm-kitty"), Some("")] {
            assert_eq!(octant_dropper(env(term, tmux)), Some(OctantDropper::Tmux));
        }
    }

    #[test]
    fn a_multiplexer_term_is_seen_without_the_variable() {
        assert_eq!(
            octant_dropper(env(Some("tmux-256color"), None)),
            Some(OctantDropper::Tmux)
        );
        assert_eq!(
            octant_dropper(env(Some("tmux-direct"), None)),
            Some(OctantDropper::Tmux)
        );
        for term in [
            "screen",
            "screen-256color",
            "SCREEN.xterm-256color",
            " screen ",
        ] {
            assert_eq!(
                octant_dropper(env(Some(term), None)),
                Some(OctantDropper::Multiplexer),
                "{term}"
            );
        }
    }

    #[test]
    fn plain_terminals_and_unknowns_drop_nothing_known() {
        for term in [
            None,
            Some(""),
            Some("xterm-256color"),
            Some("xterm-kitty"),
            Some("foot"),
            Some("alacritty"),
            Some("xterm-screen"),
            Some("dumb"),
        ] {
            assert_eq!(octant_dropper(env(term, None)), None, "{term:?}");
        }
        // An empty TMUX (a shell that unset it by assigning nothing) is no tmux.
        assert_eq!(octant_dropper(env(Some("xterm"), Some(""))), None);
    }

    #[test]
    fn names_for_the_status_line() {
        assert_eq!(OctantDropper::Tmux.name(), "tmux");
        assert_eq!(OctantDropper::Multiplexer.name(), "screen/tmux");
    }
}
