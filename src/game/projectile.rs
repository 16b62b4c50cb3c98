//! The tag: a short glowing shot from a player's eye that flies straight and level, stops at the
//! first wall or shut door on the renderer's DDA (on maps with heights also at a step's face, a
//! lintel or a balcony's side), and tags the first creature it meets at its height.

use super::creature::{Creature, CREATURE_RADIUS};
use super::sight::first_block_at;
use crate::map::Map;
use crate::vec2::Vec2;
use crate::world::door::DoorState;

/// Flight speed in cells per second.
pub const SHOT_SPEED: f64 = 8.0;

/// Farthest a shot flies, in cells.
pub const SHOT_RANGE: f64 = 6.0;

/// A shot meets a creature whose centre comes this close to its path, in cells.
pub const HIT_RADIUS: f64 = CREATURE_RADIUS + 0.1;

/// Seconds between two shots of one player.
pub const RELOAD_SECONDS: f64 = 0.4;

/// The light a shot gives, as [`super::level::Level::lights`] reports it: radius in cells.
pub const SHOT_LIGHT_RADIUS: f64 = 2.5;

/// How bright a shot is at its centre (0–1, 1 = daylight).
pub const SHOT_LIGHT_STRENGTH: f64 = 0.9;

/// One shot in flight.
#[derive(Debug, Clone, PartialEq)]
pub struct Projectile {
    /// Where it is on the map plane.
    pub pos: Vec2,
    /// Which way it flies (unit length).
    pub dir: Vec2,
    /// Its height in the world: the eye it was fired from (it flies level).
    pub z: f64,
    /// Cells flown so far.
    pub travelled: f64,
    /// The player who fired it.
    pub owner: usize,
}

/// What became of a shot in one tick.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flight {
    /// Still flying.
    Flying,
    /// Stopped by a wall, a shut door or its range.
    Spent,
    /// Met the creature of this index (which it tags).
    Hit(usize),
}

impl Projectile {
    /// Moves the shot on by `dt` seconds: the first creature within [`HIT_RADIUS`] of its path
    /// before any wall is hit; else it stops at a wall or at the end of its range.
    pub fn fly(&mut self, map: &Map, doors: &DoorState, creatures: &[Creature], dt: f64) -> Flight {
        let dist = (SHOT_SPEED * dt.max(0.0)).min(SHOT_RANGE - self.travelled);
        let end = self.pos + self.dir * dist;
        let wall = first_block_at(map, doors, (self.pos, self.z), (end, self.z));
        let reach = wall.map_or(dist, |(_, t)| dist * t);
        // The hit nearest along the path, if any comes before the wall.
        let mut hit: Option<(f64, usize)> = None;
        for (k, c) in creatures.iter().enumerate() {
            if c.is_out() || !c.spans_height(map, self.z) {
                continue;
            }
            let rel = c.pos - self.pos;
            let along = rel.dot(self.dir).clamp(0.0, reach);
            let gap = (c.pos - (self.pos + self.dir * along)).length();
            if gap >= HIT_RADIUS {
                continue;
            }
            // Where the path first comes within the radius (the shot meets the creature's edge).
            let meet = (along - (HIT_RADIUS * HIT_RADIUS - gap * gap).sqrt()).max(0.0);
            if hit.is_none_or(|(a, _)| meet < a) {
                hit = Some((meet, k));
            }
        }
        if let Some((along, k)) = hit {
            self.pos = self.pos + self.dir * along;
            return Flight::Hit(k);
        }
        self.pos = self.pos + self.dir * reach;
        self.travelled += reach;
        if wall.is_some() || self.travelled >= SHOT_RANGE - 1e-9 {
            Flight::Spent
        } else {
            Flight::Flying
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::{grid_map, Behaviour, CreatureDef, TextureRef};

    fn shot(from: Vec2, dir: Vec2) -> Projectile {
        Projectile {
            pos: from,
            dir,
            z: 0.5,
            travelled: 0.0,
            owner: 0,
        }
    }

    #[test]
    fn a_shot_stops_at_the_wall_and_at_its_range() {
        let m = grid_map("111111\n1N0001\n111111\n");
        let doors = DoorState::none();
        let mut s = shot(Vec2::new(1.5, 1.5), Vec2::new(1.0, 0.0));
        assert_eq!(s.fly(&m, &doors, &[], 0.25), Flight::Flying);
        assert_eq!(s.fly(&m, &doors, &[], 0.25), Flight::Spent);
        assert!((s.pos.x - 5.0).abs() < 1e-9, "{:?}", s.pos);
        let long = grid_map(&format!(
            "1{}1\n1N{}1\n1{}1\n",
            "1".repeat(20),
            "0".repeat(19),
            "1".repeat(20)
        ));
        let mut s = shot(Vec2::new(1.5, 1.5), Vec2::new(1.0, 0.0));
        let mut ticks = 0;
        while s.fly(&long, &doors, &[], 0.1) == Flight::Flying {
            ticks += 1;
        }
        assert!(
            (s.travelled - SHOT_RANGE).abs() < 1e-9 && ticks == 7,
            "{ticks} {s:?}"
        );
    }

    #[test]
    fn a_shot_tags_the_first_creature_on_its_path() {
        let m = grid_map("11111111\n1N000001\n11111111\n");
        let doors = DoorState::none();
        let creatures = vec![creature_at(5.5, &m), creature_at(3.5, &m)];
        let mut s = shot(Vec2::new(1.5, 1.5), Vec2::new(1.0, 0.0));
        assert_eq!(s.fly(&m, &doors, &creatures, 0.5), Flight::Hit(1));
        assert!((s.pos.x - (3.5 - HIT_RADIUS)).abs() < 1e-9, "{:?}", s.pos);
    }

    fn creature_at(x: f64, m: &Map) -> Creature {
        let def = CreatureDef {
            pos: Vec2::new(x, 1.5),
            texture: TextureRef {
                path: "c".into(),
                line: 1,
                col: 1,
            },
            speed: 1.0,
            behaviour: Behaviour::Wander,
            scale: 0.7,
            frames: 4,
            at: (1, 1),
        };
        Creature::new(&def, m)
    }

    #[test]
    fn on_height_maps_a_step_face_stops_a_shot_below_its_top_and_not_one_above() {
        let m = crate::game::sight::stepped_row("0.8 2");
        let doors = DoorState::none();
        let mut low = shot(Vec2::new(2.5, 1.5), Vec2::new(1.0, 0.0));
        assert_eq!(low.fly(&m, &doors, &[], 0.5), Flight::Spent);
        assert!((low.pos.x - 3.0).abs() < 1e-9, "{:?}", low.pos);
        let mut high = shot(Vec2::new(2.5, 1.5), Vec2::new(1.0, 0.0));
        high.z = 0.9;
        assert_eq!(high.fly(&m, &doors, &[], 0.5), Flight::Flying);
        assert!((high.pos.x - 6.5).abs() < 1e-9, "{:?}", high.pos);
    }

    #[test]
    fn a_shot_passes_over_a_creature_down_in_a_pit_and_tags_one_at_its_height() {
        let m = crate::game::sight::stepped_row("-1.5 2");
        let doors = DoorState::none();
        let creatures = vec![creature_at(3.5, &m), creature_at(5.5, &m)];
        let mut s = shot(Vec2::new(2.5, 1.5), Vec2::new(1.0, 0.0));
        assert_eq!(s.fly(&m, &doors, &creatures, 0.5), Flight::Hit(1));
        // Flat maps: every creature is at a shot's height.
        let flat = grid_map("11111111\n1N000001\n11111111\n");
        let creatures = vec![creature_at(3.5, &flat), creature_at(5.5, &flat)];
        let mut s = shot(Vec2::new(2.5, 1.5), Vec2::new(1.0, 0.0));
        assert_eq!(s.fly(&flat, &doors, &creatures, 0.5), Flight::Hit(0));
    }
}
