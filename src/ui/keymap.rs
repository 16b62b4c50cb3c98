//! Which key does what: the named things a key can do, key names as the config file spells
//! them, and the table from keys to those things (the defaults, or the config file's).

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

use crate::game::Action;

/// Something a key can be bound to; `name` is how the config file's `[keys]` table calls it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyAction {
    /// A movement held while the key is (turn keys move the debugged column while paused).
    Hold(Action),
    UseDoor,
    /// Throw a tag at a creature (the game's one attack; no gore).
    Tag,
    Jump,
    Night,
    CentrePitch,
    Pause,
    StepDda,
    RunToHit,
    /// Move the debugged column by this many columns (paused).
    Column(i32),
    Minimap,
    RayPane,
    /// Cycle the colour level (truecolor → 256 → 16 → mono).
    Colours,
    /// Cycle the view's block characters (half → quadrant → sextant → octant).
    Glyphs,
    /// Write the debugged column's figure (SVG) to a file (local play only).
    SaveFigure,
    Help,
    /// Quit (Esc closes the help first).
    Quit,
}

/// Every bindable thing: its config name, what it does, and its default keys (help order).
pub const ACTIONS: &[(&str, KeyAction, &str, &[&str])] = &[
    (
        "forward",
        KeyAction::Hold(Action::Forward),
        "walk forward",
        &["w", "up"],
    ),
    (
        "back",
        KeyAction::Hold(Action::Back),
        "walk back",
        &["s", "down"],
    ),
    (
        "turn_left",
        KeyAction::Hold(Action::TurnLeft),
        "turn left (paused: column left)",
        &["a", "left"],
    ),
    (
        "turn_right",
        KeyAction::Hold(Action::TurnRight),
        "turn right (paused: column right)",
        &["d", "right"],
    ),
    (
        "strafe_left",
        KeyAction::Hold(Action::StrafeLeft),
        "strafe left",
        &["z", ","],
    ),
    (
        "strafe_right",
        KeyAction::Hold(Action::StrafeRight),
        "strafe right",
        &["x", "."],
    ),
    (
        "look_up",
        KeyAction::Hold(Action::LookUp),
        "look up",
        &["r", "pageup"],
    ),
    (
        "look_down",
        KeyAction::Hold(Action::LookDown),
        "look down",
        &["v", "pagedown"],
    ),
    (
        "centre_pitch",
        KeyAction::CentrePitch,
        "look straight ahead again",
        &["b", "home"],
    ),
    (
        "crouch",
        KeyAction::Hold(Action::Crouch),
        "crouch (hold)",
        &["c"],
    ),
    ("jump", KeyAction::Jump, "jump", &["j"]),
    (
        "use_door",
        KeyAction::UseDoor,
        "open / close the door ahead",
        &["e", "f"],
    ),
    (
        "tag",
        KeyAction::Tag,
        "throw a tag (tags a creature it hits)",
        &["t"],
    ),
    ("night", KeyAction::Night, "night mode on / off", &["l"]),
    (
        "pause",
        KeyAction::Pause,
        "pause / resume the world (ray debugger)",
        &["space", "p"],
    ),
    (
        "column_left",
        KeyAction::Column(-1),
        "debugged column left (paused)",
        &["["],
    ),
    (
        "column_right",
        KeyAction::Column(1),
        "debugged column right (paused)",
        &["]"],
    ),
    (
        "column_left_10",
        KeyAction::Column(-10),
        "... by 10 columns",
        &["{", "shift+left"],
    ),
    (
        "column_right_10",
        KeyAction::Column(10),
        "... by 10 columns",
        &["}", "shift+right"],
    ),
    (
        "step_dda",
        KeyAction::StepDda,
        "single-step the DDA (pauses)",
        &["n"],
    ),
    (
        "run_to_hit",
        KeyAction::RunToHit,
        "run the DDA to its hit",
        &["enter", "g"],
    ),
    (
        "save_figure",
        KeyAction::SaveFigure,
        "write the debugged ray's figure to an SVG file",
        &["y"],
    ),
    (
        "minimap",
        KeyAction::Minimap,
        "show / hide the minimap",
        &["m"],
    ),
    (
        "ray_pane",
        KeyAction::RayPane,
        "show / hide the ray (DDA) pane",
        &["i"],
    ),
    (
        "colours",
        KeyAction::Colours,
        "colour level: truecolor, 256, 16, mono",
        &["o"],
    ),
    (
        "glyphs",
        KeyAction::Glyphs,
        "block characters: half, quadrant, sextant, octant",
        &["u"],
    ),
    ("help", KeyAction::Help, "this help", &["?", "h", "f1"]),
    (
        "quit",
        KeyAction::Quit,
        "quit (esc closes the help first; ctrl+c always quits)",
        &["q", "esc"],
    ),
];

/// One key as the config file names it: a code, and whether shift is part of it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Key {
    pub code: KeyCode,
    pub shift: bool,
}

const NAMED: &[(&str, KeyCode)] = &[
    ("space", KeyCode::Char(' ')),
    ("up", KeyCode::Up),
    ("down", KeyCode::Down),
    ("left", KeyCode::Left),
    ("right", KeyCode::Right),
    ("enter", KeyCode::Enter),
    ("esc", KeyCode::Esc),
    ("tab", KeyCode::Tab),
    ("backspace", KeyCode::Backspace),
    ("pageup", KeyCode::PageUp),
    ("pagedown", KeyCode::PageDown),
    ("home", KeyCode::Home),
    ("end", KeyCode::End),
    ("insert", KeyCode::Insert),
    ("delete", KeyCode::Delete),
];

impl Key {
    /// Parses a key name: one printable ASCII character (`w`, `?`, `[`), a named key (`space`,
    /// `left`, `pageup`, `f1`…`f12`, …), optionally prefixed `shift+`.
    ///
    /// # Errors
    /// The name is not one of those; the message lists what is.
    pub fn parse(name: &str) -> Result<Self, String> {
        let (shift, base) = match name.strip_prefix("shift+") {
            Some(rest) => (true, rest),
            None => (false, name),
        };
        let mut chars = base.chars();
        let code = match (chars.next(), chars.next()) {
            (Some(c), None) if c.is_ascii_graphic() => KeyCode::Char(c.to_ascii_lowercase()),
            _ => {
                let lower = base.to_ascii_lowercase();
                if let Some((_, code)) = NAMED.iter().find(|(n, _)| *n == lower) {
                    *code
                } else if let Some(n) = lower
                    .strip_prefix('f')
                    .and_then(|n| n.parse::<u8>().ok())
                    .filter(|n| (1..=12).contains(n))
                {
                    KeyCode::F(n)
                } else {
                    return Err(format!(
                        "unknown key '{name}' (a single character like \"w\" or \"?\", or one of: {}, f1-f12; \"shift+\" may prefix a named key)",
                        NAMED.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
                    ));
                }
            }
        };
        if shift && matches!(code, KeyCode::Char(_)) {
            return Err(format!(
                "'{name}': shift+ applies to named keys only (write the shifted character itself, e.g. \"{{\")"
            ));
        }
        Ok(Self { code, shift })
    }

    /// The key a terminal event is (letters caseless; shift counts for named keys only).
    #[must_use]
    pub fn of(event: &KeyEvent) -> Self {
        match event.code {
            KeyCode::Char(c) => Self {
                code: KeyCode::Char(c.to_ascii_lowercase()),
                shift: false,
            },
            code => Self {
                code,
                shift: event.modifiers.contains(KeyModifiers::SHIFT),
            },
        }
    }

    /// The name the config file and the help use.
    #[must_use]
    pub fn name(self) -> String {
        let base = match self.code {
            KeyCode::Char(c) if c != ' ' => c.to_string(),
            KeyCode::F(n) => format!("f{n}"),
            code => NAMED
                .iter()
                .find(|(_, k)| *k == code)
                .map_or("?", |(n, _)| n)
                .to_string(),
        };
        if self.shift {
            format!("shift+{base}")
        } else {
            base
        }
    }
}

/// The table from keys to what they do.
#[derive(Debug, Clone, PartialEq)]
pub struct KeyMap {
    /// (config name, keys), in [`ACTIONS`] order.
    bound: Vec<(&'static str, Vec<Key>)>,
}

impl KeyMap {
    /// The default bindings, built once: screens that list them every frame (the SSH sessions'
    /// help box) would otherwise parse every binding each frame (about 1 % of the server).
    #[must_use]
    pub fn shared_default() -> &'static Self {
        static DEFAULT_KEYS: std::sync::OnceLock<KeyMap> = std::sync::OnceLock::new();
        DEFAULT_KEYS.get_or_init(KeyMap::default)
    }
}

impl Default for KeyMap {
    fn default() -> Self {
        Self {
            bound: ACTIONS
                .iter()
                .map(|(name, _, _, keys)| {
                    let keys = keys.iter().filter_map(|k| Key::parse(k).ok()).collect();
                    (*name, keys)
                })
                .collect(),
        }
    }
}

impl KeyMap {
    /// Rebinds the action called `name` to `keys` (replacing its defaults).
    ///
    /// # Errors
    /// An unknown action name or key name.
    pub fn bind(&mut self, name: &str, keys: &[String]) -> Result<(), String> {
        let Some(slot) = self.bound.iter_mut().find(|(n, _)| *n == name) else {
            return Err(format!(
                "unknown action '{name}' (known: {})",
                ACTIONS.iter().map(|a| a.0).collect::<Vec<_>>().join(", ")
            ));
        };
        slot.1 = keys
            .iter()
            .map(|k| Key::parse(k))
            .collect::<Result<_, _>>()?;
        Ok(())
    }

    /// What `event` does: an exact match first, then the key without shift.
    #[must_use]
    pub fn lookup(&self, event: &KeyEvent) -> Option<KeyAction> {
        let key = Key::of(event);
        let find = |k: Key| {
            self.bound
                .iter()
                .zip(ACTIONS)
                .find(|((_, keys), _)| keys.contains(&k))
                .map(|(_, a)| a.1)
        };
        find(key).or_else(|| {
            key.shift
                .then(|| {
                    find(Key {
                        shift: false,
                        ..key
                    })
                })
                .flatten()
        })
    }

    /// (config name, description, key names) for every action, in help order.
    pub fn entries(&self) -> impl Iterator<Item = (&'static str, &'static str, Vec<String>)> + '_ {
        self.bound
            .iter()
            .zip(ACTIONS)
            .map(|((name, keys), a)| (*name, a.2, keys.iter().map(|k| k.name()).collect()))
    }

    /// A key bound to two actions, if any: (key name, one action, the other).
    #[must_use]
    pub fn conflict(&self) -> Option<(String, &'static str, &'static str)> {
        for (i, (a, keys)) in self.bound.iter().enumerate() {
            for (b, other) in &self.bound[i + 1..] {
                if let Some(k) = keys.iter().find(|k| other.contains(k)) {
                    return Some((k.name(), a, b));
                }
            }
        }
        None
    }

    /// The first key name bound to `name` (for hints), if any.
    #[must_use]
    pub fn first_key(&self, name: &str) -> Option<String> {
        self.bound
            .iter()
            .find(|(n, _)| *n == name)
            .and_then(|(_, k)| k.first())
            .map(|k| k.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ev(code: KeyCode, modifiers: KeyModifiers) -> KeyEvent {
        KeyEvent::new(code, modifiers)
    }

    #[test]
    fn key_names_round_trip_and_bad_ones_say_what_is_allowed() {
        for name in [
            "w",
            "?",
            "[",
            "space",
            "left",
            "shift+right",
            "f1",
            "f12",
            "pageup",
        ] {
            assert_eq!(Key::parse(name).unwrap().name(), name);
        }
        assert_eq!(Key::parse("W").unwrap().name(), "w");
        assert!(Key::parse("f13")
            .unwrap_err()
            .starts_with("unknown key 'f13'"));
        assert!(Key::parse("shift+w").is_err());
        assert!(Key::parse("").is_err());
    }

    #[test]
    fn defaults_cover_every_action_and_shift_falls_back() {
        let m = KeyMap::default();
        assert_eq!(m.entries().count(), ACTIONS.len());
        assert!(m.entries().all(|(_, _, keys)| !keys.is_empty()));
        let w = m.lookup(&ev(KeyCode::Char('W'), KeyModifiers::SHIFT));
        assert_eq!(w, Some(KeyAction::Hold(Action::Forward)));
        let sl = m.lookup(&ev(KeyCode::Left, KeyModifiers::SHIFT));
        assert_eq!(sl, Some(KeyAction::Column(-10)));
        let su = m.lookup(&ev(KeyCode::Up, KeyModifiers::SHIFT));
        assert_eq!(su, Some(KeyAction::Hold(Action::Forward)));
        let q = m.lookup(&ev(KeyCode::Char('?'), KeyModifiers::SHIFT));
        assert_eq!(q, Some(KeyAction::Help));
    }

    #[test]
    fn rebinding_replaces_the_defaults() {
        let mut m = KeyMap::default();
        m.bind("forward", &["k".into()]).unwrap();
        let k = m.lookup(&ev(KeyCode::Char('k'), KeyModifiers::NONE));
        assert_eq!(k, Some(KeyAction::Hold(Action::Forward)));
        assert_eq!(m.lookup(&ev(KeyCode::Char('w'), KeyModifiers::NONE)), None);
        assert!(m
            .bind("fly", &[])
            .unwrap_err()
            .starts_with("unknown action 'fly'"));
        assert_eq!(KeyMap::default().conflict(), None);
        m.bind("jump", &["k".into()]).unwrap();
        assert_eq!(m.conflict(), Some(("k".into(), "forward", "jump")));
    }
}
