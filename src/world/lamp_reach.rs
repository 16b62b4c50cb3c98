//! Lamp light on maps with `Hz` heights: which lamps reach each light-map sample, and from which
//! heights there each is seen, so a pixel's level comes from its own height.
//!
//! The model. A lamp is a vertical segment of light from its cell's floor up one wall height
//! (clipped by the ceiling) — on a flat map that is 0..1, the whole open span, so every surface
//! point's distance to it is the 2-D one and nothing changes. A point at height z outside the
//! segment is `dz` above or below it and lies sqrt(d² + dz²) away.
//!
//! Occlusion. Walls block as on flat maps (the 2-D bake's ray; doors counted open). On top of
//! that the floors and ceilings crossed between lamp and sample block: walking the 2-D line from
//! the lamp (s = 0) to the sample (s = 1) cell by cell, a cell with floor f spanning s0..s1 lets
//! the straight line from the top of the lamp to the point (height z) pass only if it stays
//! above f over s0..s1, i.e. z ≥ top − (top − f)/s at both ends; likewise a ceiling c against
//! the line from the lamp's bottom (z ≤ bottom + (c − bottom)/s). So each (sample, lamp) keeps
//! one lowest and one highest height it lights (`zmin`, `zmax`): a lamp in a pit cannot light the
//! top of a ledge above it, a lamp on a balcony lights the hall floor beyond the balcony's edge
//! but not the floor hidden right under it. The approximation: floors are tested against the
//! lamp's top and ceilings against its bottom (the most generous ends of the segment), and the
//! test is made at the sample, not at the pixel (bilinear blending of the samples softens the
//! shadow edges, as with walls).

use crate::map::{LightDef, Map, Span};
use crate::vec2::Vec2;
use crate::world::lamp_falloff::falloff;

/// Slack on the height tests, so a floor exactly at a visibility limit stays lit.
const EPS: f64 = 1e-3;

/// One lamp's segment and strength as the per-pixel maths needs them.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Lamp {
    /// Bottom of the lit segment (its cell's floor).
    lo: f64,
    /// Top of the lit segment (one wall up, or its cell's ceiling if lower).
    hi: f64,
    /// 1 / radius².
    inv_r2: f64,
    /// Brightness at the lamp, 0–1.
    strength: f64,
}

impl Lamp {
    fn new(map: &Map, light: &LightDef) -> Self {
        let (lo, hi) = segment(map, light);
        Self {
            lo,
            hi,
            inv_r2: 1.0 / (light.radius * light.radius),
            strength: light.strength,
        }
    }
}

/// The heights a lamp shines from: its cell's floor up one wall height, clipped by the ceiling.
#[must_use]
pub fn segment(map: &Map, light: &LightDef) -> (f64, f64) {
    let span = map
        .span(light.pos.x.floor() as i64, light.pos.y.floor() as i64)
        .unwrap_or(Span::FLAT);
    (span.floor, span.ceil.min(span.floor + 1.0))
}

/// One lamp reaching one sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach {
    /// Its light at the sample within the segment's heights (strength · falloff of the 2-D
    /// distance, exactly what a flat map's bake adds).
    flat: f64,
    /// The 2-D distance squared.
    d2: f32,
    /// Lowest height at the sample the lamp sees (with slack).
    zmin: f32,
    /// Highest height at the sample the lamp sees (with slack).
    zmax: f32,
    /// Which lamp (index into the map's lights).
    lamp: u16,
}

impl Reach {
    /// Lamp `index` (`light`) seen from point `p` of the floor plan, `d` away in 2-D.
    #[must_use]
    pub fn new(map: &Map, index: usize, light: &LightDef, d: f64, p: Vec2) -> Self {
        let (lo, hi) = segment(map, light);
        let (zmin, zmax) = seen_heights(map, light.pos, p, lo, hi);
        Self {
            flat: light.strength * falloff(d, light.radius),
            d2: (d * d) as f32,
            zmin: (zmin - EPS) as f32,
            zmax: (zmax + EPS) as f32,
            lamp: index as u16,
        }
    }
}

/// The heights at `to` that a straight line from the segment `lo..hi` above `from` reaches
/// without passing below a floor or above a ceiling crossed on the way (see the module notes).
fn seen_heights(map: &Map, from: Vec2, to: Vec2, lo: f64, hi: f64) -> (f64, f64) {
    let (mut zmin, mut zmax) = (f64::NEG_INFINITY, f64::INFINITY);
    let d = to - from;
    let (mut i, mut j) = (from.x.floor() as i64, from.y.floor() as i64);
    let target = (to.x.floor() as i64, to.y.floor() as i64);
    let (step_i, step_j) = (
        if d.x < 0.0 { -1 } else { 1 },
        if d.y < 0.0 { -1 } else { 1 },
    );
    // Fraction of the way where the line leaves column i / row j.
    let exit_x = |i: i64| {
        if d.x == 0.0 {
            f64::INFINITY
        } else {
            (if d.x > 0.0 { i + 1 } else { i } as f64 - from.x) / d.x
        }
    };
    let exit_y = |j: i64| {
        if d.y == 0.0 {
            f64::INFINITY
        } else {
            (if d.y > 0.0 { j + 1 } else { j } as f64 - from.y) / d.y
        }
    };
    let mut s0 = 0.0;
    // A line of at most 2·16 cells each way crosses fewer than 70 cells.
    for _ in 0..80 {
        let (ex, ey) = (exit_x(i), exit_y(j));
        let done = (i, j) == target;
        let s1 = if done { 1.0 } else { ex.min(ey).min(1.0) };
        if let Some(span) = map.span(i, j) {
            for s in [s0, s1] {
                if s > 0.0 {
                    zmin = zmin.max(hi - (hi - span.floor) / s);
                    zmax = zmax.min(lo + (span.ceil - lo) / s);
                }
            }
        }
        if done || s1 >= 1.0 {
            break;
        }
        s0 = s1;
        if ex < ey {
            i += step_i;
        } else {
            j += step_j;
        }
    }
    (zmin, zmax)
}

/// A sample's lamps: the level shared by every height where all of them shine fully (the fast
/// path, read per pixel), and where its list of lamps is for the other heights.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Quick {
    /// Heights from `za` to `zb` see every lamp of the sample from inside its segment (rounded
    /// inward, so the fast path is never wrong; no lamps: every height).
    za: f32,
    /// See `za`.
    zb: f32,
    /// Index into the heads, `u32::MAX` for none.
    head: u32,
    /// The level between `za` and `zb`, in 256ths (what a flat map's bake stores).
    full: u16,
}

impl Quick {
    const NONE: Quick = Quick {
        za: f32::NEG_INFINITY,
        zb: f32::INFINITY,
        head: u32::MAX,
        full: 0,
    };
}

/// Where a sample's lamps are in the list.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Head {
    first: u32,
    count: u32,
}

/// Every sample's lamps on a map with heights.
#[derive(Debug, Clone, PartialEq)]
pub struct LampReach {
    lamps: Vec<Lamp>,
    quick: Vec<Quick>,
    heads: Vec<Head>,
    entries: Vec<Reach>,
}

impl LampReach {
    /// Gathers `found` (sample, reach) pairs, in the map's lamp order, over `samples` samples.
    #[must_use]
    pub fn new(map: &Map, samples: usize, mut found: Vec<(usize, Reach)>) -> Self {
        let lamps: Vec<Lamp> = map.lights.iter().map(|l| Lamp::new(map, l)).collect();
        // Stable: each sample keeps its lamps in the map's order (sums as a flat bake's).
        found.sort_by_key(|&(sample, _)| sample);
        let mut quick = vec![Quick::NONE; samples];
        let mut heads: Vec<Head> = Vec::new();
        let mut ranges: Vec<(f64, f64)> = Vec::new();
        let mut entries = Vec::with_capacity(found.len());
        for (sample, reach) in found {
            if quick[sample].head == u32::MAX {
                quick[sample].head = heads.len() as u32;
                heads.push(Head {
                    first: entries.len() as u32,
                    count: 0,
                });
                ranges.push((f64::NEG_INFINITY, f64::INFINITY));
            }
            let lamp = &lamps[usize::from(reach.lamp)];
            let range = ranges.last_mut().expect("pushed above");
            range.0 = range.0.max(lamp.lo.max(f64::from(reach.zmin)));
            range.1 = range.1.min(lamp.hi.min(f64::from(reach.zmax)));
            heads.last_mut().expect("pushed above").count += 1;
            entries.push(reach);
        }
        for q in &mut quick {
            let Some(head) = heads.get(q.head as usize) else {
                continue;
            };
            let (za, zb) = ranges[q.head as usize];
            let list = &entries[head.first as usize..][..head.count as usize];
            q.full = quantize(list.iter().fold(0.0, |s, e| s + e.flat));
            // Inward by more than an f32 step at these heights.
            (q.za, q.zb) = ((za + 1e-5) as f32, (zb - 1e-5) as f32);
        }
        Self {
            lamps,
            quick,
            heads,
            entries,
        }
    }

    /// The light at sample `i` on a surface at height `z`, in 256ths.
    #[must_use]
    #[inline]
    pub fn level(&self, i: usize, z: f64) -> u16 {
        let q = &self.quick[i];
        if z >= f64::from(q.za) && z <= f64::from(q.zb) {
            return q.full;
        }
        self.measure(q.head, z)
    }

    /// The heights at sample `i` that all read one level, and that level.
    #[must_use]
    #[inline]
    pub fn range(&self, i: usize) -> (f64, f64, u16) {
        let q = &self.quick[i];
        (f64::from(q.za), f64::from(q.zb), q.full)
    }

    /// [`LampReach::level`] lamp by lamp, for a height outside the sample's fast range.
    fn measure(&self, head: u32, z: f64) -> u16 {
        let Some(head) = self.heads.get(head as usize) else {
            return 0;
        };
        let zf = z as f32;
        let mut sum = 0.0;
        for e in &self.entries[head.first as usize..][..head.count as usize] {
            if zf < e.zmin || zf > e.zmax {
                continue;
            }
            let lamp = &self.lamps[usize::from(e.lamp)];
            let dz = (lamp.lo - z).max(z - lamp.hi);
            if dz <= 0.0 {
                sum += e.flat;
                continue;
            }
            let t2 = (f64::from(e.d2) + dz * dz) * lamp.inv_r2;
            if t2 < 1.0 {
                sum += lamp.strength * (1.0 - t2) * (1.0 - t2);
            }
        }
        // Rounded by adding ½ (sum ≥ 0): `f64::round` is a libm call here.
        (sum.min(1.0) * f64::from(crate::world::lamp_falloff::FULL) + 0.5) as u16
    }
}

/// A summed light in 256ths, saturating at full (the flat bake's rounding).
fn quantize(sum: f64) -> u16 {
    (sum.min(1.0) * f64::from(crate::world::lamp_falloff::FULL)).round() as u16
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::parse_map;

    fn map(extra: &str, grid: &str) -> Map {
        let text = format!("NO n\nSO s\nWE w\nEA e\nF 1,2,3\nC 4,5,6\n{extra}{grid}");
        parse_map("t.cub", text.as_bytes()).unwrap()
    }

    #[test]
    fn a_lamp_in_a_pit_sees_the_pit_but_not_the_top_of_the_ledge_above_it() {
        // Pit p (floor −1, ceiling 3) beside a ledge b (floor 2); the lamp's segment is −1..0.
        let m = map("Hp -1 3\nHb 2 3\n", "111111\n1Nppbb1\n111111\n");
        let light = LightDef {
            pos: Vec2::new(2.5, 1.5),
            radius: 4.0,
            strength: 1.0,
            at: (1, 1),
        };
        assert_eq!(segment(&m, &light), (-1.0, 0.0));
        let (zmin, _) = seen_heights(&m, light.pos, Vec2::new(3.5, 1.5), -1.0, 0.0);
        assert!(zmin <= -1.0, "pit floor hidden: {zmin}");
        let (zmin, _) = seen_heights(&m, light.pos, Vec2::new(4.6, 1.5), -1.0, 0.0);
        assert!(zmin > 2.0, "ledge top lit from below: {zmin}");
    }

    #[test]
    fn a_lamp_on_a_balcony_lights_the_floor_beyond_its_edge_not_under_it() {
        // Balcony b (floor 1, ceiling 3) then a hall h (0..3); lamp segment 1..2.
        let m = map("Hb 1 3\nHh 0 3\n", "11111111\n1Nbhhhh1\n11111111\n");
        let from = Vec2::new(2.5, 1.5);
        // Right past the edge the floor (0) is hidden under the balcony's lip…
        let (near, _) = seen_heights(&m, from, Vec2::new(3.1, 1.5), 1.0, 2.0);
        assert!(near > 0.0, "{near}");
        // …farther out the light clears the edge and reaches the floor.
        let (far, _) = seen_heights(&m, from, Vec2::new(5.5, 1.5), 1.0, 2.0);
        assert!(far <= 0.0, "{far}");
    }

    #[test]
    fn on_flat_cells_every_height_of_the_span_is_seen() {
        let m = map("Hz 0 1\n", "111111\n1N00z1\n111111\n");
        let (zmin, zmax) = seen_heights(&m, Vec2::new(1.3, 1.4), Vec2::new(4.8, 1.9), 0.0, 1.0);
        assert!(zmin <= 0.0 && zmax >= 1.0, "{zmin} {zmax}");
    }
}
