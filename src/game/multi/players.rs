//! Everyone in the shared world: one [`GameState`] per player moved by the game's own step, the
//! doors they share, and the snapshot sessions render from.
//!
//! Pure (no clock, no channels): the world task in `world_task.rs` drives it at a fixed tick.

use std::collections::BTreeMap;
use std::sync::Arc;

use crate::camera::{Camera, DEFAULT_FOV_DEG};
use crate::color::Rgb;
use crate::game::collision::{centre_cell, fits_here, overlaps_wall, Obstacles, PLAYER_RADIUS};
use crate::game::Body;
use crate::game::Player as LevelPlayer;
use crate::game::{step_shared, Command, GameState, Held, Input, Level, Message, Score};

use super::rotation::Rotation;
use super::round::{self, Here, Mode, Round, RoundEnd, Scoreboard};
use crate::render::view::STANDING_EYE;
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::{SolidDisc, World};

pub use super::PlayerId;

/// Commands a player may have waiting for the next tick; more are dropped (a flood of keys).
const MAX_COMMANDS: usize = 64;

/// Colours players are told apart by (their names on the minimap), by join order.
const PALETTE: [Rgb; 8] = [
    Rgb::new(255, 64, 64),
    Rgb::new(64, 200, 255),
    Rgb::new(255, 200, 0),
    Rgb::new(160, 96, 255),
    Rgb::new(64, 255, 128),
    Rgb::new(255, 128, 200),
    Rgb::new(255, 140, 40),
    Rgb::new(200, 255, 64),
];

/// What a session may know about one player when it renders.
#[derive(Debug, Clone)]
pub struct PlayerView {
    /// Who this is, stable for the connection.
    pub id: PlayerId,
    /// The name shown over their head and on the scoreboard.
    pub name: String,
    /// Their avatar's colour.
    pub color: Rgb,
    /// The player's game state (its `doors` are stale: the world's are in [`Snapshot::doors`]).
    pub state: GameState,
    /// Whether the player moved in the last tick (its sprite walks).
    pub walking: bool,
}

/// The world as sessions see it after a tick: immutable, shared by `Arc`.
#[derive(Debug, Clone)]
pub struct Snapshot {
    /// Counts published snapshots; a session re-renders only when it changes.
    pub version: u64,
    /// The doors everybody shares.
    pub doors: DoorState,
    /// In join order.
    pub players: Vec<PlayerView>,
    /// The level everybody plays (items left, creatures, shots).
    pub level: Level,
    /// The header's game part: mode, team score or who is "it", the scoreboard.
    pub scoreboard: Scoreboard,
    /// Who is "it" (tag).
    pub it: Option<PlayerId>,
    /// The round's results while they show.
    pub ended: Option<RoundEnd>,
    /// The world this round plays (it changes between rounds when several maps rotate).
    pub world: Option<Arc<World>>,
    /// Which of the served maps that is.
    pub map: usize,
}

impl Default for Snapshot {
    fn default() -> Self {
        Self {
            world: None,
            map: 0,
            version: 0,
            doors: DoorState::none(),
            players: Vec::new(),
            level: Level::default(),
            scoreboard: Scoreboard::default(),
            it: None,
            ended: None,
        }
    }
}

impl Snapshot {
    /// The player with `id`, if still here.
    #[must_use]
    pub fn player(&self, id: PlayerId) -> Option<&PlayerView> {
        self.players.iter().find(|p| p.id == id)
    }
}

#[derive(Debug, Clone)]
struct Player {
    name: String,
    color: Rgb,
    state: GameState,
    /// What this player found and lost this round (coop shows the team's in `state.score`).
    own: Score,
    held: Held,
    commands: Vec<Command>,
    walking: bool,
    /// How long each held key has moved this player, so a quick tap still moves one tap.
    taps: super::taps::Taps,
}

/// How a server's rounds run: their length, the results' pause, the order of the maps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rules {
    /// The game everybody plays.
    pub mode: Mode,
    /// Seeds the creatures' random choices (and the shuffle, when there is one).
    pub seed: u64,
    /// Seconds a round lasts at most (`None`: coop until the exit, tag its 3 minutes).
    pub round_limit: Option<f64>,
    /// Seconds the results show before the next round.
    pub results_seconds: f64,
    /// Plays the maps in a random order (drawn from `seed`) instead of the order given.
    pub shuffle: bool,
}

impl Rules {
    /// `mode` from `seed` with the default clock and the maps in order.
    #[must_use]
    pub fn new(mode: Mode, seed: u64) -> Self {
        Self {
            mode,
            seed,
            round_limit: None,
            results_seconds: round::RESULTS_SECONDS,
            shuffle: false,
        }
    }
}

/// The game state of the shared world: every player, keyed by id, and the doors.
#[derive(Debug, Clone)]
pub struct Players {
    /// The world this round plays: `worlds[rotation.current()]`.
    world: Arc<World>,
    /// Every served map's world, in the order given.
    worlds: Vec<Arc<World>>,
    rotation: Rotation,
    solids: Vec<SolidDisc>,
    players: BTreeMap<PlayerId, Player>,
    doors: DoorState,
    /// The game everybody plays: the level, the mode's rules, the results between rounds.
    round: Round,
    /// World time in seconds: sprite animations, the same for everyone.
    time: f64,
    joined: u64,
    version: u64,
}

impl Players {
    /// Nobody here yet; every door shut; a round of coop.
    #[must_use]
    pub fn new(world: Arc<World>) -> Self {
        Self::with_mode(world, Mode::Coop, 0)
    }

    /// Nobody here yet, playing `mode`; the creatures' random choices start from `seed`.
    #[must_use]
    pub fn with_mode(world: Arc<World>, mode: Mode, seed: u64) -> Self {
        Self::rotating(vec![world], Rules::new(mode, seed))
    }

    /// Nobody here yet; rounds play `worlds` in turn (at least one) by `rules`.
    ///
    /// # Panics
    /// When `worlds` is empty.
    #[must_use]
    pub fn rotating(worlds: Vec<Arc<World>>, rules: Rules) -> Self {
        assert!(!worlds.is_empty(), "a server plays at least one map");
        let rotation = Rotation::new(worlds.len(), rules.shuffle.then_some(rules.seed));
        let world = Arc::clone(&worlds[rotation.current()]);
        let mut round = Round::new(&world.map, rules.mode, rules.seed);
        round.limit = rules.round_limit;
        round.results_seconds = rules.results_seconds;
        Self {
            solids: world.solid_discs(),
            doors: DoorState::new(&world.map),
            round,
            world,
            worlds,
            rotation,
            players: BTreeMap::new(),
            time: 0.0,
            joined: 0,
            version: 0,
        }
    }

    /// The round's results while they show (the round is over).
    #[must_use]
    pub fn ended(&self) -> Option<&RoundEnd> {
        self.round.ended.as_ref()
    }

    /// Which of the served maps this round plays.
    #[must_use]
    pub fn map_index(&self) -> usize {
        self.rotation.current()
    }

    /// Adds a player at a free spawn point, facing the map's start direction (ignored if `id`
    /// is already here). A name someone here already wears gets a number (`ada`, `ada-2`, …).
    pub fn join(&mut self, id: PlayerId, name: &str) {
        if self.players.contains_key(&id) {
            return;
        }
        let taken: Vec<Vec2> = self.players.values().map(|p| p.state.camera.pos).collect();
        let state = self.arrival(self.spawn_point(&taken));
        let color = PALETTE[(self.joined % PALETTE.len() as u64) as usize];
        self.joined += 1;
        let name = self.unique_name(name);
        self.players.insert(
            id,
            Player {
                name,
                color,
                state,
                own: Score::default(),
                held: Held::default(),
                commands: Vec::new(),
                walking: false,
                taps: Default::default(),
            },
        );
    }

    /// `name`, or `name-2`, `name-3`, … : the first nobody connected is using.
    fn unique_name(&self, name: &str) -> String {
        let taken = |n: &str| self.players.values().any(|p| p.name == n);
        if !taken(name) {
            return name.to_string();
        }
        (2..)
            .map(|k| format!("{name}-{k}"))
            .find(|n| !taken(n))
            .expect("some number is free")
    }

    /// Removes a player (no-op if absent).
    pub fn leave(&mut self, id: PlayerId) {
        self.players.remove(&id);
    }

    /// A session's input since its last message: `input.held` replaces what the player holds,
    /// its commands wait for the next tick; `view_width` is the player's view in columns (the
    /// debugger's column range).
    pub fn input(&mut self, id: PlayerId, input: Input, view_width: usize) {
        if let Some(p) = self.players.get_mut(&id) {
            p.held = input.held;
            let room = MAX_COMMANDS.saturating_sub(p.commands.len());
            p.commands.extend(input.commands.into_iter().take(room));
            p.state.view_width = view_width;
        }
    }

    /// [`Players::input`] from a client whose key releases are known (a browser, a kitty-protocol
    /// terminal): a key pressed and let go before a tick saw it enough still moves one tap
    /// (`taps`).
    pub fn input_with_releases(&mut self, id: PlayerId, input: Input, view_width: usize) {
        if let Some(p) = self.players.get_mut(&id) {
            let mut nudges = Vec::new();
            let speeds = p.state.speeds;
            p.taps.changed((p.held, input.held), speeds, &mut nudges);
            let room = MAX_COMMANDS.saturating_sub(p.commands.len());
            p.commands.extend(nudges.into_iter().take(room));
        }
        self.input(id, input, view_width);
    }

    /// Number of players.
    #[must_use]
    pub fn len(&self) -> usize {
        self.players.len()
    }

    /// Whether nobody is here.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.players.is_empty()
    }

    /// Advances the world by `dt` seconds: doors slide once, then each player (in id order)
    /// takes one `game::step_shared` against the others' current places, then the shared level
    /// moves (creatures, shots, pickups, the exit) and the mode's rules run. While a round's
    /// results show, the world waits; then the next round starts with everyone respawned.
    pub fn tick(&mut self, dt: f64) {
        self.time += dt;
        if self.round.ended.is_some() {
            if self.round.wait(dt) {
                self.next_round();
            }
            return;
        }
        self.doors.update(dt);
        if self.players.is_empty() {
            // Nobody to play for: the round's clock and its creatures wait.
            return;
        }
        self.round.elapsed += dt;
        let ids: Vec<PlayerId> = self.players.keys().copied().collect();
        for (index, &id) in ids.iter().enumerate() {
            let bodies: Vec<SolidDisc> = self
                .players
                .iter()
                .filter(|(k, _)| **k != id)
                .map(|(_, p)| SolidDisc {
                    centre: p.state.camera.pos,
                    radius: PLAYER_RADIUS,
                })
                .collect();
            let Some(p) = self.players.get_mut(&id) else {
                continue;
            };
            let input = Input {
                held: p.held,
                commands: std::mem::take(&mut p.commands),
            };
            p.taps.ticked(p.held, dt);
            let before = p.state.camera.pos;
            // The shared doors and level stand in for the player's own while it steps (locks,
            // a creature in a doorway).
            std::mem::swap(&mut p.state.doors, &mut self.doors);
            std::mem::swap(&mut p.state.level, &mut self.round.level);
            step_shared(&mut p.state, &input, dt, &bodies);
            std::mem::swap(&mut p.state.level, &mut self.round.level);
            std::mem::swap(&mut p.state.doors, &mut self.doors);
            // Shots belong to the shared level, credited to this player.
            for shot in p.state.shots.drain(..) {
                self.round.level.fire(index, shot.from, shot.z, shot.dir);
            }
            p.state.time = self.time;
            p.walking = p.state.camera.pos != before;
        }
        self.level_tick(&ids, dt);
    }

    /// The shared level's tick for everyone here, the scores it changed, the messages it has
    /// for each player, and the mode's rules.
    fn level_tick(&mut self, ids: &[PlayerId], dt: f64) {
        let coop = self.round.mode == Mode::Coop;
        let was: Vec<Score> = ids
            .iter()
            .map(|id| {
                if coop {
                    self.round.team.clone()
                } else {
                    self.players[id].own.clone()
                }
            })
            .collect();
        let mut scores = was.clone();
        let events = {
            let mut here: Vec<LevelPlayer> = ids
                .iter()
                .zip(scores.iter_mut())
                .map(|(id, score)| LevelPlayer {
                    pos: self.players[id].state.camera.pos,
                    eye: self.players[id].state.view.eye(),
                    score,
                })
                .collect();
            self.round
                .level
                .tick(&self.world.map, &self.doors, &mut here, dt)
        };
        for ((id, before), after) in ids.iter().zip(&was).zip(&scores) {
            if let Some(p) = self.players.get_mut(id) {
                p.own.points = (p.own.points + after.points - before.points).max(0);
                p.own.found += after.found.saturating_sub(before.found);
                p.own.keys.extend(after.keys.iter().cloned());
            }
        }
        if coop {
            let team_was = self.round.team.clone();
            round::pool(&mut self.round.team, &team_was, &scores);
        }
        for e in &events {
            if let Some(p) = ids.get(e.player()).and_then(|id| self.players.get_mut(id)) {
                p.state.message = Some(Message {
                    text: e.message(),
                    at: self.time,
                });
            }
        }
        let here: Vec<(PlayerId, String, Rgb, Vec2, Score)> = self
            .players
            .iter()
            .map(|(&id, p)| {
                (
                    id,
                    p.name.clone(),
                    p.color,
                    p.state.camera.pos,
                    p.own.clone(),
                )
            })
            .collect();
        let here: Vec<Here> = here
            .iter()
            .map(|(id, name, colour, pos, score)| Here {
                id: *id,
                name,
                colour: *colour,
                pos: *pos,
                score,
            })
            .collect();
        if let Some(it) = self.round.tag_tick(&here, dt) {
            let text = format!("{it} is it!");
            for p in self.players.values_mut() {
                p.state.message = Some(Message {
                    text: text.clone(),
                    at: self.time,
                });
            }
        }
        if self.round.is_over() {
            let by = self
                .round
                .level
                .finished()
                .and_then(|k| ids.get(k))
                .and_then(|id| self.players.get(id))
                .map(|p| p.name.clone());
            self.round.end(&here, by.as_deref());
            if let Some(end) = self.round.ended.as_mut() {
                end.map = self.rotation.current();
                end.next_map = self.worlds[self.rotation.next()].map.name.clone();
            }
        }
        // Each player's HUD: the team's score in coop, their own in tag.
        for p in self.players.values_mut() {
            p.state.score = if coop {
                self.round.team.clone()
            } else {
                p.own.clone()
            };
        }
    }

    /// A new round on the rotation's next map: a fresh level, scores cleared, everyone back at
    /// a spawn point.
    fn next_round(&mut self) {
        self.rotation.advance();
        let world = Arc::clone(&self.worlds[self.rotation.current()]);
        if !Arc::ptr_eq(&world, &self.world) {
            self.solids = world.solid_discs();
            self.world = world;
        }
        self.round.next(&self.world.map);
        self.doors = DoorState::new(&self.world.map);
        let ids: Vec<PlayerId> = self.players.keys().copied().collect();
        let mut taken = Vec::new();
        for id in ids {
            let pos = self.spawn_point(&taken);
            taken.push(pos);
            let mut state = self.arrival(pos);
            if let Some(p) = self.players.get_mut(&id) {
                state.speeds = p.state.speeds;
                state.view_width = p.state.view_width;
                p.state = state;
                p.own = Score::default();
            }
        }
    }

    /// A player's state as they appear at `pos`, facing the map's start direction, at the
    /// world's time. Its own level stays empty: the shared one stands in while it steps, and
    /// an empty one costs nothing to copy into every snapshot.
    fn arrival(&self, pos: Vec2) -> GameState {
        let camera = Camera::from_angle(pos, self.world.map.start.angle_deg(), DEFAULT_FOV_DEG);
        let mut state = GameState::new(Arc::clone(&self.world), camera, 0);
        state.time = self.time;
        state.level = Level::default();
        // The level's start message ("Find the exit…") is said now, on the world's clock.
        if let Some(m) = state.message.as_mut() {
            m.at = self.time;
        }
        state
    }

    /// The players as the round's rules see them.
    fn here(&self) -> Vec<Here<'_>> {
        self.players
            .iter()
            .map(|(&id, p)| Here {
                id,
                name: &p.name,
                colour: p.color,
                pos: p.state.camera.pos,
                score: &p.own,
            })
            .collect()
    }

    /// The current state as sessions see it; bumps the version.
    pub fn snapshot(&mut self) -> Snapshot {
        self.version += 1;
        let here = self.here();
        let scoreboard = self.round.header(&here);
        Snapshot {
            world: Some(Arc::clone(&self.world)),
            map: self.rotation.current(),
            level: self.round.level.clone(),
            scoreboard,
            it: self.round.it,
            ended: self.round.ended.clone(),
            version: self.version,
            doors: self.doors.clone(),
            players: self
                .players
                .iter()
                .map(|(&id, p)| PlayerView {
                    id,
                    name: p.name.clone(),
                    color: p.color,
                    state: p.state.clone(),
                    walking: p.walking,
                })
                .collect(),
        }
    }

    /// Whether a player could stand at `p`: clear of walls, shut doors and solid sprites, under
    /// a ceiling high enough to stand (by the same rule that moves everyone).
    fn free(&self, p: Vec2) -> bool {
        let map = &self.world.map;
        let obstacles = Obstacles {
            map,
            doors: Some(&self.doors),
            discs: &self.solids,
            body: None,
        };
        let (i, j) = centre_cell(p);
        let room = map.span(i, j).is_some_and(|s| {
            let standing = Body {
                feet: s.floor,
                eye: STANDING_EYE,
            };
            fits_here(map, p, PLAYER_RADIUS, standing)
        });
        room && !overlaps_wall(&obstacles, p, PLAYER_RADIUS)
            && self
                .solids
                .iter()
                .all(|d| (p - d.centre).length() >= d.radius + PLAYER_RADIUS)
    }

    /// A free place to appear: the map start if nobody is near it, else the nearest free floor
    /// cell centre (by rings around the start), else the start anyway (players may then walk
    /// apart: moving away from an overlap is always allowed).
    fn spawn_point(&self, taken: &[Vec2]) -> Vec2 {
        let map = &self.world.map;
        let start = map.start.pos();
        let free = |p: Vec2| self.free(p) && taken.iter().all(|&o| (p - o).length() >= 0.9);
        if free(start) {
            return start;
        }
        let (si, sj) = (map.start.cell.0 as i64, map.start.cell.1 as i64);
        let reach = map.width.max(map.height) as i64;
        for ring in 1..=reach {
            for j in (sj - ring)..=(sj + ring) {
                for i in (si - ring)..=(si + ring) {
                    if (i - si).abs() != ring && (j - sj).abs() != ring {
                        continue;
                    }
                    let p = Vec2::new(i as f64 + 0.5, j as f64 + 0.5);
                    if free(p) {
                        return p;
                    }
                }
            }
        }
        start
    }
}

/// A shared snapshot, as handed to sessions.
pub type SharedSnapshot = Arc<Snapshot>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::Action;

    fn players() -> Players {
        Players::new(Arc::new(World::default_world()))
    }

    fn hold(ps: &mut Players, id: PlayerId, actions: &[Action]) {
        ps.input(id, Input::holding(actions), 80);
    }

    #[test]
    fn join_move_leave() {
        let mut ps = players();
        ps.join(1, "ann");
        ps.join(2, "bob");
        let s = ps.snapshot();
        assert_eq!(s.players.len(), 2);
        let (a, b) = (&s.players[0].state.camera, &s.players[1].state.camera);
        assert!((a.pos - b.pos).length() >= 0.9);
        hold(&mut ps, 1, &[Action::TurnLeft]);
        ps.tick(0.1);
        ps.leave(2);
        let s2 = ps.snapshot();
        assert_eq!(s2.players.len(), 1);
        assert!(s2.version > s.version);
        let turned = s2.players[0].state.camera.angle_deg() - a.angle_deg();
        assert!(turned.abs() > 1.0, "{turned}");
        assert!(!s2.players[0].walking, "turning on the spot is not walking");
    }

    #[test]
    fn a_player_joining_late_is_told_the_goal_on_the_worlds_clock() {
        let mut ps = Players::new(Arc::new(World::default_world()));
        ps.join(1, "ann");
        for _ in 0..100 {
            ps.tick(0.1);
        }
        ps.join(2, "bob");
        let s = ps.snapshot();
        let bob = s.player(2).expect("bob");
        let told = bob.state.message.as_ref().expect("a start message");
        assert_eq!(told.text, "Find the exit. 0/12 treasures.");
        // Stamped now on the world's clock (10 s in), not at time 0, so a screen still shows it.
        let age = bob.state.time - told.at;
        assert!(
            (0.0..0.5).contains(&age),
            "{age} s old at {}",
            bob.state.time
        );
    }

    #[test]
    fn an_empty_world_keeps_its_round_waiting() {
        let mut ps = Players::with_mode(Arc::new(World::default_world()), Mode::Tag, 3);
        for _ in 0..400 {
            ps.tick(0.5);
        }
        ps.join(1, "ann");
        let s = ps.snapshot();
        assert!(s.ended.is_none());
        assert!(
            s.scoreboard.summary == "tag: it is nobody, 3:00 left",
            "{}",
            s.scoreboard
        );
    }

    #[test]
    fn rounds_rotate_through_the_maps_and_the_results_name_the_next() {
        let a = Arc::new(World::default_world());
        let mut bw = World::default_world();
        bw.map.name = "b.cub".into();
        let b = Arc::new(bw);
        let mut rules = Rules::new(Mode::Coop, 1);
        rules.round_limit = Some(1.0);
        rules.results_seconds = 0.5;
        let mut ps = Players::rotating(vec![a, b], rules);
        ps.join(1, "ann");
        let mut seen = Vec::new();
        for _ in 0..80 {
            ps.tick(0.1);
            let s = ps.snapshot();
            let name = s.world.as_ref().expect("a world").map.name.clone();
            if seen.last() != Some(&name) {
                seen.push(name);
            }
            if let Some(end) = &s.ended {
                let other = if s.map == 0 { "b.cub" } else { "default.cub" };
                assert_eq!(end.next_map, other);
                assert_eq!(end.map, s.map);
            }
        }
        assert_eq!(seen[..4], ["default.cub", "b.cub", "default.cub", "b.cub"]);
    }

    #[test]
    fn names_are_unique_among_those_connected() {
        let mut ps = players();
        for id in 1..=3 {
            ps.join(id, "ada");
        }
        ps.join(4, "ada-2");
        let names = |ps: &mut Players| -> Vec<String> {
            ps.snapshot().players.into_iter().map(|p| p.name).collect()
        };
        assert_eq!(names(&mut ps), ["ada", "ada-2", "ada-3", "ada-2-2"]);
        // A freed name is given again.
        ps.leave(2);
        ps.join(5, "ada");
        assert_eq!(names(&mut ps), ["ada", "ada-3", "ada-2-2", "ada-2"]);
    }

    #[test]
    fn players_block_each_other_like_solid_sprites() {
        let mut ps = players();
        ps.join(1, "ann");
        ps.join(2, "bob");
        let s = ps.snapshot();
        let (a, b) = (s.players[0].state.camera.pos, s.players[1].state.camera.pos);
        // Turn ann towards bob, then walk into him for two seconds.
        let to = b - a;
        let angle = (-to.y).atan2(to.x).to_degrees();
        let p = ps.players.get_mut(&1).expect("ann");
        p.state.camera = Camera::from_angle(a, angle, DEFAULT_FOV_DEG);
        hold(&mut ps, 1, &[Action::Forward]);
        for _ in 0..60 {
            ps.tick(1.0 / 30.0);
        }
        let s = ps.snapshot();
        let gap = (s.players[0].state.camera.pos - b).length();
        assert!(gap >= 2.0 * PLAYER_RADIUS - 1e-9, "walked into bob: {gap}");
        assert!(gap < 0.9, "ann did walk up to bob: {gap}");
    }

    #[test]
    fn doors_are_shared_one_player_opens_for_everyone() {
        let mut ps = players();
        ps.join(1, "ann");
        ps.join(2, "bob");
        // Put ann in front of the default map's door at (11,5), facing west.
        let p = ps.players.get_mut(&1).expect("ann");
        p.state.camera = Camera::from_angle(Vec2::new(12.5, 5.5), 180.0, DEFAULT_FOV_DEG);
        ps.input(
            1,
            Input {
                held: Held::default(),
                commands: vec![Command::UseDoor],
            },
            80,
        );
        for _ in 0..45 {
            ps.tick(1.0 / 30.0);
        }
        let s = ps.snapshot();
        assert!(s.doors.open_amount((11, 5)) > 0.9);
        // Doors slide once per tick, not once per player.
        let mut half = players();
        half.join(1, "ann");
        half.join(2, "bob");
        half.join(3, "cat");
        let p = half.players.get_mut(&1).expect("ann");
        p.state.camera = Camera::from_angle(Vec2::new(12.5, 5.5), 180.0, DEFAULT_FOV_DEG);
        half.input(
            1,
            Input {
                held: Held::default(),
                commands: vec![Command::UseDoor],
            },
            80,
        );
        for _ in 0..10 {
            half.tick(1.0 / 30.0);
        }
        let open = half.snapshot().doors.open_amount((11, 5));
        assert!((open - 10.0 / 30.0).abs() < 0.05, "{open}");
    }

    #[test]
    fn spawn_points_avoid_taken_places_and_solids() {
        let mut ps = players();
        for id in 0..12 {
            ps.join(id, "x");
        }
        let s = ps.snapshot();
        for (i, a) in s.players.iter().enumerate() {
            assert!(ps.free(a.state.camera.pos));
            for b in &s.players[i + 1..] {
                assert!((a.state.camera.pos - b.state.camera.pos).length() >= 0.9);
            }
        }
    }
}
