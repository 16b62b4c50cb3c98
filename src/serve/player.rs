//! One player's pose and how held keys move it, with wall and player-player collision.
//!
//! STAND-IN: the TUI branch brings `game::GameState`, `game::Input` and
//! `game::step(state, input, dt)`. When merging, make [`Players::tick`] call `game::step` per
//! player (and keep the player-player check here, or move it into `game`).

use crate::map::Map;
use crate::vec2::Vec2;

/// How far a player's body reaches from its centre, in cells (walls and other players).
pub const PLAYER_RADIUS: f64 = 0.2;
/// Walking speed in cells per second.
const MOVE_SPEED: f64 = 3.0;
/// Turning speed in degrees per second.
const TURN_SPEED: f64 = 120.0;

/// Which movement keys are held right now.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Held {
    pub forward: bool,
    pub back: bool,
    pub turn_left: bool,
    pub turn_right: bool,
    pub strafe_left: bool,
    pub strafe_right: bool,
}

impl Held {
    /// Whether any key is held (an idle player needs no step).
    #[must_use]
    pub fn any(self) -> bool {
        self != Self::default()
    }
}

/// Where a player stands and faces (angle in CLI degrees: 0 = east, 90 = north).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    pub pos: Vec2,
    pub angle_deg: f64,
}

impl Pose {
    /// The unit facing vector, (cos a, −sin a).
    #[must_use]
    pub fn dir(self) -> Vec2 {
        let a = self.angle_deg.to_radians();
        Vec2::new(a.cos(), -a.sin())
    }
}

/// Advances one pose by `dt` seconds of `held` keys; `others` are the other players' centres.
#[must_use]
pub fn step_pose(map: &Map, pose: Pose, held: Held, dt: f64, others: &[Vec2]) -> Pose {
    let turn = f64::from(i8::from(held.turn_left) - i8::from(held.turn_right));
    let angle_deg = (pose.angle_deg + turn * TURN_SPEED * dt).rem_euclid(360.0);
    let dir = Pose {
        pos: pose.pos,
        angle_deg,
    }
    .dir();
    let ahead = f64::from(i8::from(held.forward) - i8::from(held.back));
    let side = f64::from(i8::from(held.strafe_right) - i8::from(held.strafe_left));
    let mut wish = dir * ahead + dir.right_normal() * side;
    let len = wish.length();
    if len > 1.0 {
        wish = wish * (1.0 / len);
    }
    let delta = wish * (MOVE_SPEED * dt);
    let mut pos = pose.pos;
    // Per axis, so a player slides along a wall or another player instead of sticking.
    let try_x = Vec2::new(pos.x + delta.x, pos.y);
    if can_stand(map, try_x) && !bumps(pos, try_x, others) {
        pos = try_x;
    }
    let try_y = Vec2::new(pos.x, pos.y + delta.y);
    if can_stand(map, try_y) && !bumps(pos, try_y, others) {
        pos = try_y;
    }
    Pose { pos, angle_deg }
}

/// Whether a body of [`PLAYER_RADIUS`] centred at `p` touches only floor.
#[must_use]
pub fn can_stand(map: &Map, p: Vec2) -> bool {
    let r = PLAYER_RADIUS;
    [(-r, -r), (r, -r), (-r, r), (r, r)]
        .iter()
        .all(|&(dx, dy)| map.is_walkable(Vec2::new(p.x + dx, p.y + dy)))
}

/// Whether moving from `from` to `to` walks into another player (moving apart is always allowed,
/// so players spawned on top of each other can separate).
fn bumps(from: Vec2, to: Vec2, others: &[Vec2]) -> bool {
    let min = 2.0 * PLAYER_RADIUS;
    others.iter().any(|&o| {
        let d_to = (to - o).length();
        d_to < min && d_to < (from - o).length()
    })
}

/// A free place to appear: the map start if nobody is near it, else the nearest free floor cell
/// centre (by rings around the start), else the start anyway.
#[must_use]
pub fn spawn_point(map: &Map, taken: &[Vec2]) -> Vec2 {
    let start = map.start.pos();
    let free = |p: Vec2| can_stand(map, p) && taken.iter().all(|&o| (p - o).length() >= 0.9);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::World;

    fn pose(x: f64, y: f64, a: f64) -> Pose {
        Pose {
            pos: Vec2::new(x, y),
            angle_deg: a,
        }
    }

    #[test]
    fn walking_into_a_wall_stops_at_the_radius() {
        let world = World::default_world();
        let map = &world.map;
        let mut p = Pose {
            pos: map.start.pos(),
            angle_deg: 0.0,
        };
        let held = Held {
            forward: true,
            ..Held::default()
        };
        for _ in 0..600 {
            p = step_pose(map, p, held, 1.0 / 30.0, &[]);
            assert!(can_stand(map, p.pos));
        }
    }

    #[test]
    fn players_do_not_walk_through_each_other_but_may_separate() {
        let world = World::default_world();
        let map = &world.map;
        let start = map.start.pos();
        let other = start
            + Pose {
                pos: start,
                angle_deg: 0.0,
            }
            .dir()
                * 0.5;
        let held = Held {
            forward: true,
            ..Held::default()
        };
        let mut p = pose(start.x, start.y, 0.0);
        for _ in 0..60 {
            p = step_pose(map, p, held, 1.0 / 30.0, &[other]);
        }
        assert!((p.pos - other).length() >= 2.0 * PLAYER_RADIUS - 1e-9 || !can_stand(map, other));
        // Overlapping players can move apart.
        let back = Held {
            back: true,
            ..Held::default()
        };
        let q = step_pose(map, pose(start.x, start.y, 0.0), back, 0.1, &[start]);
        assert!(q.pos != start || !can_stand(map, start - Vec2::new(0.3, 0.0)));
    }

    #[test]
    fn spawn_points_avoid_taken_places() {
        let world = World::default_world();
        let map = &world.map;
        let a = spawn_point(map, &[]);
        let b = spawn_point(map, &[a]);
        let c = spawn_point(map, &[a, b]);
        assert_eq!(a, map.start.pos());
        assert!((a - b).length() >= 0.9 && (a - c).length() >= 0.9 && (b - c).length() >= 0.9);
        assert!(can_stand(map, b) && can_stand(map, c));
    }
}
