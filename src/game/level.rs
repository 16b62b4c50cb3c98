//! A level in play: the items still lying about, creatures, shots in flight and whether someone
//! reached the exit. Shared by every player of a world (one [`Level`] for a whole server), and
//! advanced only by [`Level::tick`], so a seed and the same inputs give the same game.

use std::collections::BTreeMap;

use super::creature::{Creature, Ground};
use super::projectile::{
    Flight, Projectile, RELOAD_SECONDS, SHOT_LIGHT_RADIUS, SHOT_LIGHT_STRENGTH,
};
use super::rng::Rng;
use super::score::Score;
use crate::map::{Blend, ColourKey, Map, SpriteDef, DEFAULT_SOLID_RADIUS};
use crate::render::point_light::PointLight;
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::sprite::Sprite;
use crate::world::{SolidDisc, World};

/// A player's centre this close to an item picks it up, in cells.
pub const PICKUP_RADIUS: f64 = 0.5;

/// A creature's centre this close to a player's catches them, in cells.
pub const CATCH_RADIUS: f64 = 0.45;

/// Points being caught costs (never taking a score below 0).
pub const CATCH_POINTS: i64 = 25;

/// What a player is told as a level starts ("Find the exit. 0/12 treasures."), so a first-time
/// player knows the goal; `None` on a map without game lines.
#[must_use]
pub fn start_message(map: &Map) -> Option<String> {
    let treasures = map.items.iter().filter(|i| i.is_treasure()).count();
    match (map.exits.is_empty(), treasures) {
        (false, 0) => Some("Find the exit.".to_owned()),
        (false, n) => Some(format!("Find the exit. 0/{n} treasures.")),
        (true, 0) => None,
        (true, n) => Some(format!("Find the treasures: 0/{n}.")),
    }
}

/// One player as a tick sees them: where they stand and the score they play for.
#[derive(Debug)]
pub struct Player<'a> {
    /// The player's centre on the map plane.
    pub pos: Vec2,
    /// The height of their eye in the world (what creatures look at on maps with heights).
    pub eye: f64,
    /// Their score (points, keys, treasures found).
    pub score: &'a mut Score,
}

/// Something that happened to a player in a tick (for the message line and the results).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Event {
    /// Picked up a treasure (or a key worth points).
    Picked {
        /// Index of the player in the tick's slice.
        player: usize,
        /// Points it gave.
        points: i64,
    },
    /// Picked up a key.
    KeyFound {
        /// Index of the player.
        player: usize,
        /// The key's name.
        key: String,
    },
    /// Tried a locked door without its key.
    Locked {
        /// Index of the player.
        player: usize,
        /// The key the door needs.
        key: String,
    },
    /// A creature caught the player.
    Caught {
        /// Index of the player.
        player: usize,
        /// Points it cost (less than `CATCH_POINTS` when the score was lower).
        lost: i64,
    },
    /// The player's shot tagged a creature.
    Tagged {
        /// Index of the player who fired.
        player: usize,
    },
    /// The player reached the exit: the level is over.
    Exit {
        /// Index of the player.
        player: usize,
    },
}

impl Event {
    /// The player it happened to.
    #[must_use]
    pub fn player(&self) -> usize {
        match *self {
            Event::Picked { player, .. }
            | Event::KeyFound { player, .. }
            | Event::Locked { player, .. }
            | Event::Caught { player, .. }
            | Event::Tagged { player }
            | Event::Exit { player } => player,
        }
    }

    /// The line shown to that player ("You found the red key", "Locked: needs the blue key").
    #[must_use]
    pub fn message(&self) -> String {
        match self {
            Event::Picked { points, .. } => format!("Treasure! +{points} points"),
            Event::KeyFound { key, .. } => format!("You found the {key} key"),
            Event::Locked { key, .. } => locked_message(key),
            Event::Caught { lost: 0, .. } => "Caught by a creature!".to_owned(),
            Event::Caught { lost, .. } => format!("Caught by a creature! -{lost} points"),
            Event::Tagged { .. } => "Tagged a creature! It is out for a while".to_owned(),
            Event::Exit { .. } => "You reached the exit!".to_owned(),
        }
    }
}

fn locked_message(key: &str) -> String {
    format!("Locked: needs the {key} key")
}

/// Everything of a level that changes in play.
#[derive(Debug, Clone, PartialEq)]
pub struct Level {
    /// Per `ITEM` line: whether it has been picked up.
    taken: Vec<bool>,
    /// How many `ITEM`s are treasures (not keys).
    treasures: usize,
    /// Locked door cells and the key each needs.
    locks: BTreeMap<(i64, i64), String>,
    /// Exit cells.
    exits: Vec<(i64, i64)>,
    /// Creatures, in `CREATURE` line order.
    creatures: Vec<Creature>,
    /// Their sprites' sizes and frames, from the map lines (fixed).
    looks: Vec<(f64, u16)>,
    /// Shots in flight.
    projectiles: Vec<Projectile>,
    /// The creatures' dice.
    rng: Rng,
    /// The player who reached an exit, once someone has.
    finished: Option<usize>,
    /// Seconds played.
    time: f64,
    /// When each player may fire again (level time).
    reload: BTreeMap<usize, f64>,
    /// Solid sprites, which stop creatures as they stop players.
    discs: Vec<SolidDisc>,
}

impl Default for Level {
    /// A level with nothing in it (what a shared world shows before its first tick).
    fn default() -> Self {
        Self {
            taken: Vec::new(),
            treasures: 0,
            locks: BTreeMap::new(),
            exits: Vec::new(),
            creatures: Vec::new(),
            looks: Vec::new(),
            projectiles: Vec::new(),
            rng: Rng::new(0),
            finished: None,
            time: 0.0,
            reload: BTreeMap::new(),
            discs: Vec::new(),
        }
    }
}

impl Level {
    /// The level as `map` sets it up, its creatures' choices driven by `seed`.
    #[must_use]
    pub fn new(map: &Map, seed: u64) -> Self {
        let legacy = map.sprites.iter().map(|&centre| SolidDisc {
            centre,
            radius: DEFAULT_SOLID_RADIUS,
        });
        let defs = map.sprite_defs.iter().filter_map(|d| {
            d.solid.map(|radius| SolidDisc {
                centre: d.pos,
                radius,
            })
        });
        Self {
            taken: vec![false; map.items.len()],
            treasures: map.items.iter().filter(|i| i.is_treasure()).count(),
            locks: map.locks.iter().map(|l| (l.cell, l.key.clone())).collect(),
            exits: map.exits.iter().map(|e| e.cell).collect(),
            creatures: map
                .creatures
                .iter()
                .map(|d| Creature::new(d, map))
                .collect(),
            looks: map.creatures.iter().map(|d| (d.scale, d.frames)).collect(),
            projectiles: Vec::new(),
            rng: Rng::new(seed),
            finished: None,
            time: 0.0,
            reload: BTreeMap::new(),
            discs: legacy.chain(defs).collect(),
        }
    }

    /// One tick for every player at once (local play passes one): creatures walk and catch,
    /// shots fly, items are picked up (the first player in the slice wins a tie) and an exit
    /// ends the level. After the end nothing moves.
    pub fn tick(
        &mut self,
        map: &Map,
        doors: &DoorState,
        players: &mut [Player<'_>],
        dt: f64,
    ) -> Vec<Event> {
        let mut events = Vec::new();
        if self.finished.is_some() || !dt.is_finite() || dt <= 0.0 {
            return events;
        }
        self.time += dt;
        let ground = Ground {
            map,
            doors,
            discs: &self.discs,
        };
        let positions: Vec<(Vec2, f64)> = players.iter().map(|p| (p.pos, p.eye)).collect();
        for c in &mut self.creatures {
            c.step(&ground, &positions, &mut self.rng, dt);
            if !c.can_catch() {
                continue;
            }
            let caught = players.iter_mut().enumerate().find(|(_, p)| {
                (p.pos - c.pos).length() < CATCH_RADIUS && c.spans_height(map, p.eye)
            });
            if let Some((player, p)) = caught {
                let lost = p.score.lose(CATCH_POINTS);
                events.push(Event::Caught { player, lost });
                c.back_off(p.pos);
            }
        }
        let creatures = &mut self.creatures;
        self.projectiles
            .retain_mut(|shot| match shot.fly(map, doors, creatures, dt) {
                Flight::Flying => true,
                Flight::Spent => false,
                Flight::Hit(k) => {
                    creatures[k].tag();
                    events.push(Event::Tagged { player: shot.owner });
                    false
                }
            });
        for (k, item) in map.items.iter().enumerate() {
            if self.taken.get(k).is_none_or(|&t| t) {
                continue;
            }
            let Some((player, p)) = players
                .iter_mut()
                .enumerate()
                .find(|(_, p)| (p.pos - item.pos).length() < PICKUP_RADIUS)
            else {
                continue;
            };
            self.taken[k] = true;
            p.score.points += item.points;
            if item.points > 0 {
                events.push(Event::Picked {
                    player,
                    points: item.points,
                });
            }
            // A key's own message comes last, so it is the one the message line shows.
            if let Some(key) = &item.key {
                p.score.keys.insert(key.clone());
                events.push(Event::KeyFound {
                    player,
                    key: key.clone(),
                });
            } else {
                p.score.found += 1;
            }
        }
        let reached = players.iter().position(|p| {
            self.exits
                .contains(&(p.pos.x.floor() as i64, p.pos.y.floor() as i64))
        });
        if let Some(player) = reached {
            self.finished = Some(player);
            events.push(Event::Exit { player });
        }
        events
    }

    /// Fires a shot for `player` from `from`, at height `z` (their eye), along `dir` (ignored
    /// while that player reloads, for a zero direction, or once the level is over).
    pub fn fire(&mut self, player: usize, from: Vec2, z: f64, dir: Vec2) {
        let len = dir.length();
        if self.finished.is_some() || !(len > 0.0 && len.is_finite()) {
            return;
        }
        if self.reload.get(&player).is_some_and(|&t| t > self.time) {
            return;
        }
        self.reload.insert(player, self.time + RELOAD_SECONDS);
        self.projectiles.push(Projectile {
            pos: from,
            dir: dir * (1.0 / len),
            z,
            travelled: 0.0,
            owner: player,
        });
    }

    /// Whether a player with `score` may open the door at `door`.
    ///
    /// # Errors
    /// The message for a locked door whose key the player lacks ("Locked: needs the blue key").
    pub fn may_open(&self, door: (i64, i64), score: &Score) -> Result<(), String> {
        match self.locks.get(&door) {
            Some(key) if !score.has_key(key) => Err(locked_message(key)),
            _ => Ok(()),
        }
    }

    /// Whether a creature stands in cell `cell` (a door must not shut on it).
    #[must_use]
    pub fn creature_in(&self, cell: (i64, i64)) -> bool {
        self.creatures.iter().any(|c| {
            let r = super::creature::CREATURE_RADIUS;
            let (x0, x1) = ((c.pos.x - r).floor() as i64, (c.pos.x + r).floor() as i64);
            let (y0, y1) = ((c.pos.y - r).floor() as i64, (c.pos.y + r).floor() as i64);
            (x0..=x1).contains(&cell.0) && (y0..=y1).contains(&cell.1)
        })
    }

    /// The key the door at `door` needs, if it is locked.
    #[must_use]
    pub fn lock_of(&self, door: (i64, i64)) -> Option<&str> {
        self.locks.get(&door).map(String::as_str)
    }

    /// This frame's game sprites: items not yet taken, creatures (dimmed while tagged) and
    /// glowing shots, for [`crate::Scene::with_sprites`].
    #[must_use]
    pub fn sprites(&self, world: &World) -> Vec<Sprite> {
        let map = &world.map;
        let mut out = Vec::new();
        for (k, item) in map.items.iter().enumerate() {
            if self.taken.get(k).is_none_or(|&t| t) {
                continue;
            }
            let mut def = billboard(item.pos, item.texture.clone(), item.scale, item.at);
            def.key = ColourKey::Auto;
            out.push(Sprite {
                def,
                sheet: world.item_sheets[k],
            });
        }
        for (k, c) in self.creatures.iter().enumerate() {
            let d = &map.creatures[k];
            let (scale, frames) = self.looks[k];
            let mut def = billboard(c.pos, d.texture.clone(), scale, d.at);
            def.views = 8;
            def.facing_deg = c.facing_deg();
            def.frames = frames;
            // Walking frames follow the time; a frozen creature stands still on its first.
            def.fps = if c.is_out() { 0.0 } else { 2.5 * c.speed };
            if c.is_out() {
                def.blend = Blend::Average;
            }
            out.push(Sprite {
                def,
                sheet: world.creature_sheets[k],
            });
        }
        // Each exit as a glowing arch standing in its cell (see-through, so the way on shows).
        for &(i, j) in &self.exits {
            let texture = crate::map::TextureRef {
                path: "exit".to_owned(),
                line: 0,
                col: 0,
            };
            let centre = Vec2::new(i as f64 + 0.5, j as f64 + 0.5);
            let mut def = billboard(centre, texture, 0.9, (0, 0));
            def.key = ColourKey::Auto;
            out.push(Sprite {
                def,
                sheet: world.exit_sheet,
            });
        }
        for shot in &self.projectiles {
            let size = 0.25;
            let texture = crate::map::TextureRef {
                path: "glow".to_owned(),
                line: 0,
                col: 0,
            };
            let mut def = billboard(shot.pos, texture, size, (0, 0));
            def.offset = shot.z - size / 2.0;
            def.blend = Blend::Additive;
            if map.has_heights() {
                // sprite_base adds the cell's floor on Hz maps; z already includes it.
                let (i, j) = (shot.pos.x.floor() as i64, shot.pos.y.floor() as i64);
                def.offset -= map.floor_height(i, j);
            }
            out.push(Sprite {
                def,
                sheet: world.glow_sheet,
            });
        }
        out
    }

    /// Shots in flight as moving lights (they light the walls near them at night), for
    /// [`crate::Scene::with_lights`].
    #[must_use]
    pub fn lights(&self) -> Vec<PointLight> {
        self.projectiles
            .iter()
            .map(|s| PointLight {
                pos: s.pos,
                z: s.z,
                radius: SHOT_LIGHT_RADIUS,
                strength: SHOT_LIGHT_STRENGTH,
            })
            .collect()
    }

    /// Items not yet picked up.
    #[must_use]
    pub fn items_left(&self) -> usize {
        self.taken.iter().filter(|&&t| !t).count()
    }

    /// Every item of the level (treasures and keys).
    #[must_use]
    pub fn items_total(&self) -> usize {
        self.taken.len()
    }

    /// Treasures (items that are not keys) in the level.
    #[must_use]
    pub fn treasures_total(&self) -> usize {
        self.treasures
    }

    /// Treasures of `map` (this level's map) not yet picked up: what the status line counts,
    /// so it agrees with the start message's "0/12 treasures" (keys show once held).
    #[must_use]
    pub fn treasures_left(&self, map: &Map) -> usize {
        map.items
            .iter()
            .enumerate()
            .filter(|(k, item)| item.is_treasure() && !self.is_taken(*k))
            .count()
    }

    /// The player who reached an exit, once the level is over.
    #[must_use]
    pub fn finished(&self) -> Option<usize> {
        self.finished
    }

    /// Seconds the level has been played.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The creatures as they are now.
    #[must_use]
    pub fn creatures(&self) -> &[Creature] {
        &self.creatures
    }

    /// The shots in flight.
    #[must_use]
    pub fn projectiles(&self) -> &[Projectile] {
        &self.projectiles
    }

    /// Whether item `k` (its `ITEM` line's index) has been picked up.
    #[must_use]
    pub fn is_taken(&self, k: usize) -> bool {
        self.taken.get(k).copied().unwrap_or(true)
    }
}

/// A plain floor-standing billboard at `pos` (no collision), as items and creatures start.
fn billboard(
    pos: Vec2,
    texture: crate::map::TextureRef,
    scale: f64,
    at: (usize, usize),
) -> SpriteDef {
    let mut def = SpriteDef::legacy(pos, texture);
    def.scale = (scale, scale);
    def.solid = None;
    def.at = at;
    def
}
