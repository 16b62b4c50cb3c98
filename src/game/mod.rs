//! The game's state and its one way to change: [`step`]`(state, input, dt)`.
//!
//! No terminal, no clock, no I/O: the TUI, replays (fixed `dt`) and an SSH server all drive
//! the same function, so a recorded input sequence always gives the same poses.

pub(crate) mod body;
pub(crate) mod collision;
pub(crate) mod creature;
pub(crate) mod debugger;
pub(crate) mod footing;
pub(crate) mod input;
pub(crate) mod level;
pub mod multi;
pub mod pose;
pub(crate) mod projectile;
#[cfg(test)]
mod random_grid_props;
pub(crate) mod rng;
pub(crate) mod score;
pub(crate) mod sight;
#[cfg(test)]
mod sight_heights_oracle;

use std::sync::Arc;

use crate::camera::Camera;
use crate::render::cast::{trace_column_doors, DdaTrace};
use crate::render::view::{View, MAX_PITCH_DEG, STANDING_EYE};
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::{SolidDisc, World};

// The body's sizes are rules a level designer (and a test) needs: how close to a wall a
// player or creature comes, the head room under a ceiling, how long a step up eases.
pub use body::{Body, HEAD_ROOM};
pub use collision::PLAYER_RADIUS;
pub use creature::CREATURE_RADIUS;
pub use debugger::{Cursor, Debugger};
pub use footing::{Footing, STEP_EASE};
pub use input::{
    tap_seconds, Action, Command, Held, Input, Speeds, TAP_LOOK_DEG, TAP_TURN_DEG, TAP_WALK_CELLS,
};
pub use level::{Event, Level, Player};
pub use score::Score;

/// Walking speed in cells per second.
pub const MOVE_SPEED: f64 = 3.0;

/// Turning speed in radians per second (about 150°/s).
pub const TURN_SPEED: f64 = 2.6;

/// Looking up or down, in degrees per second.
pub const LOOK_SPEED: f64 = 60.0;

/// Eye height while crouching (walls are 1 high).
pub const CROUCH_EYE: f64 = 0.3;

/// How fast the eye moves toward the crouching or standing height, in wall heights per second.
pub const CROUCH_SPEED: f64 = 2.0;

/// Upward speed at take-off, in wall heights per second: the uncut arc would peak at 0.38, so
/// the feet hang at [`JUMP_RISE`] for about 0.17 s (half a cell of walking) before falling.
pub const JUMP_SPEED: f64 = 2.6;

/// Gravity, in wall heights per second squared.
pub const GRAVITY: f64 = 9.0;

/// Highest a jump lifts the feet, in wall heights: the arc is cut flat there, so at any frame rate a jump climbs a ledge of exactly
/// [`body::STEP_UP`] + `JUMP_RISE` = 0.5 and no higher.
pub const JUMP_RISE: f64 = 0.25;

/// Longest frame time one step honours, so a stall (suspend, slow terminal) is not a jump.
pub const MAX_DT: f64 = 0.25;

/// A tag shot a player asked for: from their eye (position and height), along their view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shot {
    /// The eye's position on the map plane.
    pub from: Vec2,
    /// The eye's height in the world.
    pub z: f64,
    /// The view direction.
    pub dir: Vec2,
}

/// Everything that changes while playing, and the shared world it plays in.
#[derive(Debug, Clone)]
pub struct GameState {
    /// The world played in (shared, never changed by play).
    pub world: Arc<World>,
    /// The player's eye.
    pub camera: Camera,
    /// The ray debugger's state.
    pub debugger: Debugger,
    /// Columns of the 3D view, so the debugged column can be clamped and stepped.
    pub view_width: usize,
    /// How far each door is open.
    pub doors: DoorState,
    /// Pitch and eye height.
    pub view: View,
    /// Eye height without the jump (standing or crouching), and the jump's height (above the
    /// floor of the player's cell) and speed.
    pub base_eye: f64,
    /// The jump: (height above the base eye, vertical speed).
    pub jump: (f64, f64),
    /// The floor of the player's cell, and the eye's eased way onto it after a step.
    pub footing: Footing,
    /// Night mode (dark, lit near the player).
    pub night: bool,
    /// Walking and turning speeds.
    pub speeds: Speeds,
    /// Game time in seconds (animations); advances with the steps, paused with the world.
    pub time: f64,
    /// The level in play: items, creatures, shots, the exit (advanced by [`step`] only).
    pub level: Level,
    /// This player's points, keys and treasures.
    pub score: Score,
    /// What happened to this player in the last step (pickups, locked doors, catches…).
    pub events: Vec<Event>,
    /// The latest event's message and the game time it happened at (the message line).
    pub message: Option<Message>,
    /// Tag shots asked for in the last [`step_shared`]: the shared world fires them in its
    /// own [`Level`] (a local [`step`] fires at once).
    pub shots: Vec<Shot>,
    solids: Vec<SolidDisc>,
}

/// A line for the player, with when it was said (so the HUD can let it fade).
#[derive(Debug, Clone, PartialEq)]
pub struct Message {
    /// What to show ("You found the red key").
    pub text: String,
    /// Game time ([`GameState::time`]) it was said at.
    pub at: f64,
}

impl GameState {
    /// Starts at `camera` (moved off any wall it overlaps) with the debugger on the centre ray,
    /// standing exactly on its cell's floor, or crouching where the ceiling is too low to stand;
    /// the level's creatures use seed 0.
    #[must_use]
    pub fn new(world: Arc<World>, camera: Camera, view_width: usize) -> Self {
        Self::with_seed(world, camera, view_width, 0)
    }

    /// [`GameState::new`] with the level's creatures driven by `seed` (a replay stores it).
    #[must_use]
    pub fn with_seed(world: Arc<World>, mut camera: Camera, view_width: usize, seed: u64) -> Self {
        let map = &world.map;
        camera.pos = collision::settle(map, camera.pos, collision::PLAYER_RADIUS);
        let (i, j) = collision::centre_cell(camera.pos);
        let floor = map.floor_height(i, j);
        let standing = Body {
            feet: floor,
            eye: STANDING_EYE,
        };
        let base_eye = if collision::fits_here(map, camera.pos, collision::PLAYER_RADIUS, standing)
        {
            STANDING_EYE
        } else {
            CROUCH_EYE
        };
        let doors = DoorState::new(map);
        let solids = world.solid_discs();
        let level = Level::new(map, seed);
        let message = level::start_message(map).map(|text| Message { text, at: 0.0 });
        Self {
            world,
            camera,
            debugger: Debugger::default(),
            view_width,
            doors,
            view: View::new(0.0, base_eye).on_ground(floor),
            base_eye,
            jump: (0.0, 0.0),
            footing: Footing::on(floor),
            night: false,
            speeds: Speeds::default(),
            time: 0.0,
            level,
            score: Score::default(),
            events: Vec::new(),
            message,
            shots: Vec::new(),
            solids,
        }
    }

    /// The player's body now: feet on the cell's floor plus the jump, eye without the jump.
    #[must_use]
    pub fn body(&self) -> Body {
        Body {
            feet: self.footing.floor + self.jump.0,
            eye: self.base_eye,
        }
    }

    /// What stops the player now: the grid, the doors as they are, solid sprites, and cells
    /// too high to step onto or too low to fit under.
    #[must_use]
    pub fn obstacles(&self) -> collision::Obstacles<'_> {
        collision::Obstacles {
            map: &self.world.map,
            doors: Some(&self.doors),
            discs: &self.solids,
            body: Some(self.body()),
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
            trace_column_doors(
                &self.world.map,
                &self.doors,
                &self.camera,
                self.debug_column(),
                self.view_width,
            )
        })
    }
}

/// Advances the game by `dt` seconds: commands first, then movement (unless paused).
pub fn step(state: &mut GameState, input: &Input, dt: f64) {
    advance(state, input, dt, true, &[]);
}

/// [`step`] for one of several players in a shared world (`halfcast serve`): the caller owns
/// the clock and slides the doors once per tick, and `bodies` (the other players) block too.
pub fn step_shared(state: &mut GameState, input: &Input, dt: f64, bodies: &[SolidDisc]) {
    advance(state, input, dt, false, bodies);
}

fn advance(state: &mut GameState, input: &Input, dt: f64, owns_world: bool, bodies: &[SolidDisc]) {
    let dt = if dt.is_finite() {
        dt.clamp(0.0, MAX_DT)
    } else {
        0.0
    };
    state.events.clear();
    state.shots.clear();
    let mut turn = 0.0;
    // Seconds of "as if held" per action from taps (Command::Nudge), in Action::ALL order.
    let mut nudged = [0.0f64; 9];
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
            Command::RunToHit if d.paused => {
                d.cursor = Cursor::AtHit;
                d.scroll = 0;
            }
            Command::ScrollPane(by) if d.paused => {
                let total = state.debug_trace().map_or(0, |t| t.steps.len());
                state.debugger.scroll_by(by, total);
            }
            Command::Turn(radians) if !d.paused && radians.is_finite() => turn += radians,
            Command::UseDoor if !d.paused => use_door(state),
            Command::Fire if !d.paused => {
                let (cam, eye) = (&state.camera, state.view.eye());
                if owns_world {
                    state.level.fire(0, cam.pos, eye, cam.dir);
                } else {
                    state.shots.push(Shot {
                        from: cam.pos,
                        z: eye,
                        dir: cam.dir,
                    });
                }
            }
            Command::Jump if !d.paused && state.jump == (0.0, 0.0) => state.jump.1 = JUMP_SPEED,
            Command::ToggleNight => state.night = !state.night,
            Command::Nudge(a, secs) if !d.paused && secs.is_finite() => {
                nudged[a as usize] += secs.clamp(0.0, MAX_DT);
            }
            Command::CentrePitch if !d.paused => state.view.pitch_deg = 0.0,
            _ => {}
        }
    }
    if state.debugger.paused {
        return;
    }
    if owns_world {
        state.time += dt;
        state.doors.update(dt);
    }
    let held = input.held;
    let nudge = |plus: Action, minus: Action| nudged[plus as usize] - nudged[minus as usize];
    let look = nudge(Action::LookUp, Action::LookDown);
    vertical(state, held, dt, look);
    let speeds = state.speeds;
    turn += (held.axis(Action::TurnLeft, Action::TurnRight) * dt
        + nudge(Action::TurnLeft, Action::TurnRight))
        * speeds.turn_radians;
    if turn != 0.0 {
        state.camera.rotate(turn);
    }
    let forward = held.axis(Action::Forward, Action::Back);
    let right = held.axis(Action::StrafeRight, Action::StrafeLeft);
    let cam = &state.camera;
    let mut wish = cam.dir * forward + cam.dir.right_normal() * right;
    let len = wish.length();
    if len > 0.0 {
        wish = wish * (speeds.move_cells * dt / len);
    }
    wish = wish
        + (cam.dir * nudge(Action::Forward, Action::Back)
            + cam.dir.right_normal() * nudge(Action::StrafeRight, Action::StrafeLeft))
            * speeds.move_cells;
    if wish.length() > 0.0 {
        let mut discs = Vec::new();
        let mut obstacles = state.obstacles();
        if !bodies.is_empty() {
            discs.extend_from_slice(&state.solids);
            discs.extend_from_slice(bodies);
            obstacles.discs = &discs;
        }
        state.camera.pos =
            collision::slide(&obstacles, state.camera.pos, wish, collision::PLAYER_RADIUS);
    }
    follow_floor(state);
    state.footing.advance(dt);
    state.view = View::new(state.view.pitch_deg, state.base_eye + state.jump.0)
        .on_ground(state.footing.shown());
    if owns_world {
        let mut players = [Player {
            pos: state.camera.pos,
            eye: state.view.eye(),
            score: &mut state.score,
        }];
        let events = state
            .level
            .tick(&state.world.map, &state.doors, &mut players, dt);
        state.events.extend(events);
    }
    if let Some(last) = state.events.last() {
        state.message = Some(Message {
            text: last.message(),
            at: state.time,
        });
    }
}

/// Opens or closes the door ahead, unless it is shut, locked and this player lacks its key
/// (then a [`Event::Locked`] is recorded instead and the door stays shut), or a creature
/// stands in its doorway (a door does not shut on anyone).
fn use_door(state: &mut GameState) {
    let (map, cam) = (&state.world.map, &state.camera);
    if let Some(cell) = crate::world::door::door_ahead(map, cam.pos, cam.dir) {
        let shut = state.doors.open_amount(cell) == 0.0;
        if shut && state.level.may_open(cell, &state.score).is_err() {
            let key = state.level.lock_of(cell).unwrap_or_default().to_owned();
            state.events.push(Event::Locked { player: 0, key });
            return;
        }
        if !shut && state.level.creature_in(cell) {
            return;
        }
    }
    state.doors.toggle_facing(map, cam.pos, cam.dir);
}

/// After moving: the floor of the player's cell is the one stood on. A jump that reached a
/// higher floor ends on it (its height given back to the eye's easing, so the eye does not
/// dip); on a lower floor the jump goes on above it and the eye eases down.
fn follow_floor(state: &mut GameState) {
    let (i, j) = collision::centre_cell(state.camera.pos);
    let Some(span) = state.world.map.span(i, j) else {
        return;
    };
    let rise = span.floor - state.footing.floor;
    if rise == 0.0 {
        return;
    }
    let (height, speed) = state.jump;
    if rise > 0.0 {
        let left = height - rise;
        if left > 0.0 {
            state.jump = (left, speed);
            state.footing.move_to(span.floor, rise);
        } else {
            state.jump = (0.0, 0.0);
            state.footing.move_to(span.floor, height);
        }
    } else {
        state.footing.move_to(span.floor, 0.0);
    }
}

/// Looking up/down, crouching and jumping: the pitch, the eye above the feet and the jump.
/// Getting up waits until the ceilings over the player leave room for a standing eye; a jump
/// rises at most [`JUMP_RISE`] and never puts the head into a ceiling.
fn vertical(state: &mut GameState, held: Held, dt: f64, nudged_look: f64) {
    let look = (held.axis(Action::LookUp, Action::LookDown) * dt + nudged_look) * LOOK_SPEED;
    state.view.pitch_deg = (state.view.pitch_deg + look).clamp(-MAX_PITCH_DEG, MAX_PITCH_DEG);
    let (map, pos, r) = (&state.world.map, state.camera.pos, collision::PLAYER_RADIUS);
    let standing = Body {
        eye: STANDING_EYE,
        ..state.body()
    };
    let target = if held.contains(Action::Crouch) || !collision::fits_here(map, pos, r, standing) {
        CROUCH_EYE
    } else {
        STANDING_EYE
    };
    let reach = CROUCH_SPEED * dt;
    state.base_eye += (target - state.base_eye).clamp(-reach, reach);
    let (mut height, mut speed) = state.jump;
    if height > 0.0 || speed > 0.0 {
        height += speed * dt;
        speed -= GRAVITY * dt;
        let ceiling = collision::lowest_ceiling(map, pos, r);
        let top = (ceiling - body::HEAD_ROOM - state.base_eye - state.footing.floor).min(JUMP_RISE);
        if height >= top {
            height = top;
            // A head that meets a ceiling falls back at once; at the jump's own top the arc is
            // cut flat but goes on (the feet hang there while it would still rise), which gives
            // a body time to get its centre over a ledge it reached.
            if top < JUMP_RISE {
                speed = speed.min(0.0);
            }
        }
        if height <= 0.0 {
            (height, speed) = (0.0, 0.0);
        }
    }
    state.jump = (height, speed);
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
    fn nudges_move_as_if_held_at_the_set_speeds_and_not_while_paused() {
        let mut s = state();
        s.speeds = Speeds::new(2.0, 100.0).unwrap();
        let (pose, angle) = (s.camera.pos, s.camera.angle_deg());
        let tap = |a| Input {
            held: Held::default(),
            commands: vec![Command::Nudge(a, 0.08)],
        };
        step(&mut s, &tap(Action::TurnLeft), 0.016);
        assert!((s.camera.angle_deg() - angle - 8.0).abs() < 1e-9);
        step(&mut s, &tap(Action::TurnRight), 0.016);
        step(&mut s, &tap(Action::Forward), 0.016);
        assert!(((s.camera.pos - pose).length() - 0.16).abs() < 1e-9);
        step(&mut s, &tap(Action::LookUp), 0.016);
        assert!((s.view.pitch_deg - LOOK_SPEED * 0.08).abs() < 1e-9);
        let centre = Input {
            held: Held::default(),
            commands: vec![Command::CentrePitch],
        };
        step(&mut s, &centre, 0.016);
        assert_eq!(s.view.pitch_deg, 0.0);
        let before = s.camera;
        let paused = Input {
            held: Held::default(),
            commands: vec![
                Command::TogglePause,
                Command::Nudge(Action::TurnLeft, 0.1),
                Command::Nudge(Action::Forward, 0.1),
            ],
        };
        step(&mut s, &paused, 0.016);
        assert_eq!(s.camera, before);
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

    fn at(pos: (f64, f64), angle: f64) -> GameState {
        let world = Arc::new(World::default_world());
        GameState::new(
            world,
            Camera::from_angle(crate::vec2::Vec2::new(pos.0, pos.1), angle, 66.0),
            80,
        )
    }

    fn walk(s: &mut GameState, seconds: f64) {
        for _ in 0..(seconds * 30.0) as usize {
            step(s, &Input::holding(&[Action::Forward]), 1.0 / 30.0);
        }
    }

    #[test]
    fn a_shut_door_blocks_until_used_then_lets_the_player_through() {
        // The default map's door at (11,5), west of the start room's doorway.
        let mut s = at((12.5, 5.5), 180.0);
        walk(&mut s, 1.0);
        assert!(
            s.camera.pos.x >= 12.0 + collision::PLAYER_RADIUS - 1e-9,
            "{:?}",
            s.camera.pos
        );
        let open = Input {
            held: Held::default(),
            commands: vec![Command::UseDoor],
        };
        step(&mut s, &open, 1.0 / 30.0);
        for _ in 0..45 {
            step(&mut s, &Input::default(), 1.0 / 30.0);
        }
        assert!(s.doors.open_amount((11, 5)) >= crate::world::door::PASSABLE_OPEN);
        walk(&mut s, 1.0);
        assert!(s.camera.pos.x < 11.0, "walked through: {:?}", s.camera.pos);
    }

    #[test]
    fn solid_sprites_stop_the_player() {
        // A solid pillar stands at (13.5, 2.5); walk north into it from below.
        let mut s = at((13.5, 4.5), 90.0);
        walk(&mut s, 2.0);
        assert!(s.camera.pos.y > 2.5 + 0.2, "{:?}", s.camera.pos);
        assert!((s.camera.pos.x - 13.5).abs() < 1e-9);
    }

    #[test]
    fn shared_steps_leave_the_clock_and_doors_to_the_caller_and_bodies_block() {
        let mut s = state();
        let ahead = s.camera.pos + s.camera.dir * 1.0;
        let body = SolidDisc {
            centre: ahead,
            radius: collision::PLAYER_RADIUS,
        };
        for _ in 0..60 {
            step_shared(
                &mut s,
                &Input::holding(&[Action::Forward]),
                1.0 / 30.0,
                &[body],
            );
        }
        assert_eq!(s.time, 0.0);
        let gap = (s.camera.pos - ahead).length();
        assert!(
            (2.0 * collision::PLAYER_RADIUS - 1e-9..0.5).contains(&gap),
            "stopped at the other body: {gap}"
        );
    }

    #[test]
    fn jump_rises_and_lands_crouch_lowers_and_look_is_clamped() {
        let mut s = state();
        let jump = Input {
            held: Held::default(),
            commands: vec![Command::Jump],
        };
        step(&mut s, &jump, 1.0 / 30.0);
        let mut peak: f64 = 0.0;
        for _ in 0..60 {
            step(&mut s, &Input::default(), 1.0 / 30.0);
            peak = peak.max(s.view.eye_z);
        }
        assert!(peak > STANDING_EYE + 0.2, "{peak}");
        assert!((s.view.eye_z - STANDING_EYE).abs() < 1e-9);
        for _ in 0..15 {
            step(
                &mut s,
                &Input::holding(&[Action::Crouch, Action::LookUp]),
                1.0 / 30.0,
            );
        }
        assert!((s.view.eye_z - CROUCH_EYE).abs() < 1e-9);
        assert!(
            (s.view.pitch_deg - 30.0).abs() < 1e-6,
            "{}",
            s.view.pitch_deg
        );
        for _ in 0..120 {
            step(&mut s, &Input::holding(&[Action::LookDown]), 1.0 / 30.0);
        }
        assert!((s.view.pitch_deg + MAX_PITCH_DEG).abs() < 1e-9);
    }
}
