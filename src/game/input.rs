//! What the player asks for in one step: actions held down plus one-shot commands.
//!
//! Built by the edge (keyboard, replay file, SSH session) and read by [`super::step`];
//! it knows nothing about keys or terminals.

/// A continuous action: applies for as long as it is held, scaled by the frame time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Action {
    /// Walk forward.
    Forward,
    /// Walk back.
    Back,
    /// Turn left.
    TurnLeft,
    /// Turn right.
    TurnRight,
    /// Strafe left.
    StrafeLeft,
    /// Strafe right.
    StrafeRight,
    /// Tilt the view up (shifts the horizon down).
    LookUp,
    /// Tilt the view down.
    LookDown,
    /// Lower the eye while held.
    Crouch,
}

impl Action {
    /// Every action, for iteration (bit order of [`Held`]).
    pub const ALL: [Action; 9] = [
        Action::Forward,
        Action::Back,
        Action::TurnLeft,
        Action::TurnRight,
        Action::StrafeLeft,
        Action::StrafeRight,
        Action::LookUp,
        Action::LookDown,
        Action::Crouch,
    ];

    fn bit(self) -> u16 {
        1 << (self as u8)
    }
}

/// The set of actions held during a step (a bitset: cheap to copy into replays).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Held(u16);

impl Held {
    /// Whether `a` is held.
    #[must_use]
    pub fn contains(self, a: Action) -> bool {
        self.0 & a.bit() != 0
    }

    /// Marks `a` held.
    pub fn insert(&mut self, a: Action) {
        self.0 |= a.bit();
    }

    /// Marks `a` released.
    pub fn remove(&mut self, a: Action) {
        self.0 &= !a.bit();
    }

    /// Whether nothing is held.
    #[must_use]
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// +1, 0 or −1 from a pair of opposing actions.
    #[must_use]
    pub fn axis(self, plus: Action, minus: Action) -> f64 {
        f64::from(u8::from(self.contains(plus))) - f64::from(u8::from(self.contains(minus)))
    }
}

impl FromIterator<Action> for Held {
    fn from_iter<I: IntoIterator<Item = Action>>(iter: I) -> Self {
        let mut h = Held::default();
        for a in iter {
            h.insert(a);
        }
        h
    }
}

/// A one-shot request, applied once at the start of the step it arrives in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Command {
    /// Freeze or unfreeze the world for the ray debugger.
    TogglePause,
    /// Move the debugged column by this many columns (only while paused).
    MoveColumn(i32),
    /// Advance the debugged ray's DDA by one step (only while paused).
    StepDda,
    /// Show the debugged ray's whole traversal up to its hit (only while paused).
    RunToHit,
    /// Turn by this many radians at once, positive to the left (mouse drag; ignored while paused).
    Turn(f64),
    /// Open or close the door straight ahead, if one is within reach.
    UseDoor,
    /// Jump (only from standing on the floor).
    Jump,
    /// Switch night mode (dark, lit near the player) on or off.
    ToggleNight,
    /// Act as if `Action` were held for this many seconds, at once (a key tap on a terminal
    /// without key-release events; ignored while paused). Crouch is not nudged.
    Nudge(Action, f64),
    /// Level the view: pitch back to 0 (look straight ahead).
    CentrePitch,
    /// Fire a tag shot from the eye along the view (ignored while paused or reloading).
    Fire,
    /// Scroll the ray pane's derivation by this many steps, positive = back toward the start
    /// (only while paused).
    ScrollPane(i32),
}

/// One tap's turn, in degrees: what a key pressed and let go at once moves, on any terminal.
pub const TAP_TURN_DEG: f64 = 8.0;

/// One tap's walk (or strafe), in cells.
pub const TAP_WALK_CELLS: f64 = 0.25;

/// One tap's look up or down, in degrees.
pub const TAP_LOOK_DEG: f64 = 5.0;

/// How long `action` is held, at `speeds`, to move one tap's worth: so a tap is the same angle
/// and distance at any speed. `None` for crouch, which has no step.
#[must_use]
pub fn tap_seconds(action: Action, speeds: Speeds) -> Option<f64> {
    match action {
        Action::Crouch => None,
        Action::TurnLeft | Action::TurnRight => {
            Some(TAP_TURN_DEG.to_radians() / speeds.turn_radians)
        }
        Action::LookUp | Action::LookDown => Some(TAP_LOOK_DEG / super::LOOK_SPEED),
        _ => Some(TAP_WALK_CELLS / speeds.move_cells),
    }
}

/// How fast the player walks and turns; set by `--move-speed`, `--turn-speed` or the config file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Speeds {
    /// Walking (and strafing) speed in cells per second.
    pub move_cells: f64,
    /// Turning speed in radians per second.
    pub turn_radians: f64,
}

impl Default for Speeds {
    fn default() -> Self {
        Self {
            move_cells: super::MOVE_SPEED,
            turn_radians: super::TURN_SPEED,
        }
    }
}

impl Speeds {
    /// Fastest speeds accepted (cells/s, degrees/s): beyond them one frame jumps through walls or spins.
    pub const MAX: (f64, f64) = (50.0, 3600.0);

    /// Speeds from cells per second and degrees per second, or why they are unusable.
    ///
    /// # Errors
    /// A speed that is not a finite number in (0, [`Speeds::MAX`]].
    pub fn new(move_cells: f64, turn_deg: f64) -> Result<Self, String> {
        check_speed("move speed", move_cells, Self::MAX.0, "cells per second")?;
        check_speed("turn speed", turn_deg, Self::MAX.1, "degrees per second")?;
        Ok(Self {
            move_cells,
            turn_radians: turn_deg.to_radians(),
        })
    }

    /// The turning speed in degrees per second.
    #[must_use]
    pub fn turn_deg(&self) -> f64 {
        self.turn_radians.to_degrees()
    }
}

fn check_speed(what: &str, v: f64, max: f64, unit: &str) -> Result<(), String> {
    if v.is_finite() && v > 0.0 && v <= max {
        Ok(())
    } else {
        Err(format!(
            "{what} must be a number above 0 and at most {max} ({unit}), not {v}"
        ))
    }
}

/// Everything one step reads from the outside world.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Input {
    /// Which movement keys are held.
    pub held: Held,
    /// One-shot commands of this step, in order.
    pub commands: Vec<Command>,
}

impl Input {
    /// Input with only `held` actions and no commands (tests, replays).
    #[must_use]
    pub fn holding(actions: &[Action]) -> Self {
        Self {
            held: actions.iter().copied().collect(),
            commands: Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn held_set_inserts_removes_and_gives_axes() {
        let mut h = Held::default();
        assert!(h.is_empty());
        h.insert(Action::Forward);
        h.insert(Action::TurnRight);
        assert!(h.contains(Action::Forward) && !h.contains(Action::Back));
        assert_eq!(h.axis(Action::Forward, Action::Back), 1.0);
        assert_eq!(h.axis(Action::TurnLeft, Action::TurnRight), -1.0);
        h.insert(Action::Back);
        assert_eq!(h.axis(Action::Forward, Action::Back), 0.0);
        h.remove(Action::Forward);
        h.remove(Action::Back);
        h.remove(Action::TurnRight);
        assert!(h.is_empty());
        assert_eq!(Action::ALL.len(), 9);
    }

    #[test]
    fn speeds_are_checked_and_kept_in_radians() {
        let s = Speeds::new(2.0, 90.0).unwrap();
        assert!((s.turn_radians - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!((s.turn_deg() - 90.0).abs() < 1e-9);
        for (m, t) in [
            (0.0, 90.0),
            (-1.0, 90.0),
            (3.0, f64::NAN),
            (51.0, 90.0),
            (3.0, 4000.0),
        ] {
            assert!(Speeds::new(m, t).is_err(), "{m} {t}");
        }
        assert_eq!(
            Speeds::new(0.0, 90.0).unwrap_err(),
            "move speed must be a number above 0 and at most 50 (cells per second), not 0"
        );
    }
}
