//! Terminal events → game [`Input`] and UI commands, including held-key tracking.
//!
//! With the kitty keyboard protocol a key is held from its press to its release. Without it a
//! terminal only sends presses: a first press is a *tap*, a short fixed step (a
//! [`Command::Nudge`]: about 8° of turn or a quarter cell of walk), and a key only counts as held
//! once its auto-repeat arrives (presses of the same key closer together than a tap can be),
//! until the repeats stop. The clock is passed in (`now`), so all of this is testable without a
//! terminal.

use std::time::{Duration, Instant};

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};

use super::keymap::{Key, KeyAction, KeyMap};
use super::repeat::RepeatTiming;
use crate::game::{Action, Command, Held, Input, Speeds};

/// How key presses and releases reach us; shown in the status line and help.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputMode {
    /// Kitty keyboard protocol: real press, repeat and release events.
    Kitty,
    /// Presses only; holds are inferred from auto-repeat with timeouts.
    Emulated,
    /// Press and release as they happened, without repeats (a browser page, which lets go of
    /// every key when it loses focus): a key is held until its release.
    Released,
}

impl InputMode {
    /// A short name for the status line.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            InputMode::Kitty => "kitty keys",
            InputMode::Emulated => "key-repeat",
            InputMode::Released => "browser keys",
        }
    }

    /// How long a held key with no event stays held (never asked in emulated mode).
    fn stale_after(self) -> Duration {
        match self {
            InputMode::Released => RELEASED_STALE,
            _ => KITTY_STALE,
        }
    }
}

/// Kitty mode: a key with no event for this long is let go (tmux and friends drop releases).
pub const KITTY_STALE: Duration = Duration::from_millis(900);
/// Released mode: the client sends no repeats, so a hold lasts until its release; this only
/// bounds a release that never comes.
pub const RELEASED_STALE: Duration = Duration::from_secs(3600);

pub use crate::game::{TAP_LOOK_DEG, TAP_TURN_DEG, TAP_WALK_CELLS};

/// Things the TUI itself does (not the game); defined with the replay format that records them.
pub use crate::replay::format::UiCommand;

/// What a key event turns into.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Binding {
    Hold(Action),
    Game(Command),
    /// Toggles fire on the first press only, not on repeats.
    Toggle(Command),
    Ui(UiCommand),
}

fn binding(map: &KeyMap, key: &KeyEvent, paused: bool) -> Option<Binding> {
    if key.modifiers.contains(KeyModifiers::CONTROL) {
        return matches!(key.code, KeyCode::Char('c' | 'C'))
            .then_some(Binding::Ui(UiCommand::Quit));
    }
    let shift = key.modifiers.contains(KeyModifiers::SHIFT);
    let fast = if shift { 10 } else { 1 };
    Some(match map.lookup(key)? {
        // Paused, the world does not turn: the turn keys move the debugged column instead.
        KeyAction::Hold(Action::TurnLeft) if paused => Binding::Game(Command::MoveColumn(-fast)),
        KeyAction::Hold(Action::TurnRight) if paused => Binding::Game(Command::MoveColumn(fast)),
        // ... and the walk keys scroll the ray pane's derivation (back = toward the start).
        KeyAction::Hold(Action::Forward) if paused => Binding::Game(Command::ScrollPane(fast)),
        KeyAction::Hold(Action::Back) if paused => Binding::Game(Command::ScrollPane(-fast)),
        KeyAction::Hold(a) => Binding::Hold(a),
        KeyAction::UseDoor => Binding::Toggle(Command::UseDoor),
        KeyAction::Tag => Binding::Toggle(Command::Fire),
        KeyAction::Jump => Binding::Toggle(Command::Jump),
        KeyAction::Night => Binding::Toggle(Command::ToggleNight),
        KeyAction::CentrePitch => Binding::Toggle(Command::CentrePitch),
        KeyAction::Pause => Binding::Toggle(Command::TogglePause),
        KeyAction::StepDda => Binding::Game(Command::StepDda),
        KeyAction::RunToHit => Binding::Game(Command::RunToHit),
        KeyAction::Column(by) => Binding::Game(Command::MoveColumn(by)),
        KeyAction::Minimap => Binding::Ui(UiCommand::ToggleMinimap),
        KeyAction::RayPane => Binding::Ui(UiCommand::ToggleDebug),
        KeyAction::Colours => Binding::Ui(UiCommand::CycleColours),
        KeyAction::Glyphs => Binding::Ui(UiCommand::CycleGlyphs),
        KeyAction::SaveFigure => Binding::Ui(UiCommand::SaveFigure),
        KeyAction::Help => Binding::Ui(UiCommand::ToggleHelp),
        KeyAction::Quit if key.code == KeyCode::Esc => Binding::Ui(UiCommand::Back),
        KeyAction::Quit => Binding::Ui(UiCommand::Quit),
    })
}

/// Presses of one key close together: a run of taps, or an auto-repeat (then it is held).
#[derive(Debug, Clone, Copy)]
struct KeyRun {
    key: Key,
    action: Action,
    /// Held until then (kitty: until the release; emulated: while repeats keep coming).
    until: Option<Instant>,
    /// Presses seen in this run (emulated mode), to learn the repeat timing.
    presses: u32,
    last: Instant,
    first_gap: Option<Duration>,
    /// When the key went down, and whether a step has seen it held (kitty mode: a press and
    /// release between two steps still moves, for exactly as long as the key was down).
    pressed: Instant,
    stepped: bool,
}

/// Collects events between frames and hands them to the game as one [`Input`].
#[derive(Debug)]
pub struct Controls {
    mode: InputMode,
    keymap: KeyMap,
    speeds: Speeds,
    paused: bool,
    runs: Vec<KeyRun>,
    commands: Vec<Command>,
    ui: Vec<UiCommand>,
    drag_column: Option<u16>,
    /// Radians turned per terminal column of mouse drag.
    turn_per_column: f64,
    repeat: RepeatTiming,
}

impl Controls {
    /// Controls for an input mode found by the start-up probe, with the default keys and speeds.
    #[must_use]
    pub fn new(mode: InputMode) -> Self {
        Self {
            mode,
            keymap: KeyMap::default(),
            speeds: Speeds::default(),
            paused: false,
            runs: Vec::new(),
            commands: Vec::new(),
            ui: Vec::new(),
            drag_column: None,
            turn_per_column: 0.02,
            repeat: RepeatTiming::default(),
        }
    }

    /// Uses these key bindings (from the config file).
    pub fn set_keymap(&mut self, keymap: KeyMap) {
        self.keymap = keymap;
    }

    /// The speeds the game moves at, so a tap is the same angle and distance at any speed.
    pub fn set_speeds(&mut self, speeds: Speeds) {
        self.speeds = speeds;
    }

    /// Whether the world is paused: then the turn keys only move the debugged column.
    pub fn set_paused(&mut self, paused: bool) {
        if paused != self.paused {
            self.runs.clear();
        }
        self.paused = paused;
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
            Event::FocusLost => self.runs.clear(),
            _ => {}
        }
    }

    fn key(&mut self, key: &KeyEvent, now: Instant) {
        let Some(b) = binding(&self.keymap, key, self.paused) else {
            return;
        };
        // Shift may change between press and release ('W' then 'w'): keys compare caseless.
        let id = Key::of(key);
        if key.kind == KeyEventKind::Release {
            let quick = self
                .runs
                .iter()
                .find(|r| r.key.code == id.code && !r.stepped && r.until.is_some())
                .map(|r| (r.action, now.saturating_duration_since(r.pressed)));
            if let Some((action, down)) = quick.filter(|(a, _)| *a != Action::Crouch) {
                self.commands
                    .push(Command::Nudge(action, down.as_secs_f64()));
            }
            self.runs.retain(|r| r.key.code != id.code);
            return;
        }
        let repeat = key.kind == KeyEventKind::Repeat;
        match b {
            Binding::Hold(a) => self.hold(id, a, now),
            Binding::Game(c) => self.commands.push(c),
            Binding::Toggle(c) if !repeat => {
                if c == Command::TogglePause {
                    // Nothing held before a pause or resume carries over to the other side.
                    self.runs.clear();
                }
                self.commands.push(c);
            }
            Binding::Ui(u) if !repeat => self.ui.push(u),
            Binding::Toggle(_) | Binding::Ui(_) => {}
        }
    }

    /// A tap's length in seconds of holding `action` at the current speeds.
    fn tap_seconds(&self, action: Action) -> f64 {
        crate::game::tap_seconds(action, self.speeds).unwrap_or(0.0)
    }

    fn hold(&mut self, key: Key, action: Action, now: Instant) {
        let emulated = self.mode == InputMode::Emulated;
        if let Some(i) = self.runs.iter().position(|r| r.key.code == key.code) {
            let r = &mut self.runs[i];
            let gap = now.saturating_duration_since(r.last);
            if !emulated {
                r.until = Some(now + self.mode.stale_after());
                return;
            }
            if gap <= RepeatTiming::MAX_DELAY {
                r.presses += 1;
                r.last = now;
                match (r.presses, r.first_gap) {
                    (2, _) => r.first_gap = Some(gap),
                    (3, Some(delay)) => self.repeat.observe(delay, gap),
                    _ => {}
                }
                let r = &mut self.runs[i];
                let holding = r.until.is_some_and(|u| u > now);
                if holding || self.repeat.is_repeat(gap) {
                    // Auto-repeat: held from now on while the repeats keep coming.
                    r.until = Some(now + self.repeat.repeat_hold());
                } else {
                    self.tap(action, now, i);
                }
                return;
            }
            self.runs.remove(i);
        }
        // Without releases, pressing the opposite key lets go.
        if let Some(opposite) = opposite(action) {
            self.runs.retain(|r| r.action != opposite);
        }
        self.runs.push(KeyRun {
            key,
            action,
            until: (!emulated).then_some(now + self.mode.stale_after()),
            presses: 1,
            last: now,
            first_gap: None,
            pressed: now,
            stepped: false,
        });
        if emulated {
            let i = self.runs.len() - 1;
            self.tap(action, now, i);
        }
    }

    /// One tap of `action` (emulated mode): a fixed step; crouch, which has no step, is held
    /// for as long as a key's repeat delay.
    fn tap(&mut self, action: Action, now: Instant, run: usize) {
        if action == Action::Crouch {
            self.runs[run].until = Some(now + self.repeat.first_hold());
        } else {
            self.runs[run].until = None;
            self.commands
                .push(Command::Nudge(action, self.tap_seconds(action)));
        }
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
        self.runs.retain(|r| {
            r.until.is_some_and(|u| u > now)
                || now.saturating_duration_since(r.last) <= RepeatTiming::MAX_DELAY
        });
        let mut held = Held::default();
        for r in self
            .runs
            .iter_mut()
            .filter(|r| r.until.is_some_and(|u| u > now))
        {
            r.stepped = true;
            held.insert(r.action);
        }
        Input {
            held,
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

    fn nudges(input: &Input) -> Vec<(Action, f64)> {
        input
            .commands
            .iter()
            .filter_map(|c| match *c {
                Command::Nudge(a, s) => Some((a, s)),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn emulated_tap_is_one_short_step_not_a_hold() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Emulated);
        c.handle(&press('d'), t0);
        let input = c.take_input(ms(t0, 16));
        assert!(input.held.is_empty());
        let n = nudges(&input);
        assert_eq!(n.len(), 1);
        let turned = n[0].1 * Speeds::default().turn_radians;
        assert_eq!(n[0].0, Action::TurnRight);
        assert!((turned.to_degrees() - TAP_TURN_DEG).abs() < 1e-9);
        for t in (33..1500).step_by(17) {
            assert!(c.take_input(ms(t0, t)) == Input::default(), "{t} ms");
        }
        // A tap's walk is a quarter cell whatever the speed.
        c.set_speeds(Speeds::new(6.0, 90.0).unwrap());
        c.handle(&press('w'), ms(t0, 2000));
        let n = nudges(&c.take_input(ms(t0, 2001)));
        assert!((n[0].1 * 6.0 - TAP_WALK_CELLS).abs() < 1e-12);
    }

    #[test]
    fn emulated_taps_apart_are_each_one_step() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Emulated);
        let mut steps = 0;
        for i in 0..5 {
            c.handle(&press('d'), ms(t0, i * 600));
            for t in (0..600).step_by(16) {
                let input = c.take_input(ms(t0, i * 600 + t));
                assert!(input.held.is_empty());
                steps += nudges(&input).len();
            }
        }
        assert_eq!(steps, 5);
    }

    #[test]
    fn emulated_hold_moves_once_repeats_arrive_and_stops_soon_after_them() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Emulated);
        c.handle(&press('w'), t0);
        assert_eq!(nudges(&c.take_input(ms(t0, 1))).len(), 1);
        assert!(c.take_input(ms(t0, 400)).held.is_empty());
        // Auto-repeat starts at 500 ms and runs every 33 ms: the first repeat is one more
        // step (it cannot be told from a tap yet), the next ones hold the key.
        c.handle(&press('w'), ms(t0, 500));
        assert_eq!(nudges(&c.take_input(ms(t0, 501))).len(), 1);
        for t in (533..1000).step_by(33) {
            c.handle(&press('w'), ms(t0, t));
            let input = c.take_input(ms(t0, t + 20));
            assert!(input.held.contains(Action::Forward), "{t}");
            assert!(nudges(&input).is_empty());
        }
        // The last repeat was at 995 ms; three of the learned 33 ms intervals later the key
        // is let go.
        assert!(c.take_input(ms(t0, 1080)).held.contains(Action::Forward));
        assert!(c.take_input(ms(t0, 1200)).held.is_empty());
    }

    #[test]
    fn emulated_learns_a_fast_keyboard() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Emulated);
        // A held key on a fast keyboard: 250 ms delay, then every 20 ms.
        for t in [0, 250, 270, 290] {
            c.handle(&press('w'), ms(t0, t));
        }
        assert!(c.take_input(ms(t0, 300)).held.contains(Action::Forward));
        // Let go sooner: three of its intervals (clamped to at least 60 ms).
        assert!(c.take_input(ms(t0, 360)).held.is_empty());
    }

    #[test]
    fn paused_turn_keys_move_the_column_and_resuming_does_not_turn() {
        let t0 = Instant::now();
        for mode in [InputMode::Emulated, InputMode::Kitty] {
            let mut c = Controls::new(mode);
            c.handle(&key(KeyCode::Char(' '), KeyEventKind::Press), t0);
            assert_eq!(c.take_input(t0).commands, vec![Command::TogglePause]);
            c.set_paused(true);
            c.handle(&key(KeyCode::Right, KeyEventKind::Press), ms(t0, 100));
            c.handle(&key(KeyCode::Right, KeyEventKind::Repeat), ms(t0, 130));
            c.handle(&press('a'), ms(t0, 140));
            c.handle(&key(KeyCode::Char(' '), KeyEventKind::Press), ms(t0, 300));
            let input = c.take_input(ms(t0, 310));
            assert!(input.held.is_empty(), "{mode:?}");
            assert_eq!(
                input.commands,
                vec![
                    Command::MoveColumn(1),
                    Command::MoveColumn(1),
                    Command::MoveColumn(-1),
                    Command::TogglePause
                ],
                "{mode:?}"
            );
            c.set_paused(false);
            for t in (320..1500).step_by(16) {
                assert!(c.take_input(ms(t0, t)) == Input::default(), "{mode:?} {t}");
            }
        }
    }

    #[test]
    fn emulated_opposite_key_lets_go_of_the_other() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Emulated);
        for t in [0, 500, 533] {
            c.handle(&press('w'), ms(t0, t));
        }
        assert!(c.take_input(ms(t0, 540)).held.contains(Action::Forward));
        c.handle(&press('s'), ms(t0, 550));
        let input = c.take_input(ms(t0, 560));
        assert!(input.held.is_empty());
        assert_eq!(nudges(&input)[0].0, Action::Back);
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
    fn kitty_press_and_release_between_steps_moves_for_as_long_as_the_key_was_down() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Kitty);
        c.handle(&press('d'), t0);
        c.handle(&key(KeyCode::Char('d'), KeyEventKind::Release), ms(t0, 40));
        let input = c.take_input(ms(t0, 50));
        assert!(input.held.is_empty());
        assert_eq!(nudges(&input), vec![(Action::TurnRight, 0.04)]);
        // Held across a step: the step moved it, the release adds nothing.
        c.handle(&press('w'), ms(t0, 100));
        assert!(c.take_input(ms(t0, 116)).held.contains(Action::Forward));
        c.handle(&key(KeyCode::Char('w'), KeyEventKind::Release), ms(t0, 120));
        assert_eq!(c.take_input(ms(t0, 133)), Input::default());
    }

    #[test]
    fn arrows_turn_toggles_ignore_repeats() {
        let t0 = Instant::now();
        let mut c = Controls::new(InputMode::Kitty);
        c.handle(&key(KeyCode::Left, KeyEventKind::Press), t0);
        c.handle(&key(KeyCode::Char(' '), KeyEventKind::Press), t0);
        c.handle(&key(KeyCode::Char(' '), KeyEventKind::Repeat), t0);
        c.handle(&key(KeyCode::Char('q'), KeyEventKind::Repeat), t0);
        c.handle(&key(KeyCode::Left, KeyEventKind::Press), t0);
        let input = c.take_input(t0);
        assert!(input.held.contains(Action::TurnLeft));
        assert_eq!(input.commands, vec![Command::TogglePause]);
        assert!(c.take_ui().is_empty());
        assert!(c.take_input(t0).commands.is_empty());
        c.handle(&press('q'), t0);
        c.handle(&key(KeyCode::Esc, KeyEventKind::Press), t0);
        assert_eq!(c.take_ui(), vec![UiCommand::Quit, UiCommand::Back]);
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
