//! Everyone in the shared world: joins, leaves, held keys, and one fixed-size step for all.
//!
//! Pure (no clock, no channels): the world task in `world_task.rs` drives it at a fixed tick.

use std::collections::BTreeMap;
use std::sync::Arc;

use super::player::{spawn_point, step_pose, Held, Pose};
use crate::color::Rgb;
use crate::map::Map;
use crate::vec2::Vec2;

/// A connection's id; also names its player in the world.
pub type PlayerId = u64;

/// Colours players are told apart by (in the minimap and as markers), by join order.
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
#[derive(Debug, Clone, PartialEq)]
pub struct PlayerView {
    pub id: PlayerId,
    pub name: String,
    pub pose: Pose,
    pub color: Rgb,
}

/// The world as sessions see it after a tick: immutable, shared by `Arc`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Snapshot {
    /// Counts published snapshots; a session re-renders only when it changes.
    pub version: u64,
    /// In join order.
    pub players: Vec<PlayerView>,
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
    pose: Pose,
    held: Held,
    color: Rgb,
}

/// The game state of the shared world: every player, keyed by id.
#[derive(Debug, Clone, Default)]
pub struct Players {
    players: BTreeMap<PlayerId, Player>,
    joined: u64,
    version: u64,
    changed: bool,
}

impl Players {
    /// Nobody here yet.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a player at a free spawn point (ignored if `id` is already here).
    pub fn join(&mut self, map: &Map, id: PlayerId, name: &str) {
        if self.players.contains_key(&id) {
            return;
        }
        let taken: Vec<Vec2> = self.players.values().map(|p| p.pose.pos).collect();
        let pos = spawn_point(map, &taken);
        let color = PALETTE[(self.joined % PALETTE.len() as u64) as usize];
        self.joined += 1;
        self.players.insert(
            id,
            Player {
                name: name.to_string(),
                pose: Pose {
                    pos,
                    angle_deg: map.start.angle_deg(),
                },
                held: Held::default(),
                color,
            },
        );
        self.changed = true;
    }

    /// Removes a player (no-op if absent).
    pub fn leave(&mut self, id: PlayerId) {
        self.changed |= self.players.remove(&id).is_some();
    }

    /// Sets which keys a player holds until the next change.
    pub fn set_held(&mut self, id: PlayerId, held: Held) {
        if let Some(p) = self.players.get_mut(&id) {
            p.held = held;
        }
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

    /// Moves everyone by `dt` seconds, in id order, each against the others' current places.
    /// Returns whether anything changed since the last call (then a new snapshot is due).
    pub fn tick(&mut self, map: &Map, dt: f64) -> bool {
        let ids: Vec<PlayerId> = self.players.keys().copied().collect();
        for id in ids {
            let Some(me) = self.players.get(&id) else {
                continue;
            };
            if !me.held.any() {
                continue;
            }
            let others: Vec<Vec2> = self
                .players
                .iter()
                .filter(|(k, _)| **k != id)
                .map(|(_, p)| p.pose.pos)
                .collect();
            let next = step_pose(map, me.pose, me.held, dt, &others);
            if let Some(me) = self.players.get_mut(&id) {
                if next != me.pose {
                    me.pose = next;
                    self.changed = true;
                }
            }
        }
        std::mem::take(&mut self.changed)
    }

    /// The current state as sessions see it; bumps the version.
    pub fn snapshot(&mut self) -> Snapshot {
        self.version += 1;
        Snapshot {
            version: self.version,
            players: self
                .players
                .iter()
                .map(|(&id, p)| PlayerView {
                    id,
                    name: p.name.clone(),
                    pose: p.pose,
                    color: p.color,
                })
                .collect(),
        }
    }
}

/// A shared snapshot, as handed to sessions.
pub type SharedSnapshot = Arc<Snapshot>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::World;

    #[test]
    fn join_move_leave() {
        let world = World::default_world();
        let map = &world.map;
        let mut ps = Players::new();
        ps.join(map, 1, "ann");
        ps.join(map, 2, "bob");
        assert!(ps.tick(map, 0.1), "joins are changes");
        let s = ps.snapshot();
        assert_eq!(s.players.len(), 2);
        assert_ne!(s.players[0].pose.pos, s.players[1].pose.pos);
        assert!(!ps.tick(map, 0.1), "idle players change nothing");
        ps.set_held(
            1,
            Held {
                turn_left: true,
                ..Held::default()
            },
        );
        assert!(ps.tick(map, 0.1));
        ps.leave(2);
        assert!(ps.tick(map, 0.0));
        let s2 = ps.snapshot();
        assert_eq!(s2.players.len(), 1);
        assert!(s2.version > s.version);
        assert!((s2.players[0].pose.angle_deg - s.players[0].pose.angle_deg).abs() > 1.0);
    }
}
