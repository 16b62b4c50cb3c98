//! Lamp light baked onto the map: how brightly the `LIGHT`s reach each point of the floor plan,
//! walls casting shadows. Built once per world; renderers read it per pixel when the world is
//! dark (night or `SHADE`), so lamps are islands of light.
//!
//! On maps with `Hz` heights light also depends on a surface point's height, so the bake keeps,
//! per sample, every lamp that reaches it (see [`crate::world::lamp_reach`]) and the level is
//! worked out per pixel from the height the pixel shows. A map without `Hz` lines keeps one
//! level per sample, exactly as before heights existed.

use crate::map::{LightDef, Map};
use crate::texture::texel_index;
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::lamp_falloff::{falloff, FULL};
use crate::world::lamp_reach::{LampReach, Reach};
use crate::world::ray::cast_ray_doors;

/// Samples per cell along each axis (read back with bilinear filtering).
const PER_CELL: usize = 4;

/// Lamp brightness over the map in 256ths, sampled [`PER_CELL`] times per cell on each axis.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LightMap {
    width: usize,
    height: usize,
    /// One level per sample (maps without heights).
    levels: Vec<u16>,
    /// The lamps reaching each sample (maps with heights); `None` on flat maps.
    reach: Option<Box<LampReach>>,
}

impl LightMap {
    /// Bakes `map`'s lights; walls block light, doorways let it through (doors as open). On a map
    /// with heights, floors and ceilings block it too and the level is left to [`LightMap::at_z`].
    #[must_use]
    pub fn build(map: &Map) -> Self {
        if map.lights.is_empty() {
            return Self::default();
        }
        let (width, height) = (map.width * PER_CELL, map.height * PER_CELL);
        let mut doors = DoorState::new(map);
        for cell in doors.cells().to_vec() {
            doors.set_open(cell, 1.0);
        }
        if map.has_heights() {
            let mut found = Vec::new();
            for (index, light) in map.lights.iter().enumerate() {
                bake_one(map, &doors, light, (width, height), |sample, d, p| {
                    found.push((sample, Reach::new(map, index, light, d, p)));
                });
            }
            let reach = LampReach::new(map, width * height, found);
            return Self {
                width,
                height,
                levels: Vec::new(),
                reach: Some(Box::new(reach)),
            };
        }
        let mut sum = vec![0.0f64; width * height];
        for light in &map.lights {
            bake_one(map, &doors, light, (width, height), |sample, d, _| {
                sum[sample] += light.strength * falloff(d, light.radius);
            });
        }
        let levels = sum
            .iter()
            .map(|&v| (v.min(1.0) * f64::from(FULL)).round() as u16)
            .collect();
        Self {
            width,
            height,
            levels,
            reach: None,
        }
    }

    /// Whether the map has no lights (renderers then skip every lookup).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.levels.is_empty() && self.reach.is_none()
    }

    /// Lamp brightness at `p` in 256ths (0 off the map or without lights), bilinear between
    /// samples. On a map with heights this is the light at height 0; surfaces there read
    /// [`LightMap::at_z`] at their own height.
    #[must_use]
    #[inline]
    pub fn at(&self, p: Vec2) -> u16 {
        if let Some(reach) = &self.reach {
            return self.blend(p, |i| reach.level(i, 0.0));
        }
        if self.levels.is_empty() {
            return 0;
        }
        self.blend(p, |i| self.levels[i])
    }

    /// Lamp brightness in 256ths at the surface point above `p` at height `z`: on a map with
    /// heights every lamp reaching the nearby samples is measured in 3-D; on a flat map this is
    /// [`LightMap::at`] (every point there lies within the lamps' own 0..1).
    #[must_use]
    #[inline]
    pub fn at_z(&self, p: Vec2, z: f64) -> u16 {
        match &self.reach {
            Some(reach) => self.blend(p, |i| reach.level(i, z)),
            None => self.at(p),
        }
    }

    /// The lamps reaching `p`, for reading many heights there (a face's rows): `probe(p).at(z)`
    /// equals `at_z(p, z)`, and costs nothing more where every nearby lamp shines fully.
    #[must_use]
    #[inline]
    pub fn probe(&self, p: Vec2) -> Probe<'_> {
        let Some(reach) = &self.reach else {
            return Probe::Level(self.at(p));
        };
        let k = PER_CELL as f64;
        let (sx, sy) = (p.x * k - 0.5, p.y * k - 0.5);
        let inside =
            sx >= 0.0 && sy >= 0.0 && sx < (self.width - 1) as f64 && sy < (self.height - 1) as f64;
        let (mut za, mut zb) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut corners = None;
        if inside {
            let (x0, y0) = (sx as usize, sy as usize);
            let fx = ((sx - x0 as f64) * 256.0) as u32;
            let fy = ((sy - y0 as f64) * 256.0) as u32;
            let i = y0 * self.width + x0;
            (za, zb) = (f64::NEG_INFINITY, f64::INFINITY);
            for j in [i, i + 1, i + self.width, i + self.width + 1] {
                let (a, b, _) = reach.range(j);
                (za, zb) = (za.max(a), zb.min(b));
            }
            corners = Some((i, fx, fy));
        }
        let level = if za <= zb {
            self.blend(p, |i| reach.range(i).2)
        } else {
            0
        };
        Probe::Heights {
            map: self,
            p,
            za,
            zb,
            level,
            corners,
        }
    }

    /// [`LightMap::at_z`], remembering the four samples it read in `corners`: a run of pixels
    /// over the same samples at one height (a floor's rows) measures them once.
    #[must_use]
    #[inline]
    pub fn at_z_cached(&self, p: Vec2, z: f64, corners: &mut Corners) -> u16 {
        let Some(reach) = &self.reach else {
            return self.at(p);
        };
        let k = PER_CELL as f64;
        let (sx, sy) = (p.x * k - 0.5, p.y * k - 0.5);
        let inside =
            sx >= 0.0 && sy >= 0.0 && sx < (self.width - 1) as f64 && sy < (self.height - 1) as f64;
        if !inside {
            return self.at_z(p, z);
        }
        let (x0, y0) = (texel_index(sx), texel_index(sy));
        let fx = ((sx - x0 as f64) * 256.0) as u32;
        let fy = ((sy - y0 as f64) * 256.0) as u32;
        let i = y0 * self.width + x0;
        if corners.sample != i || corners.z != z {
            let w = self.width;
            corners.levels = [
                reach.level(i, z),
                reach.level(i + 1, z),
                reach.level(i + w, z),
                reach.level(i + w + 1, z),
            ];
            (corners.sample, corners.z) = (i, z);
        }
        let l = |j: usize| u32::from(corners.levels[j]);
        let top = l(0) * (256 - fx) + l(1) * fx;
        let bottom = l(2) * (256 - fx) + l(3) * fx;
        ((top * (256 - fy) + bottom * fy + (1 << 15)) >> 16) as u16
    }

    /// Bilinear blend at `p` of the sample levels `level` gives.
    #[inline]
    fn blend(&self, p: Vec2, level: impl Fn(usize) -> u16) -> u16 {
        let k = PER_CELL as f64;
        let (sx, sy) = (p.x * k - 0.5, p.y * k - 0.5);
        let inside =
            sx >= 0.0 && sy >= 0.0 && sx < (self.width - 1) as f64 && sy < (self.height - 1) as f64;
        if !inside {
            return self.at_edge(sx, sy, level);
        }
        // Truncation is ⌊⌋ here (both positive) and avoids a libm call per floor pixel.
        let (x0, y0) = (texel_index(sx), texel_index(sy));
        let fx = ((sx - x0 as f64) * 256.0) as u32;
        let fy = ((sy - y0 as f64) * 256.0) as u32;
        let i = y0 * self.width + x0;
        let l = |j: usize| u32::from(level(j));
        let top = l(i) * (256 - fx) + l(i + 1) * fx;
        let bottom = l(i + self.width) * (256 - fx) + l(i + self.width + 1) * fx;
        ((top * (256 - fy) + bottom * fy + (1 << 15)) >> 16) as u16
    }

    /// [`LightMap::blend`] on the outer half-sample rim or off the map: samples clamped to the edge.
    #[cold]
    fn at_edge(&self, sx: f64, sy: f64, level: impl Fn(usize) -> u16) -> u16 {
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
            f64::from(level(y * self.width + x))
        };
        let top = sample(x0, y0) * (1.0 - fx) + sample(x0 + 1.0, y0) * fx;
        let bottom = sample(x0, y0 + 1.0) * (1.0 - fx) + sample(x0 + 1.0, y0 + 1.0) * fx;
        (top * (1.0 - fy) + bottom * fy).round() as u16
    }
}

/// The four sample levels [`LightMap::at_z_cached`] read last, and where and at what height.
#[derive(Debug, Clone, Copy)]
pub struct Corners {
    sample: usize,
    z: f64,
    levels: [u16; 4],
}

impl Default for Corners {
    fn default() -> Self {
        Self {
            sample: usize::MAX,
            z: f64::NAN,
            levels: [0; 4],
        }
    }
}

/// The lamp light at one map point, read at many heights (the rows of a face).
#[derive(Debug, Clone, Copy)]
pub enum Probe<'a> {
    /// A flat map: one level at every height.
    Level(u16),
    /// A map with heights: `level` between `za` and `zb`, else measured per height.
    Heights {
        /// The light map.
        map: &'a LightMap,
        /// The point on the floor plan.
        p: Vec2,
        /// Lowest height of the shared level.
        za: f64,
        /// Highest height of the shared level.
        zb: f64,
        /// The level every height from `za` to `zb` reads.
        level: u16,
        /// The first of the four samples around `p` and the weights between them (256ths),
        /// away from the map's rim.
        corners: Option<(usize, u32, u32)>,
    },
}

impl Probe<'_> {
    /// Lamp brightness in 256ths at height `z` above the probed point.
    #[must_use]
    #[inline]
    pub fn at(&self, z: f64) -> u16 {
        match *self {
            Probe::Level(l) => l,
            Probe::Heights {
                map,
                p,
                za,
                zb,
                level,
                corners,
            } => {
                if z >= za && z <= zb {
                    return level;
                }
                let (Some((i, fx, fy)), Some(reach)) = (corners, map.reach.as_deref()) else {
                    return map.at_z(p, z);
                };
                let w = map.width;
                let l = |j: usize| u32::from(reach.level(j, z));
                let top = l(i) * (256 - fx) + l(i + 1) * fx;
                let bottom = l(i + w) * (256 - fx) + l(i + w + 1) * fx;
                ((top * (256 - fy) + bottom * fy + (1 << 15)) >> 16) as u16
            }
        }
    }
}

/// Calls `reached(sample, distance, point)` for every sample `light` sees within its radius.
fn bake_one(
    map: &Map,
    doors: &DoorState,
    light: &LightDef,
    (width, height): (usize, usize),
    mut reached: impl FnMut(usize, f64, Vec2),
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
            reached(sy * width + sx, d, p);
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
            assert_eq!(m.at(p), m.at_edge(sx, sy, |i| m.levels[i]), "at {p:?}");
        }
        // Between samples the fixed-point path stays within a level of the exact blend.
        for i in 1..40 {
            let p = Vec2::new(0.3 + i as f64 * 0.16, 0.4 + i as f64 * 0.1);
            let (sx, sy) = (p.x * 4.0 - 0.5, p.y * 4.0 - 0.5);
            assert!(
                m.at(p).abs_diff(m.at_edge(sx, sy, |i| m.levels[i])) <= 1,
                "at {p:?}"
            );
        }
    }

    #[test]
    fn on_heights_maps_a_probe_reads_what_at_z_reads() {
        let text = "NO n\nSO s\nWE w\nEA e\nF 1,2,3\nC 4,5,6\nHp -1 3\nHb 2 3\n\
                    LIGHT 3.5,2.5 4 1\nLIGHT 5.2,1.7 3 0.7\n\
                    11111111\n1N0bbb01\n10ppbb01\n10pppb01\n11111111\n";
        let map = crate::map::parse_map("t.cub", text.as_bytes()).unwrap();
        let m = LightMap::build(&map);
        let mut lit_above = 0;
        for i in 0..60 {
            let p = Vec2::new(0.9 + i as f64 * 0.11, 1.05 + (i % 7) as f64 * 0.41);
            let probe = m.probe(p);
            for k in 0..30 {
                let z = -1.2 + k as f64 * 0.15;
                assert_eq!(probe.at(z), m.at_z(p, z), "at {p:?} z {z}");
                let mut corners = Corners::default();
                assert_eq!(m.at_z_cached(p, z, &mut corners), m.at_z(p, z));
                // Read again from the cache, and a neighbour over the same samples.
                assert_eq!(m.at_z_cached(p, z, &mut corners), m.at_z(p, z));
                let q = Vec2::new(p.x + 0.01, p.y);
                assert_eq!(m.at_z_cached(q, z, &mut corners), m.at_z(q, z));
                lit_above += usize::from(z > 2.0 && m.at_z(p, z) > 0);
            }
        }
        assert!(lit_above > 0);
        // A flat map's probe is its one level at every height.
        let flat = lit(ROOMS, &[(2.0, 2.0, 3.0)]);
        let p = Vec2::new(2.3, 2.2);
        assert_eq!(flat.probe(p).at(7.0), flat.at(p));
        assert_eq!(flat.at_z(p, -3.0), flat.at(p));
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
