//! Terminal events → game [`Input`] and UI commands, including held-key tracking.
//!
//! With the kitty keyboard protocol a key is held from its press to its release. Without
//! it a terminal only sends presses (auto-repeat), so a key counts as held until its repeats
//! stop: long enough after the first press to bridge the repeat delay, short after a repeat.
//! The clock is passed in (`now`), so all of this is testable without a terminal.

use std::time::{Duration, Instant};

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};

use super::repeat::RepeatTiming;
use crate::game::{Action, Command, Held, Input};

/// How key presses and releases reach us; shown in the status line and help.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputMode {
    /// Kitty keyboard protocol: real press, repeat and release events.
    Kitty,
    /// Presses only; holds are inferred from auto-repeat with timeouts.
    Emulated,
}

impl InputMode {
    /// A short name for the status line.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            InputMode::Kitty => "kitty keys",
            InputMode::Emulated => "key-repeat",
        }
    }
}

/// Kitty mode: a key with no event for this long is let go (tmux and friends drop releases).
pub const KITTY_STALE: Duration = Duration::from_millis(900);

/// Things the TUI itself does (not the game).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UiCommand {
    Quit,
    /// Esc: closes the help if open, else quits.
    Back,
    ToggleMinimap,
    ToggleDebug,
    ToggleHelp,
}

/// What one key means.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Binding {
    Hold(Action),
    /// Held action plus a command on every press/repeat (arrows: turn, or move the column when paused).
    HoldAnd(Action, Command),
    Game(Command),
    /// Toggles fire on the first press only, not on repeats.
    Toggle(Command),
    Ui(UiCommand),
}

fn binding(key: &KeyEvent) -> Option<Binding> {
    use Action::*;
    use Binding::*;
    let shift = key.modifiers.contains(KeyModifiers::SHIFT);
    let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
    let fast = if shift { 10 } else { 1 };
    Some(match key.code {
        KeyCode::Char('c' | 'C') if ctrl => Ui(UiCommand::Quit),
        _ if ctrl => return None,
        KeyCode::Up => Hold(Forward),
        KeyCode::Down => Hold(Back),
        KeyCode::Left => HoldAnd(TurnLeft, Command::MoveColumn(-fast)),
        KeyCode::Right => HoldAnd(TurnRight, Command::MoveColumn(fast)),
        KeyCode::Esc => Ui(UiCommand::Back),
        KeyCode::F(1) => Ui(UiCommand::ToggleHelp),
        KeyCode::Enter => Game(Command::RunToHit),
        KeyCode::PageUp => Hold(LookUp),
        KeyCode::PageDown => Hold(LookDown),
        KeyCode::Char(c) => match c {
            'w' | 'W' => Hold(Forward),
            's' | 'S' => Hold(Back),
            'a' | 'A' => Hold(TurnLeft),
            'd' | 'D' => Hold(TurnRight),
            'z' | 'Z' | ',' | '<' => Hold(StrafeLeft),
            'x' | 'X' | '.' | '>' => Hold(StrafeRight),
            '[' if !shift => Game(Command::MoveColumn(-1)),
            ']' if !shift => Game(Command::MoveColumn(1)),
            '{' | '[' => Game(Command::MoveColumn(-10)),
            '}' | ']' => Game(Command::MoveColumn(10)),
            'n' | 'N' => Game(Command::StepDda),
            'e' | 'E' | 'f' | 'F' => Toggle(Command::UseDoor),
            'j' | 'J' => Toggle(Command::Jump),
            'c' | 'C' => Hold(Crouch),
            'r' | 'R' => Hold(LookUp),
            'v' | 'V' => Hold(LookDown),
            'l' | 'L' => Toggle(Command::ToggleNight),
            'g' | 'G' => Game(Command::RunToHit),
            ' ' | 'p' | 'P' => Toggle(Command::TogglePause),
            'q' | 'Q' => Ui(UiCommand::Quit),
            'm' | 'M' => Ui(UiCommand::ToggleMinimap),
            'i' | 'I' => Ui(UiCommand::ToggleDebug),
            '?' | 'h' | 'H' => Ui(UiCommand::ToggleHelp),
            '/' if shift => Ui(UiCommand::ToggleHelp),
            _ => return None,
        },
        _ => return None,
    })
}

/// A key being held: which action, and (emulated mode, or as a safety net) until when.
#[derive(Debug, Clone, Copy)]
struct HeldKey {
    code: KeyCode,
    action: Action,
    until: Instant,
    /// Presses seen since the key went down (emulated mode), to learn the repeat timing.
    presses: u32,
    last: Instant,
    first_gap: Option<Duration>,
}

/// Collects events between frames and hands them to the game as one [`Input`].
#[derive(Debug)]
pub struct Controls {
    mode: InputMode,
    held: Vec<HeldKey>,
    commands: Vec<Command>,
    ui: Vec<UiCommand>,
    drag_column: Option<u16>,
    /// Radians turned per terminal column of mouse drag.
    turn_per_column: f64,
    repeat: RepeatTiming,
}

impl Controls {
    /// Controls for an input mode found by the start-up probe.
    #[must_use]
    pub fn new(mode: InputMode) -> Self {
        Self {
            mode,
            held: Vec::new(),
            commands: Vec::new(),
            ui: Vec::new(),
            drag_column: None,
            turn_per_column: 0.02,
            repeat: RepeatTiming::default(),
        }
    }

    /// The input mode in use.
    #[must_use]
    pub fn mode(&self) -> InputMode {
        self.mode
    }

    /// Sets mouse-drag sensitivity (the app uses FOV / view width: a drag across the view
    /// turns by one field of view).
    pub fn set_turn_per_column(&mut self, radians: f64) {
        if radians.is_finite() {
            self.turn_per_column = radians;
        }
    }

    /// Takes one terminal event received at `now`.
    pub fn handle(&mut self, event: &Event, now: Instant) {
        match event {
            Event::Key(key) => self.key(key, now),
            Event::Mouse(m) => self.mouse(m),
            Event::FocusLost => self.held.clear(),
            _ => {}
        }
    }

    fn key(&mut self, key: &KeyEvent, now: Instant) {
        let Some(b) = binding(key) else { return };
        // Shift may change between press and release ('W' then 'w'): compare letters caseless.
        let code = match key.code {
            KeyCode::Char(c) => KeyCode::Char(c.to_ascii_lowercase()),
            other => other,
        };
        if key.kind == KeyEventKind::Release {
            self.held.retain(|h| h.code != code);
            return;
        }
        let repeat = key.kind == KeyEventKind::Repeat;
        match b {
            Binding::Hold(a) => self.hold(code, a, now),
            Binding::HoldAnd(a, c) => {
                self.hold(code, a, now);
                self.commands.push(c);
            }
            Binding::Game(c) => self.commands.push(c),
            Binding::Toggle(c) if !repeat => self.commands.push(c),
            Binding::Ui(u) if !repeat => self.ui.push(u),
            Binding::Toggle(_) | Binding::Ui(_) => {}
        }
    }

    fn hold(&mut self, code: KeyCode, action: Action, now: Instant) {
        if let Some(h) = self.held.iter_mut().find(|h| h.code == code) {
            let gap = now.saturating_duration_since(h.last);
            h.presses += 1;
            h.last = now;
            match (h.presses, h.first_gap) {
                (2, _) => h.first_gap = Some(gap),
                (3, Some(delay)) => self.repeat.observe(delay, gap),
                _ => {}
            }
            h.until = now
                + match self.mode {
                    InputMode::Kitty => KITTY_STALE,
                    InputMode::Emulated => self.repeat.repeat_hold(),
                };
            return;
        }
        // Emulated mode never sees releases, so pressing the opposite key lets go.
        if let Some(opposite) = opposite(action) {
            self.held.retain(|h| h.action != opposite);
        }
        let hold = match self.mode {
            InputMode::Kitty => KITTY_STALE,
            InputMode::Emulated => self.repeat.first_hold(),
        };
        self.held.push(HeldKey {
            code,
            action,
            until: now + hold,
            presses: 1,
            last: now,
            first_gap: None,
        });
    }

    fn mouse(&mut self, m: &MouseEvent) {
        match m.kind {
            MouseEventKind::Down(MouseButton::Left) => self.drag_column = Some(m.column),
            MouseEventKind::Drag(MouseButton::Left) => {
                if let Some(from) = self.drag_column {
                    let moved = f64::from(m.column) - f64::from(from);
                    if moved != 0.0 {
                        self.commands
                            .push(Command::Turn(-moved * self.turn_per_column));
                    }
                }
                self.drag_column = Some(m.column);
            }
            MouseEventKind::Up(_) => self.drag_column = None,
            _ => {}
        }
    }

    /// The game input for the step at `now`: keys still held, and the commands since last time.
    pub fn take_input(&mut self, now: Instant) -> Input {
        self.held.retain(|h| h.until > now);
        Input {
            held: self.held.iter().map(|h| h.action).collect::<Held>(),
            commands: std::mem::take(&mut self.commands),
        }
    }

    /// The UI commands since last time.
    pub fn take_ui(&mut self) -> Vec<UiCommand> {
        std::mem::take(&mut self.ui)
    }
}

fn opposite(a: Action) -> Option<Action> {
    Some(match a {
        Action::Forward => Action::Back,
        Action::Back => Action::Forward,
        Action::TurnLeft => Action::TurnRight,
        Action::TurnRight => Action::TurnLeft,
        Action::StrafeLeft => Action::StrafeRight,
        Action::StrafeRight => Action::StrafeLeft,
        Action::LookUp => Action::LookDown,
        Action::LookDown => Action::LookUp,
        Action::Crouch => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crossterm::event::KeyEventState;

    fn key(code: KeyCode, kind: KeyEventKind) -> Event {
        Event::Key(KeyEvent {
            code,
            modifiers: KeyModifiers::NONE,
            kind,
            state: KeyEventState::NONE,
        })
    }

    fn press(c: char) -> Event {
        key(KeyCode::Char(c), KeyEventKind::Press)
    }

    fn ms(t0: Instant, n: u64) -> Instant {
        t0 + Duration::from_millis(n)
    }

    #[test]
    fn emulated_hold_bridges_the_repeat_delay_then_expires() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Emulated);
        c.handle(&press('w'), t0);
        assert!(c.take_input(ms(t0, 400)).held.contains(Action::Forward));
        // Auto-repeat starts at 500 ms and runs every 33 ms.
        for t in (500..900).step_by(33) {
            c.handle(&press('w'), ms(t0, t));
            assert!(c.take_input(ms(t0, t + 20)).held.contains(Action::Forward));
        }
        // The last repeat was at 896 ms; shortly after it stops (a few intervals), it is let go.
        assert!(c.take_input(ms(t0, 960)).held.contains(Action::Forward));
        assert!(c.take_input(ms(t0, 1100)).held.is_empty());
    }

    #[test]
    fn emulated_learns_a_short_repeat_delay_so_taps_stop_sooner() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Emulated);
        // A held key on a fast keyboard: 250 ms delay, then every 30 ms.
        for t in [0, 250, 280, 310] {
            c.handle(&press('w'), ms(t0, t));
        }
        assert!(c.take_input(ms(t0, 400)).held.is_empty());
        // Now a single tap is held only about as long as that delay.
        c.handle(&press('w'), ms(t0, 1000));
        assert!(c.take_input(ms(t0, 1290)).held.contains(Action::Forward));
        assert!(c.take_input(ms(t0, 1320)).held.is_empty());
    }

    #[test]
    fn emulated_opposite_key_lets_go_of_the_other() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Emulated);
        c.handle(&press('w'), t0);
        c.handle(&press('s'), ms(t0, 50));
        let held = c.take_input(ms(t0, 60)).held;
        assert!(held.contains(Action::Back) && !held.contains(Action::Forward));
    }

    #[test]
    fn kitty_holds_until_release_with_a_safety_net() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Kitty);
        c.handle(&press('a'), t0);
        c.handle(&key(KeyCode::Char('a'), KeyEventKind::Repeat), ms(t0, 600));
        assert!(c.take_input(ms(t0, 1400)).held.contains(Action::TurnLeft));
        c.handle(
            &key(KeyCode::Char('a'), KeyEventKind::Release),
            ms(t0, 1450),
        );
        assert!(c.take_input(ms(t0, 1451)).held.is_empty());
        // A lost release (tmux) still ends the hold eventually.
        c.handle(&press('d'), ms(t0, 2000));
        assert!(c.take_input(ms(t0, 2000) + KITTY_STALE).held.is_empty());
    }

    #[test]
    fn arrows_turn_and_move_the_debug_column_toggles_ignore_repeats() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Kitty);
        c.handle(&key(KeyCode::Left, KeyEventKind::Press), t0);
        c.handle(&key(KeyCode::Char(' '), KeyEventKind::Press), t0);
        c.handle(&key(KeyCode::Char(' '), KeyEventKind::Repeat), t0);
        c.handle(&key(KeyCode::Char('q'), KeyEventKind::Repeat), t0);
        let input = c.take_input(t0);
        assert!(input.held.contains(Action::TurnLeft));
        assert_eq!(
            input.commands,
            vec![Command::MoveColumn(-1), Command::TogglePause]
        );
        assert!(c.take_ui().is_empty());
        assert!(c.take_input(t0).commands.is_empty());
        c.handle(&press('q'), t0);
        assert_eq!(c.take_ui(), vec![UiCommand::Quit]);
    }

    #[test]
    fn ctrl_c_quits_and_focus_loss_releases_everything() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Emulated);
        c.handle(&press('w'), t0);
        c.handle(&Event::FocusLost, t0);
        assert!(c.take_input(t0).held.is_empty());
        c.handle(
            &Event::Key(KeyEvent::new(KeyCode::Char('c'), KeyModifiers::CONTROL)),
            t0,
        );
        assert_eq!(c.take_ui(), vec![UiCommand::Quit]);
    }

    #[test]
    fn dragging_right_turns_right() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Emulated);
        c.set_turn_per_column(0.1);
        let m = |kind, column| {
            Event::Mouse(MouseEvent {
                kind,
                column,
                row: 3,
                modifiers: KeyModifiers::NONE,
            })
        };
        c.handle(&m(MouseEventKind::Down(MouseButton::Left), 10), t0);
        c.handle(&m(MouseEventKind::Drag(MouseButton::Left), 13), t0);
        c.handle(&m(MouseEventKind::Up(MouseButton::Left), 13), t0);
        c.handle(&m(MouseEventKind::Drag(MouseButton::Left), 20), t0);
        let cmds = c.take_input(t0).commands;
        assert_eq!(cmds.len(), 1);
        let Command::Turn(r) = cmds[0] else { panic!() };
        assert!((r + 0.3).abs() < 1e-12);
    }
}
