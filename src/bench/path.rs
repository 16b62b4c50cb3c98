//! Fixed camera paths on the default map, so every bench run replays the same frames.

use crate::camera::{Camera, DEFAULT_FOV_DEG};
use crate::map::Map;
use crate::vec2::Vec2;

/// A named camera path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BenchScene {
    /// Turning on the spot at the start, 3° a frame: every column changes every frame.
    Turn,
    /// Walking east along the start row (east of its door) with a gentle sway.
    Walk,
    /// Walking through the flat-coloured zone `a` in the south-west room.
    Flat,
}

impl BenchScene {
    /// Every scene the default bench runs.
    pub const ALL: [BenchScene; 3] = [BenchScene::Turn, BenchScene::Walk, BenchScene::Flat];

    /// The name in the bench JSON.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            BenchScene::Turn => "turn",
            BenchScene::Walk => "walk",
            BenchScene::Flat => "flat",
        }
    }
}

/// `frames` camera poses along `scene`'s path; every position is a walkable cell of `map`.
///
/// # Panics
/// If the path leaves the walkable area (only possible with a map other than the default).
#[must_use]
pub fn camera_path(map: &Map, scene: BenchScene, frames: usize) -> Vec<Camera> {
    let start = map.start.pos();
    (0..frames)
        .map(|i| {
            let t = i as f64;
            let (pos, angle) = match scene {
                BenchScene::Turn => (start, map.start.angle_deg() + 3.0 * t),
                BenchScene::Walk => {
                    let x = 12.2 + 14.0 * t / frames.max(1) as f64;
                    (Vec2::new(x, 5.5), 12.0 * (t / 15.0).sin())
                }
                BenchScene::Flat => {
                    let x = 2.6 + 18.0 * t / frames.max(1) as f64;
                    (Vec2::new(x, 20.4), 8.0 + 20.0 * (t / 25.0).sin())
                }
            };
            assert!(
                map.is_walkable(pos),
                "bench path leaves the floor at {pos:?}"
            );
            Camera::from_angle(pos, angle, DEFAULT_FOV_DEG)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::World;

    #[test]
    fn every_path_stays_on_the_default_maps_floor() {
        let world = World::default_world();
        for scene in BenchScene::ALL {
            let path = camera_path(&world.map, scene, 300);
            assert_eq!(path.len(), 300);
            assert!(path.iter().all(|c| world.map.is_walkable(c.pos)));
        }
    }
}
