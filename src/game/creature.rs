//! Creatures that walk the grid: from cell centre to cell centre, with the players' collision
//! rules, looking for players along the renderer's DDA and chasing the nearest one they see.

use std::collections::VecDeque;

use super::body::Body;
use super::collision::{self, Obstacles};
use super::rng::Rng;
use super::sight::{blocks_sight, sees, SIGHT_RANGE};
use crate::map::{Behaviour, CreatureDef, Map};
use crate::render::view::STANDING_EYE;
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::SolidDisc;

/// A creature's half-size for collision, in cells (a player's is 0.2).
pub const CREATURE_RADIUS: f64 = 0.25;

/// How far a `chase` creature sees, in cells (others see [`SIGHT_RANGE`]).
pub const CHASE_SIGHT_RANGE: f64 = 16.0;

/// Seconds a creature keeps heading for where it last saw a player.
pub const FORGET_SECONDS: f64 = 3.0;

/// How much faster a creature walks while chasing.
pub const CHASE_SPEEDUP: f64 = 1.4;

/// Seconds a creature that caught someone keeps away (and cannot catch anyone).
pub const BACK_OFF_SECONDS: f64 = 3.0;

/// Seconds a tagged creature stays out (frozen, drawn dimmed, harmless).
pub const TAGGED_SECONDS: f64 = 10.0;

/// How far from its cell the path search looks, in cells each way.
const SEARCH_SPAN: i64 = 12;

/// The four ways a creature can step: east, south, west, north.
const STEPS: [(i64, i64); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)];

/// What a creature walks in this tick: the grid, the doors as they are and solid sprites.
#[derive(Debug, Clone, Copy)]
pub struct Ground<'a> {
    /// The grid.
    pub map: &'a Map,
    /// How far each door is open (a door that blocks players blocks creatures).
    pub doors: &'a DoorState,
    /// Solid sprites.
    pub discs: &'a [SolidDisc],
}

impl Ground<'_> {
    /// Whether a creature standing in `from` may step into the neighbouring cell `to`: open
    /// (no wall, void or shut door), enterable at its height, and not holding a solid sprite.
    #[must_use]
    pub fn can_step(&self, from: (i64, i64), to: (i64, i64)) -> bool {
        if blocks_sight(self.map, self.doors, to.0, to.1) {
            return false;
        }
        let feet = self.map.floor_height(from.0, from.1);
        let body = Body {
            feet,
            eye: STANDING_EYE,
        };
        body.can_enter(self.map, to.0, to.1)
            && !self
                .discs
                .iter()
                .any(|d| collision::centre_cell(d.centre) == to)
    }
}

/// Where a chasing creature is heading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chase {
    /// Where it last saw the player it chases.
    pub target: Vec2,
    /// Seconds since it last saw anyone.
    pub unseen: f64,
}

/// One creature's state (everything that changes while it plays).
#[derive(Debug, Clone, PartialEq)]
pub struct Creature {
    /// Centre on the map plane.
    pub pos: Vec2,
    /// Which way it walks (unit), for its 8-view sprite.
    pub facing: Vec2,
    /// What it does when it sees nobody.
    pub behaviour: Behaviour,
    /// Walking speed in cells per second.
    pub speed: f64,
    /// Its chase, while it sees (or lately saw) a player.
    pub chase: Option<Chase>,
    /// Seconds left out after being tagged (0 = playing).
    pub tagged: f64,
    /// Seconds left keeping away after a catch.
    pub backing_off: f64,
    /// Distance walked, in cells (its walking animation).
    pub walked: f64,
    /// The cell whose centre it walks to.
    goal: (i64, i64),
    /// The last step it took (wander keeps going, patrol turns back).
    heading: (i64, i64),
    /// Where the player it caught stood (it keeps away from there).
    flee_from: Vec2,
}

fn centre(c: (i64, i64)) -> Vec2 {
    Vec2::new(c.0 as f64 + 0.5, c.1 as f64 + 0.5)
}

fn add(c: (i64, i64), d: (i64, i64)) -> (i64, i64) {
    (c.0 + d.0, c.1 + d.1)
}

impl Creature {
    /// A creature at its map line's place, heading for its cell's centre; a patroller's line is
    /// the longer run of open cells (east–west or north–south) through its start.
    #[must_use]
    pub fn new(def: &CreatureDef, map: &Map) -> Self {
        let pos = collision::settle(map, def.pos, CREATURE_RADIUS);
        let cell = collision::centre_cell(pos);
        let run = |d: (i64, i64)| {
            let mut n = 0;
            let mut c = add(cell, d);
            while map.span(c.0, c.1).is_some() && n < 1024 {
                n += 1;
                c = add(c, d);
            }
            n
        };
        let (ew, ns) = (run((1, 0)) + run((-1, 0)), run((0, 1)) + run((0, -1)));
        let heading = match (ns > ew, run((1, 0)) > 0, run((0, 1)) > 0) {
            (false, true, _) => (1, 0),
            (false, false, _) => (-1, 0),
            (true, _, true) => (0, 1),
            (true, _, false) => (0, -1),
        };
        Self {
            pos,
            facing: Vec2::new(heading.0 as f64, heading.1 as f64),
            behaviour: def.behaviour,
            speed: def.speed,
            chase: None,
            tagged: 0.0,
            backing_off: 0.0,
            walked: 0.0,
            goal: cell,
            heading,
            flee_from: pos,
        }
    }

    /// Whether it is out of play (tagged).
    #[must_use]
    pub fn is_out(&self) -> bool {
        self.tagged > 0.0
    }

    /// Whether touching a player now counts as a catch.
    #[must_use]
    pub fn can_catch(&self) -> bool {
        !self.is_out() && self.backing_off <= 0.0
    }

    /// The creature's facing in CLI degrees (0 = east, 90 = north), for its sprite's views.
    #[must_use]
    pub fn facing_deg(&self) -> f64 {
        (-self.facing.y).atan2(self.facing.x).to_degrees()
    }

    /// Takes it out of play for [`TAGGED_SECONDS`].
    pub fn tag(&mut self) {
        self.tagged = TAGGED_SECONDS;
        self.chase = None;
    }

    /// After catching the player at `player`: keep away from there for [`BACK_OFF_SECONDS`],
    /// turning back to its cell's centre if its next cell is nearer the player.
    pub fn back_off(&mut self, player: Vec2) {
        self.backing_off = BACK_OFF_SECONDS;
        self.chase = None;
        self.flee_from = player;
        let here = collision::centre_cell(self.pos);
        let d = |c: (i64, i64)| (centre(c) - player).length();
        if d(here) > d(self.goal) {
            self.heading = (here.0 - self.goal.0, here.1 - self.goal.1);
            self.goal = here;
        }
    }

    /// Whether height `z` is within its body, from the floor of its cell up one wall: a tag
    /// over a pit, or a player on a balcony above, passes a creature below.
    #[must_use]
    pub fn spans_height(&self, map: &Map, z: f64) -> bool {
        let (i, j) = collision::centre_cell(self.pos);
        let feet = map.floor_height(i, j);
        (feet..=feet + 1.0).contains(&z)
    }

    /// One tick: look for players (each a position and the height of their eye), then walk up
    /// to `speed · dt` along its cells.
    pub fn step(&mut self, ground: &Ground, players: &[(Vec2, f64)], rng: &mut Rng, dt: f64) {
        if self.is_out() {
            self.tagged = (self.tagged - dt).max(0.0);
            return;
        }
        self.backing_off = (self.backing_off - dt).max(0.0);
        self.look(ground, players, dt);
        let speed = if self.chase.is_some() {
            self.speed * CHASE_SPEEDUP
        } else {
            self.speed
        };
        let mut budget = speed * dt;
        let feet = |p: Vec2| {
            let c = collision::centre_cell(p);
            ground.map.floor_height(c.0, c.1)
        };
        for _ in 0..4 {
            if budget <= 0.0 {
                break;
            }
            let target = centre(self.goal);
            let to = target - self.pos;
            let d = to.length();
            if d < 1e-9 {
                self.pos = target;
                if !self.choose_goal(ground, rng) {
                    break;
                }
                continue;
            }
            let go = d.min(budget);
            let obstacles = Obstacles {
                map: ground.map,
                doors: Some(ground.doors),
                discs: ground.discs,
                body: Some(Body {
                    feet: feet(self.pos),
                    eye: STANDING_EYE,
                }),
            };
            let next = collision::slide(&obstacles, self.pos, to * (go / d), CREATURE_RADIUS);
            let moved = (next - self.pos).length();
            self.facing = to * (1.0 / d);
            self.pos = next;
            self.walked += moved;
            budget -= go;
            if moved < go * 0.5 {
                // Something shut or stood in the way: turn back to this cell's centre and
                // choose again from there.
                let here = collision::centre_cell(self.pos);
                if here == self.goal {
                    self.heading = (-self.heading.0, -self.heading.1);
                } else {
                    self.heading = (here.0 - self.goal.0, here.1 - self.goal.1);
                    self.goal = here;
                }
                break;
            }
            if (self.pos - target).length() < 1e-6 {
                self.pos = target;
                if !self.choose_goal(ground, rng) {
                    break;
                }
            }
        }
    }

    /// Updates its chase from what it sees: the nearest player in its line of sight and range.
    fn look(&mut self, ground: &Ground, players: &[(Vec2, f64)], dt: f64) {
        if self.backing_off > 0.0 {
            self.chase = None;
            return;
        }
        let range = if self.behaviour == Behaviour::Chase {
            CHASE_SIGHT_RANGE
        } else {
            SIGHT_RANGE
        };
        // It looks from a standing eye's height over its own floor.
        let (i, j) = collision::centre_cell(self.pos);
        let eye = ground.map.floor_height(i, j) + STANDING_EYE;
        let mut best: Option<(f64, Vec2)> = None;
        for &(p, p_eye) in players {
            let d = (p - self.pos).length();
            if best.is_none_or(|(bd, _)| d < bd)
                && sees(ground.map, ground.doors, (self.pos, eye), (p, p_eye), range)
            {
                best = Some((d, p));
            }
        }
        match (best, &mut self.chase) {
            (Some((_, p)), _) => {
                self.chase = Some(Chase {
                    target: p,
                    unseen: 0.0,
                });
            }
            (None, Some(c)) => {
                c.unseen += dt;
                if c.unseen > FORGET_SECONDS {
                    self.chase = None;
                }
            }
            (None, None) => {}
        }
    }

    /// At a cell centre: picks the next cell; false when every way is shut (it waits).
    fn choose_goal(&mut self, ground: &Ground, rng: &mut Rng) -> bool {
        let here = collision::centre_cell(self.pos);
        let open: Vec<(i64, i64)> = STEPS
            .iter()
            .copied()
            .filter(|&d| ground.can_step(here, add(here, d)))
            .collect();
        if open.is_empty() {
            self.goal = here;
            return false;
        }
        let back = (-self.heading.0, -self.heading.1);
        let step = if self.backing_off > 0.0 {
            let away = |d: &(i64, i64)| (centre(add(here, *d)) - self.flee_from).length();
            *open
                .iter()
                .max_by(|a, b| away(a).total_cmp(&away(b)))
                .expect("open is not empty")
        } else if let Some(chase) = self.chase {
            let target = collision::centre_cell(chase.target);
            if target == here && chase.unseen > 0.0 {
                // Searched where the player was last seen: give up.
                self.chase = None;
                self.wander(&open, back, rng)
            } else {
                path_step(ground, here, target).unwrap_or_else(|| {
                    let near = |d: &(i64, i64)| (centre(add(here, *d)) - chase.target).length();
                    *open
                        .iter()
                        .min_by(|a, b| near(a).total_cmp(&near(b)))
                        .expect("open is not empty")
                })
            }
        } else if self.behaviour == Behaviour::Patrol {
            if open.contains(&self.heading) {
                self.heading
            } else if open.contains(&back) {
                back
            } else {
                open[rng.below(open.len())]
            }
        } else {
            self.wander(&open, back, rng)
        };
        self.heading = step;
        self.goal = add(here, step);
        true
    }

    /// A wanderer's choice: often straight on, else any way but back (back only at a dead end).
    fn wander(&self, open: &[(i64, i64)], back: (i64, i64), rng: &mut Rng) -> (i64, i64) {
        if open.contains(&self.heading) && rng.unit() < 0.5 {
            return self.heading;
        }
        let ways: Vec<(i64, i64)> = open.iter().copied().filter(|&d| d != back).collect();
        if ways.is_empty() {
            back
        } else {
            ways[rng.below(ways.len())]
        }
    }
}

/// The first step of a shortest way from `from` to `to` over cells a creature can step into,
/// searched within [`SEARCH_SPAN`] cells of `from` (breadth first, so the same map and doors
/// always give the same step); `None` when there is none in that window.
fn path_step(ground: &Ground, from: (i64, i64), to: (i64, i64)) -> Option<(i64, i64)> {
    if from == to || (to.0 - from.0).abs() > SEARCH_SPAN || (to.1 - from.1).abs() > SEARCH_SPAN {
        return None;
    }
    let side = (2 * SEARCH_SPAN + 1) as usize;
    let index = |c: (i64, i64)| {
        let (x, y) = (c.0 - from.0 + SEARCH_SPAN, c.1 - from.1 + SEARCH_SPAN);
        ((0..side as i64).contains(&x) && (0..side as i64).contains(&y))
            .then(|| y as usize * side + x as usize)
    };
    // The first step that led to each cell (None = not reached yet).
    let mut first: Vec<Option<(i64, i64)>> = vec![None; side * side];
    let mut queue = VecDeque::new();
    for d in STEPS {
        let c = add(from, d);
        if let Some(k) = index(c) {
            if ground.can_step(from, c) {
                first[k] = Some(d);
                queue.push_back(c);
            }
        }
    }
    while let Some(c) = queue.pop_front() {
        let k = index(c).expect("queued cells are in the window");
        if c == to {
            return first[k];
        }
        for d in STEPS {
            let n = add(c, d);
            let Some(nk) = index(n) else { continue };
            if n == from || first[nk].is_some() || !ground.can_step(c, n) {
                continue;
            }
            first[nk] = first[k];
            queue.push_back(n);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::grid_map;

    fn def(pos: Vec2, behaviour: Behaviour) -> CreatureDef {
        CreatureDef {
            pos,
            texture: crate::map::TextureRef {
                path: "creature".into(),
                line: 1,
                col: 1,
            },
            speed: 1.5,
            behaviour,
            scale: 0.7,
            frames: 4,
            at: (1, 1),
        }
    }

    #[test]
    fn a_patroller_walks_its_longer_line_back_and_forth() {
        let m = grid_map("1111111\n1N00001\n1011111\n1011111\n1111111\n");
        let doors = DoorState::none();
        let ground = Ground {
            map: &m,
            doors: &doors,
            discs: &[],
        };
        let mut c = Creature::new(&def(Vec2::new(2.5, 1.5), Behaviour::Patrol), &m);
        let mut rng = Rng::new(1);
        let (mut min_x, mut max_x) = (f64::MAX, f64::MIN);
        for _ in 0..600 {
            c.step(&ground, &[], &mut rng, 0.05);
            min_x = min_x.min(c.pos.x);
            max_x = max_x.max(c.pos.x);
            assert!((c.pos.y - 1.5).abs() < 1e-9, "left its line: {:?}", c.pos);
        }
        assert!(
            min_x <= 1.5 + 1e-6 && max_x >= 5.5 - 1e-6,
            "{min_x} {max_x}"
        );
    }

    #[test]
    fn a_creature_that_sees_a_player_walks_to_it_round_a_corner() {
        let m = grid_map("111111\n1N0001\n111101\n111101\n111111\n");
        let doors = DoorState::none();
        let ground = Ground {
            map: &m,
            doors: &doors,
            discs: &[],
        };
        let mut c = Creature::new(&def(Vec2::new(1.5, 1.5), Behaviour::Wander), &m);
        let mut rng = Rng::new(3);
        let player = Vec2::new(4.5, 1.5);
        for _ in 0..40 {
            c.step(&ground, &[(player, STANDING_EYE)], &mut rng, 0.05);
        }
        assert!(c.chase.is_some());
        assert!((c.pos - player).length() < 1.0, "{:?}", c.pos);
    }

    #[test]
    fn a_path_goes_round_walls() {
        let m = grid_map("11111\n1N001\n11101\n10001\n11111\n");
        let doors = DoorState::none();
        let ground = Ground {
            map: &m,
            doors: &doors,
            discs: &[],
        };
        assert_eq!(path_step(&ground, (1, 1), (1, 3)), Some((1, 0)));
        assert_eq!(path_step(&ground, (3, 3), (1, 1)), Some((0, -1)));
        assert_eq!(path_step(&ground, (1, 1), (1, 1)), None);
    }
}
