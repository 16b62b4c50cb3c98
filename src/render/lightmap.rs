//! Lamp light baked onto the map: how brightly the `LIGHT`s reach each point of the floor plan,
//! walls casting shadows. Built once per world; renderers read it per pixel when the world is
//! dark (night or `SHADE`), so lamps are islands of light.

use crate::map::{LightDef, Map};
use crate::render::cast::cast_ray_doors;
use crate::vec2::Vec2;
use crate::world::door::DoorState;

/// Samples per cell along each axis (read back with bilinear filtering).
const PER_CELL: usize = 4;

/// Full brightness in the stored levels (256ths, like [`crate::render::light::Shade`]).
pub const FULL: u16 = 256;

/// Lamp brightness over the map in 256ths, sampled [`PER_CELL`] times per cell on each axis.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct LightMap {
    width: usize,
    height: usize,
    levels: Vec<u16>,
}

impl LightMap {
    /// Bakes `map`'s lights; walls block light, doorways let it through (doors as open).
    #[must_use]
    pub fn build(map: &Map) -> Self {
        if map.lights.is_empty() {
            return Self::default();
        }
        let (width, height) = (map.width * PER_CELL, map.height * PER_CELL);
        let mut sum = vec![0.0f64; width * height];
        let mut doors = DoorState::new(map);
        for cell in doors.cells().to_vec() {
            doors.set_open(cell, 1.0);
        }
        for light in &map.lights {
            bake_one(map, &doors, light, (width, height), &mut sum);
        }
        let levels = sum
            .iter()
            .map(|&v| (v.min(1.0) * f64::from(FULL)).round() as u16)
            .collect();
        Self {
            width,
            height,
            levels,
        }
    }

    /// Whether the map has no lights (renderers then skip every lookup).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.levels.is_empty()
    }

    /// Lamp brightness at `p` in 256ths (0 off the map or without lights), bilinear between samples.
    #[must_use]
    #[inline]
    pub fn at(&self, p: Vec2) -> u16 {
        if self.levels.is_empty() {
            return 0;
        }
        let k = PER_CELL as f64;
        let (sx, sy) = (p.x * k - 0.5, p.y * k - 0.5);
        let inside =
            sx >= 0.0 && sy >= 0.0 && sx < (self.width - 1) as f64 && sy < (self.height - 1) as f64;
        if !inside {
            return self.at_edge(sx, sy);
        }
        // Truncation is ⌊⌋ here (both positive) and avoids a libm call per floor pixel.
        let (x0, y0) = (sx as usize, sy as usize);
        let fx = ((sx - x0 as f64) * 256.0) as u32;
        let fy = ((sy - y0 as f64) * 256.0) as u32;
        let i = y0 * self.width + x0;
        let l = |j: usize| u32::from(self.levels[j]);
        let top = l(i) * (256 - fx) + l(i + 1) * fx;
        let bottom = l(i + self.width) * (256 - fx) + l(i + self.width + 1) * fx;
        ((top * (256 - fy) + bottom * fy + (1 << 15)) >> 16) as u16
    }

    /// [`LightMap::at`] on the outer half-sample rim or off the map: samples clamped to the edge.
    #[cold]
    fn at_edge(&self, sx: f64, sy: f64) -> u16 {
        if !(sx.is_finite() && sy.is_finite()) {
            return 0;
        }
        let (x0, y0) = (sx.floor(), sy.floor());
        let (fx, fy) = (sx - x0, sy - y0);
        let sample = |x: f64, y: f64| -> f64 {
            let (x, y) = (
                x.clamp(0.0, (self.width - 1) as f64) as usize,
                y.clamp(0.0, (self.height - 1) as f64) as usize,
            );
            f64::from(self.levels[y * self.width + x])
        };
        let top = sample(x0, y0) * (1.0 - fx) + sample(x0 + 1.0, y0) * fx;
        let bottom = sample(x0, y0 + 1.0) * (1.0 - fx) + sample(x0 + 1.0, y0 + 1.0) * fx;
        (top * (1.0 - fy) + bottom * fy).round() as u16
    }
}

/// How much of a light of `radius` reaches `d` cells away: full at the lamp, smoothly nothing
/// at the radius.
#[must_use]
pub fn falloff(d: f64, radius: f64) -> f64 {
    let t = (d / radius).clamp(0.0, 1.0);
    (1.0 - t * t).powi(2)
}

/// Adds one light's reach to every sample it can see within its radius.
fn bake_one(
    map: &Map,
    doors: &DoorState,
    light: &LightDef,
    (width, height): (usize, usize),
    sum: &mut [f64],
) {
    let k = PER_CELL as f64;
    let lo = |c: f64| ((c - light.radius) * k).floor().max(0.0) as usize;
    let hi = |c: f64, n: usize| (((c + light.radius) * k).ceil().max(0.0) as usize).min(n);
    for sy in lo(light.pos.y)..hi(light.pos.y, height) {
        for sx in lo(light.pos.x)..hi(light.pos.x, width) {
            let p = Vec2::new((sx as f64 + 0.5) / k, (sy as f64 + 0.5) / k);
            let d = (p - light.pos).length();
            if d >= light.radius || !visible(map, doors, light.pos, p, d) {
                continue;
            }
            sum[sy * width + sx] += light.strength * falloff(d, light.radius);
        }
    }
}

/// Whether the straight line from `from` reaches `to` (`d` apart) before a wall; a sample inside
/// a wall cell counts as seen when the wall it is in is the first thing hit (its lit face).
fn visible(map: &Map, doors: &DoorState, from: Vec2, to: Vec2, d: f64) -> bool {
    if d < 1e-9 {
        return true;
    }
    let dir = (to - from) * (1.0 / d);
    let hit = cast_ray_doors(map, doors, from, dir, |_| {});
    let cell = (to.x.floor() as i64, to.y.floor() as i64);
    hit.perp_dist >= d - 1e-9 || hit.cell == cell
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::grid_map;

    fn lit(grid: &str, lights: &[(f64, f64, f64)]) -> LightMap {
        let mut map = grid_map(grid);
        map.lights = lights
            .iter()
            .map(|&(x, y, radius)| LightDef {
                pos: Vec2::new(x, y),
                radius,
                strength: 1.0,
                at: (1, 1),
            })
            .collect();
        LightMap::build(&map)
    }

    const ROOMS: &str = "1111111\n1N01001\n1000001\n1001001\n1111111\n";

    #[test]
    fn falloff_is_full_at_the_lamp_and_nothing_at_its_radius() {
        assert_eq!(falloff(0.0, 3.0), 1.0);
        assert_eq!(falloff(3.0, 3.0), 0.0);
        assert_eq!(falloff(9.0, 3.0), 0.0);
        assert!(falloff(1.0, 3.0) > falloff(2.0, 3.0));
    }

    #[test]
    fn bright_near_dim_far_dark_beyond_the_radius() {
        let m = lit(ROOMS, &[(2.0, 2.0, 3.0)]);
        let near = m.at(Vec2::new(2.1, 2.1));
        let mid = m.at(Vec2::new(3.4, 2.0));
        assert!(near > 240, "{near}");
        assert!(mid > 40 && mid < near, "{mid}");
        assert_eq!(m.at(Vec2::new(5.5, 3.5)), 0);
    }

    #[test]
    fn walls_cast_shadows() {
        // The wall stub at (3, 1) hides cell (4, 1) from a lamp at (2.5, 1.5) looking east…
        let m = lit(ROOMS, &[(2.5, 1.5, 4.0)]);
        assert_eq!(m.at(Vec2::new(4.5, 1.5)), 0);
        // …but not (3, 2) below it, seen past the stub's corner.
        assert!(m.at(Vec2::new(3.6, 2.9)) > 0);
        // The stub's west face, toward the lamp, is lit.
        assert!(m.at(Vec2::new(2.99, 1.5)) > 100);
    }

    #[test]
    fn lights_add_up_and_saturate() {
        let one = lit(ROOMS, &[(2.0, 2.0, 3.0)]);
        let two = lit(ROOMS, &[(2.0, 2.0, 3.0), (3.0, 2.0, 3.0)]);
        let p = Vec2::new(2.5, 3.0);
        assert!(two.at(p) > one.at(p));
        assert!(two.at(Vec2::new(2.5, 2.0)) <= FULL);
    }

    #[test]
    fn inner_and_edge_lookups_agree_where_they_meet() {
        let m = lit(ROOMS, &[(1.5, 1.5, 6.0)]);
        // On the samples themselves both paths give the stored level.
        for (x, y) in [
            (0.125, 0.125),
            (1.375, 2.125),
            (6.875, 4.875),
            (3.625, 0.125),
        ] {
            let p = Vec2::new(x, y);
            let k = PER_CELL as f64;
            let (sx, sy) = (p.x * k - 0.5, p.y * k - 0.5);
            assert_eq!(m.at(p), m.at_edge(sx, sy), "at {p:?}");
        }
        // Between samples the fixed-point path stays within a level of the exact blend.
        for i in 1..40 {
            let p = Vec2::new(0.3 + i as f64 * 0.16, 0.4 + i as f64 * 0.1);
            let (sx, sy) = (p.x * 4.0 - 0.5, p.y * 4.0 - 0.5);
            assert!(m.at(p).abs_diff(m.at_edge(sx, sy)) <= 1, "at {p:?}");
        }
    }

    #[test]
    fn no_lights_no_map() {
        let m = lit(ROOMS, &[]);
        assert!(m.is_empty());
        assert_eq!(m.at(Vec2::new(2.0, 2.0)), 0);
        assert_eq!(
            lit(ROOMS, &[(2.0, 2.0, 3.0)]).at(Vec2::new(f64::NAN, 1.0)),
            0
        );
    }
}
