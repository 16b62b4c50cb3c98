//! What a session does with a key: the keys only a server has (switching whom a spectator
//! follows), and everything else — the colour key too — handed to `ui::keys::Controls`, the keys
//! of a local terminal, as the crossterm event a local terminal would have produced.

use crossterm::event::{
    Event, KeyCode, KeyEvent as CtKeyEvent, KeyEventKind, KeyEventState, KeyModifiers,
};

use super::key_bytes::{Key, KeyEvent, KeyKind};

/// Where a key goes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Routed {
    /// Follow the next player (Tab) or the previous one (Shift-Tab).
    NextTarget,
    PrevTarget,
    /// Show or hide the server's lasting leaderboard (`L`, shifted: `l` stays night mode).
    Leaderboard,
    /// The TUI's key map decides (movement, doors, debugger, panes, help, quit).
    Tui(Event),
    /// Releases and repeats of server keys, and keys no terminal library names.
    Nothing,
}

/// Routes one parsed key event.
#[must_use]
pub fn route(ev: KeyEvent) -> Routed {
    let kind = match ev.kind {
        KeyKind::Press => KeyEventKind::Press,
        KeyKind::Repeat => KeyEventKind::Repeat,
        KeyKind::Release => KeyEventKind::Release,
    };
    let server_key = match ev.key {
        Key::Tab => Some(Routed::NextTarget),
        Key::BackTab => Some(Routed::PrevTarget),
        Key::Char('L') => Some(Routed::Leaderboard),
        _ => None,
    };
    if let Some(r) = server_key {
        return if kind == KeyEventKind::Press {
            r
        } else {
            Routed::Nothing
        };
    }
    let (code, modifiers) = match ev.key {
        Key::Char(c) if c.is_ascii_uppercase() => (KeyCode::Char(c), KeyModifiers::SHIFT),
        Key::Char(c) => (KeyCode::Char(c), KeyModifiers::NONE),
        Key::Ctrl(c) => (KeyCode::Char(c), KeyModifiers::CONTROL),
        Key::Up => (KeyCode::Up, KeyModifiers::NONE),
        Key::Down => (KeyCode::Down, KeyModifiers::NONE),
        Key::Left => (KeyCode::Left, KeyModifiers::NONE),
        Key::Right => (KeyCode::Right, KeyModifiers::NONE),
        Key::Home => (KeyCode::Home, KeyModifiers::NONE),
        Key::End => (KeyCode::End, KeyModifiers::NONE),
        Key::PageUp => (KeyCode::PageUp, KeyModifiers::NONE),
        Key::PageDown => (KeyCode::PageDown, KeyModifiers::NONE),
        Key::Insert => (KeyCode::Insert, KeyModifiers::NONE),
        Key::Delete => (KeyCode::Delete, KeyModifiers::NONE),
        Key::Enter => (KeyCode::Enter, KeyModifiers::NONE),
        Key::Backspace => (KeyCode::Backspace, KeyModifiers::NONE),
        Key::Esc => (KeyCode::Esc, KeyModifiers::NONE),
        Key::F(n) => (KeyCode::F(n), KeyModifiers::NONE),
        Key::Tab | Key::BackTab => return Routed::Nothing,
    };
    Routed::Tui(Event::Key(CtKeyEvent {
        code,
        modifiers,
        kind,
        state: KeyEventState::NONE,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::{Action, Command};
    use crate::ui::keys::{Controls, InputMode, UiCommand};
    use std::time::Instant;

    fn press(key: Key) -> KeyEvent {
        KeyEvent {
            key,
            kind: KeyKind::Press,
        }
    }

    fn feed(c: &mut Controls, key: Key, kind: KeyKind, now: Instant) {
        if let Routed::Tui(ev) = route(KeyEvent { key, kind }) {
            c.handle(&ev, now);
        }
    }

    #[test]
    fn server_keys_fire_on_press_only() {
        assert_eq!(route(press(Key::Tab)), Routed::NextTarget);
        assert_eq!(route(press(Key::BackTab)), Routed::PrevTarget);
        let release = KeyEvent {
            key: Key::Tab,
            kind: KeyKind::Release,
        };
        assert_eq!(route(release), Routed::Nothing);
    }

    #[test]
    fn the_tui_key_map_moves_opens_doors_and_quits() {
        let now = Instant::now();
        let mut c = Controls::new(InputMode::Kitty);
        feed(&mut c, Key::Char('w'), KeyKind::Press, now);
        feed(&mut c, Key::Left, KeyKind::Press, now);
        feed(&mut c, Key::Char('E'), KeyKind::Press, now);
        let input = c.take_input(now);
        assert!(input.held.contains(Action::Forward) && input.held.contains(Action::TurnLeft));
        assert!(input.commands.contains(&Command::UseDoor));
        feed(&mut c, Key::Char('W'), KeyKind::Release, now);
        assert!(!c.take_input(now).held.contains(Action::Forward));
        feed(&mut c, Key::Ctrl('c'), KeyKind::Press, now);
        feed(&mut c, Key::Char('m'), KeyKind::Press, now);
        feed(&mut c, Key::Char('O'), KeyKind::Press, now);
        assert_eq!(
            c.take_ui(),
            [
                UiCommand::Quit,
                UiCommand::ToggleMinimap,
                UiCommand::CycleColours
            ]
        );
    }
}
