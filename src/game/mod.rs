//! The game's state and its one way to change: [`step`]`(state, input, dt)`.
//!
//! No terminal, no clock, no I/O: the TUI, replays (fixed `dt`) and an SSH server all drive
//! the same function, so a recorded input sequence always gives the same poses.

pub mod collision;
pub mod debugger;
pub mod input;

use std::sync::Arc;

use crate::camera::Camera;
use crate::cast::{trace_column, DdaTrace};
use crate::world::World;

pub use debugger::{Cursor, Debugger};
pub use input::{Action, Command, Held, Input};

/// Walking speed in cells per second.
pub const MOVE_SPEED: f64 = 3.0;

/// Turning speed in radians per second (about 150°/s).
pub const TURN_SPEED: f64 = 2.6;

/// Longest frame time one step honours, so a stall (suspend, slow terminal) is not a jump.
pub const MAX_DT: f64 = 0.25;

/// Everything that changes while playing, and the shared world it plays in.
#[derive(Debug, Clone)]
pub struct GameState {
    pub world: Arc<World>,
    pub camera: Camera,
    pub debugger: Debugger,
    /// Columns of the 3D view, so the debugged column can be clamped and stepped.
    pub view_width: usize,
}

impl GameState {
    /// Starts at `camera` (moved off any wall it overlaps) with the debugger on the centre ray.
    #[must_use]
    pub fn new(world: Arc<World>, mut camera: Camera, view_width: usize) -> Self {
        camera.pos = collision::settle(&world.map, camera.pos, collision::PLAYER_RADIUS);
        Self {
            world,
            camera,
            debugger: Debugger::default(),
            view_width,
        }
    }

    /// The column the debugger traces in the current view.
    #[must_use]
    pub fn debug_column(&self) -> usize {
        self.debugger.column_in(self.view_width)
    }

    /// The full DDA trace of the debugged column (the debugger decides how much is shown).
    #[must_use]
    pub fn debug_trace(&self) -> Option<DdaTrace> {
        (self.view_width > 0).then(|| {
            trace_column(
                &self.world.map,
                &self.camera,
                self.debug_column(),
                self.view_width,
            )
        })
    }
}

/// Advances the game by `dt` seconds: commands first, then movement (unless paused).
pub fn step(state: &mut GameState, input: &Input, dt: f64) {
    let dt = if dt.is_finite() {
        dt.clamp(0.0, MAX_DT)
    } else {
        0.0
    };
    let mut turn = 0.0;
    for &command in &input.commands {
        let d = &mut state.debugger;
        match command {
            Command::TogglePause => d.toggle_pause(),
            Command::MoveColumn(by) if d.paused => d.move_column(by, state.view_width),
            Command::StepDda => {
                // Stepping is a breakpoint: it pauses the world if it is running.
                if !d.paused {
                    d.toggle_pause();
                }
                let total = state.debug_trace().map_or(0, |t| t.steps.len());
                state.debugger.step(total);
            }
            Command::RunToHit if d.paused => d.cursor = Cursor::AtHit,
            Command::Turn(radians) if !d.paused && radians.is_finite() => turn += radians,
            _ => {}
        }
    }
    if state.debugger.paused {
        return;
    }
    let held = input.held;
    turn += held.axis(Action::TurnLeft, Action::TurnRight) * TURN_SPEED * dt;
    if turn != 0.0 {
        state.camera.rotate(turn);
    }
    let forward = held.axis(Action::Forward, Action::Back);
    let right = held.axis(Action::StrafeRight, Action::StrafeLeft);
    let cam = &state.camera;
    let mut wish = cam.dir * forward + cam.dir.right_normal() * right;
    let len = wish.length();
    if len > 0.0 {
        wish = wish * (MOVE_SPEED * dt / len);
        state.camera.pos = collision::slide(
            &state.world.map,
            state.camera.pos,
            wish,
            collision::PLAYER_RADIUS,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state() -> GameState {
        let world = Arc::new(World::default_world());
        let start = world.map.start;
        let cam = Camera::from_angle(start.pos(), start.angle_deg(), 66.0);
        GameState::new(world, cam, 80)
    }

    #[test]
    fn holding_forward_for_one_second_walks_move_speed_cells() {
        let mut s = state();
        let before = s.camera.pos;
        // The default map's start faces north with open floor ahead.
        for _ in 0..10 {
            step(&mut s, &Input::holding(&[Action::Forward]), 0.1);
        }
        let moved = s.camera.pos - before;
        assert!((moved.y + MOVE_SPEED).abs() < 1e-9, "{moved:?}");
        assert!(moved.x.abs() < 1e-9, "{moved:?}");
    }

    #[test]
    fn turning_is_frame_time_based() {
        let mut a = state();
        let mut b = state();
        step(&mut a, &Input::holding(&[Action::TurnLeft]), 0.2);
        for _ in 0..4 {
            step(&mut b, &Input::holding(&[Action::TurnLeft]), 0.05);
        }
        assert!((a.camera.angle_deg() - b.camera.angle_deg()).abs() < 1e-9);
        let expect = 90.0 + (TURN_SPEED * 0.2).to_degrees();
        assert!((a.camera.angle_deg() - expect).abs() < 1e-9);
    }

    #[test]
    fn diagonal_strafe_is_not_faster_than_walking() {
        let mut s = state();
        let before = s.camera.pos;
        step(
            &mut s,
            &Input::holding(&[Action::Forward, Action::StrafeRight]),
            0.1,
        );
        let d = (s.camera.pos - before).length();
        assert!((d - MOVE_SPEED * 0.1).abs() < 1e-9, "{d}");
    }

    #[test]
    fn paused_world_ignores_movement_but_runs_the_debugger() {
        let mut s = state();
        let pose = s.camera;
        let cmds = |c: Vec<Command>| Input {
            held: [Action::Forward, Action::TurnLeft].into_iter().collect(),
            commands: c,
        };
        step(&mut s, &cmds(vec![Command::TogglePause]), 0.1);
        assert!(s.debugger.paused);
        assert_eq!(s.camera, pose);
        step(
            &mut s,
            &cmds(vec![Command::MoveColumn(-3), Command::StepDda]),
            0.1,
        );
        assert_eq!(s.debug_column(), 37);
        assert_eq!(s.debugger.cursor, Cursor::Steps(0));
        step(
            &mut s,
            &cmds(vec![Command::Turn(1.0), Command::RunToHit]),
            0.1,
        );
        assert_eq!(s.debugger.cursor, Cursor::AtHit);
        assert_eq!(s.camera, pose);
        step(&mut s, &cmds(vec![Command::TogglePause]), 0.1);
        assert!(!s.debugger.paused && s.camera != pose);
    }

    #[test]
    fn column_commands_wait_for_a_pause_but_stepping_pauses() {
        let mut s = state();
        let input = Input {
            held: Held::default(),
            commands: vec![Command::MoveColumn(5), Command::RunToHit],
        };
        step(&mut s, &input, 0.016);
        assert_eq!(s.debugger, Debugger::default());
        let input = Input {
            held: Held::default(),
            commands: vec![Command::StepDda],
        };
        step(&mut s, &input, 0.016);
        assert!(s.debugger.paused);
        assert_eq!(s.debugger.cursor, Cursor::Steps(0));
    }

    #[test]
    fn a_stalled_frame_is_capped() {
        let mut s = state();
        let before = s.camera.pos;
        step(&mut s, &Input::holding(&[Action::Forward]), 100.0);
        let d = (s.camera.pos - before).length();
        assert!(d <= MOVE_SPEED * MAX_DT + 1e-9, "{d}");
        let here = s.camera.pos;
        step(&mut s, &Input::holding(&[Action::Forward]), f64::NAN);
        assert_eq!(s.camera.pos, here);
    }
}
