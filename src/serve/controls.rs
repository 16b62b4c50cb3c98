//! What the keys do in a session, and which movement keys count as held.
//!
//! STAND-IN for the TUI branch's input model (key map, kitty press/release, auto-repeat hold).
//! When merging, map [`KeyEvent`]s to the TUI's `game::Input` instead and drop [`HeldKeys`].

use std::time::{Duration, Instant};

use super::input::{Key, KeyEvent, KeyKind};
use super::player::Held;

/// How long a key counts as held after its first press without a release event (bridges the
/// terminal's auto-repeat delay so held keys don't stutter).
const FIRST_HOLD: Duration = Duration::from_millis(300);
/// How long after each auto-repeat a key still counts as held.
const REPEAT_HOLD: Duration = Duration::from_millis(120);

/// A key's meaning in a session.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// One of the six movement keys (index into [`HeldKeys`]).
    Move(usize),
    Quit,
    CycleColour,
    /// Spectators: follow the next player (Tab) or the previous one (Shift-Tab).
    NextTarget,
    PrevTarget,
    Nothing,
}

/// The key map: W/S or ↑/↓ walk, A/D or ←/→ turn, Q/E strafe; Esc or Ctrl-C quits; C cycles colours.
#[must_use]
pub fn action(key: Key) -> Action {
    match key {
        Key::Char('w' | 'W') | Key::Up => Action::Move(0),
        Key::Char('s' | 'S') | Key::Down => Action::Move(1),
        Key::Char('a' | 'A') | Key::Left => Action::Move(2),
        Key::Char('d' | 'D') | Key::Right => Action::Move(3),
        Key::Char('q' | 'Q') => Action::Move(4),
        Key::Char('e' | 'E') => Action::Move(5),
        Key::Esc | Key::Ctrl('c' | 'd') => Action::Quit,
        Key::Char('c' | 'C') => Action::CycleColour,
        Key::Tab => Action::NextTarget,
        Key::BackTab => Action::PrevTarget,
        _ => Action::Nothing,
    }
}

/// Per movement key: held until a deadline (plain terminals) or until released (kitty).
#[derive(Debug, Clone, Default)]
pub struct HeldKeys {
    until: [Option<Instant>; 6],
    /// The terminal reports releases (kitty protocol answered), so no deadlines are needed.
    pub releases: bool,
}

impl HeldKeys {
    /// Updates from one key event at time `now`; returns the event's action.
    pub fn on_event(&mut self, ev: KeyEvent, now: Instant) -> Action {
        let act = action(ev.key);
        if let Action::Move(i) = act {
            self.until[i] = match (ev.kind, self.releases) {
                (KeyKind::Release, _) => None,
                // With release events, a press holds until its release (bounded for safety).
                (_, true) => Some(now + Duration::from_secs(30)),
                (KeyKind::Repeat, false) => Some(now + REPEAT_HOLD),
                (KeyKind::Press, false) => match self.until[i] {
                    Some(t) if t > now => Some(now + REPEAT_HOLD.max(t - now)),
                    _ => Some(now + FIRST_HOLD),
                },
            };
        }
        if ev.kind == KeyKind::Release {
            return Action::Nothing;
        }
        act
    }

    /// The movement keys held at `now`.
    #[must_use]
    pub fn held(&self, now: Instant) -> Held {
        let on = |i: usize| self.until[i].is_some_and(|t| t > now);
        Held {
            forward: on(0),
            back: on(1),
            turn_left: on(2),
            turn_right: on(3),
            strafe_left: on(4),
            strafe_right: on(5),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ev(key: Key, kind: KeyKind) -> KeyEvent {
        KeyEvent { key, kind }
    }

    #[test]
    fn a_tap_holds_briefly_and_repeats_keep_it_held() {
        let t0 = Instant::now();
        let mut h = HeldKeys::default();
        assert_eq!(
            h.on_event(ev(Key::Char('w'), KeyKind::Press), t0),
            Action::Move(0)
        );
        assert!(h.held(t0 + Duration::from_millis(250)).forward);
        assert!(!h.held(t0 + Duration::from_millis(400)).forward);
        h.on_event(
            ev(Key::Char('w'), KeyKind::Press),
            t0 + Duration::from_millis(280),
        );
        assert!(h.held(t0 + Duration::from_millis(350)).forward);
    }

    #[test]
    fn releases_end_holds_in_kitty_mode() {
        let t0 = Instant::now();
        let mut h = HeldKeys {
            releases: true,
            ..HeldKeys::default()
        };
        h.on_event(ev(Key::Left, KeyKind::Press), t0);
        assert!(h.held(t0 + Duration::from_secs(5)).turn_left);
        assert_eq!(
            h.on_event(ev(Key::Left, KeyKind::Release), t0),
            Action::Nothing
        );
        assert!(!h.held(t0).turn_left);
    }
}
