//! Light by distance: shading, fog and night, precomputed into a table so pixels never call `exp`.
//!
//! Permadi's recipe: intensity falls with distance and converges to a "target colour" (black for
//! darkness, grey or white for fog). Each table entry says how a colour seen at that distance is
//! scaled and what is added: `out = c · mul / 256 + add`.

use crate::color::Rgb;

pub use crate::map::Fog;

/// The light of a frame; the default (no fog, day, no falloff) leaves every colour unchanged.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Lighting {
    /// Distance fog, if any.
    pub fog: Option<Fog>,
    /// Dark world lit only near the player (a lantern), as in Permadi's night effect.
    pub night: bool,
    /// Plain distance darkening: brightness = 1 / (1 + falloff · distance); 0 = off.
    pub falloff: f64,
}

impl crate::world::World {
    /// The light the map asks for: its `FOG` and `SHADE` lines (day, no night).
    #[must_use]
    pub fn lighting(&self) -> Lighting {
        Lighting {
            fog: self.map.fog,
            night: false,
            falloff: self.map.shade.unwrap_or(0.0),
        }
    }
}

/// Distance at which night light has fallen to half, in cells.
pub const NIGHT_RADIUS: f64 = 2.5;

/// The least light at night, so far walls are dim shapes, not pure black.
pub const NIGHT_AMBIENT: f64 = 0.05;

/// Table resolution: entries per cell of distance.
const STEPS_PER_CELL: f64 = 8.0;

/// Table length; distances beyond `LEN / STEPS_PER_CELL` (64 cells) use the last entry.
const LEN: usize = 512;

impl Lighting {
    /// Brightness in [0, 1] at `dist` (before fog).
    #[must_use]
    pub fn brightness(&self, dist: f64) -> f64 {
        let mut b = 1.0 / (1.0 + self.falloff.max(0.0) * dist);
        if self.night {
            let r = dist / NIGHT_RADIUS;
            b *= (1.0 / (1.0 + r * r)).max(NIGHT_AMBIENT);
        }
        b
    }

    /// How much of the fog colour replaces the surface colour at `dist`, in [0, 1].
    #[must_use]
    pub fn fog_amount(&self, dist: f64) -> f64 {
        self.fog
            .map_or(0.0, |f| 1.0 - (-f.density.max(0.0) * dist).exp())
    }

    /// Whether surfaces are darker than fog alone makes them (night or falloff), so lamps show.
    #[must_use]
    pub fn is_dark(&self) -> bool {
        self.night || self.falloff > 0.0
    }

    /// Whether every colour passes unchanged (lets renderers skip the table).
    #[must_use]
    pub fn is_neutral(&self) -> bool {
        self.fog.is_none_or(|f| f.density <= 0.0) && !self.night && self.falloff <= 0.0
    }
}

/// One table entry: `out = c · mul / 256 + add` per channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shade {
    /// Surface brightness in 256ths.
    pub mul: u16,
    /// Fog colour already weighted by the fog amount, per channel.
    pub add: [u16; 3],
    /// The surface's share left after fog, in 256ths: the most any light can bring back.
    pub keep: u16,
}

impl Shade {
    /// No change.
    pub const IDENTITY: Shade = Shade {
        mul: 256,
        add: [0; 3],
        keep: 256,
    };

    /// Applies the entry to a colour (integer maths, the per-pixel cost of lighting).
    #[must_use]
    #[inline]
    pub fn apply(self, c: Rgb) -> Rgb {
        let ch = |v: u8, a: u16| {
            (((u32::from(v) * u32::from(self.mul)) >> 8) + u32::from(a)).min(255) as u8
        };
        Rgb::new(
            ch(c.r, self.add[0]),
            ch(c.g, self.add[1]),
            ch(c.b, self.add[2]),
        )
    }

    /// This entry with the surface colour further scaled by `k`/256 (side shading), fog unchanged.
    #[must_use]
    #[inline]
    pub fn scaled(self, k: u16) -> Shade {
        let by_k = |v: u16| ((u32::from(v) * u32::from(k)) >> 8) as u16;
        Shade {
            mul: by_k(self.mul),
            add: self.add,
            keep: by_k(self.keep),
        }
    }

    /// This entry where lamps shine `lamp`/256 on the surface: the brighter of the two lights
    /// wins, still seen through the same fog.
    #[must_use]
    #[inline]
    pub fn lit(self, lamp: u16) -> Shade {
        let by_lamp = ((u32::from(lamp) * u32::from(self.keep)) >> 8) as u16;
        Shade {
            mul: self.mul.max(by_lamp),
            ..self
        }
    }
}

/// [`Lighting`] sampled every 1/8 cell out to 64 cells; a framebuffer keeps it while the light stays.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ShadeTable {
    entries: Box<[Shade; LEN]>,
}

impl ShadeTable {
    /// Samples `light` at the centre of each distance step.
    #[must_use]
    pub fn new(light: &Lighting) -> Self {
        let mut entries = Box::new([Shade::IDENTITY; LEN]);
        if !light.is_neutral() {
            let fog = light.fog.map_or(Rgb::default(), |f| f.colour);
            for (i, e) in entries.iter_mut().enumerate() {
                let d = (i as f64 + 0.5) / STEPS_PER_CELL;
                let f = light.fog_amount(d);
                let b = light.brightness(d) * (1.0 - f);
                let add = |c: u8| (f64::from(c) * f).round() as u16;
                *e = Shade {
                    mul: (b * 256.0).round() as u16,
                    add: [add(fog.r), add(fog.g), add(fog.b)],
                    keep: ((1.0 - f) * 256.0).round() as u16,
                };
            }
        }
        Self { entries }
    }

    /// The entry for distance `dist` (negative or NaN reads as 0, far beyond as the last entry).
    #[must_use]
    #[inline]
    pub fn at(&self, dist: f64) -> Shade {
        let i = (dist * STEPS_PER_CELL) as usize;
        self.entries[i.min(LEN - 1)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neutral_light_is_the_identity_everywhere() {
        let t = ShadeTable::new(&Lighting::default());
        let c = Rgb::new(200, 10, 99);
        for d in [0.0, 1.0, 33.3, 1e9, -1.0, f64::NAN] {
            assert_eq!(t.at(d).apply(c), c);
        }
    }

    #[test]
    fn fog_converges_to_its_colour() {
        let light = Lighting {
            fog: Some(Fog {
                colour: Rgb::new(100, 120, 140),
                density: 0.5,
            }),
            ..Lighting::default()
        };
        let t = ShadeTable::new(&light);
        let c = Rgb::new(255, 0, 0);
        let near = t.at(0.0).apply(c);
        let far = t.at(1000.0).apply(c);
        assert!(near.r > 240 && near.g < 10, "{near:?}");
        assert!(
            far.r.abs_diff(100) <= 1 && far.b.abs_diff(140) <= 1,
            "{far:?}"
        );
        let mid = t.at(2.0).apply(c);
        let expect = 255.0 * (-1.0f64).exp() + 100.0 * (1.0 - (-1.0f64).exp());
        assert!(
            (f64::from(mid.r) - expect).abs() < 4.0,
            "{mid:?} vs {expect}"
        );
    }

    #[test]
    fn night_is_bright_near_and_dark_far() {
        let light = Lighting {
            night: true,
            ..Lighting::default()
        };
        let t = ShadeTable::new(&light);
        let c = Rgb::new(200, 200, 200);
        assert!(t.at(0.2).apply(c).r > 190);
        assert!(t.at(20.0).apply(c).r < 15);
        assert!(light.brightness(1.0) > light.brightness(2.0));
    }

    #[test]
    fn side_scaling_keeps_fog_additive_part() {
        let s = Shade {
            mul: 128,
            add: [10, 20, 30],
            keep: 200,
        };
        assert_eq!(
            s.scaled(128),
            Shade {
                mul: 64,
                add: [10, 20, 30],
                keep: 100,
            }
        );
        assert_eq!(
            Shade::IDENTITY.scaled(184).apply(Rgb::new(100, 0, 0)),
            Rgb::new(100, 0, 0).scaled(184)
        );
    }

    #[test]
    fn lamps_brighten_dark_surfaces_up_to_what_fog_leaves() {
        let light = Lighting {
            night: true,
            fog: Some(Fog {
                colour: Rgb::new(0, 0, 0),
                density: 0.1,
            }),
            ..Lighting::default()
        };
        let t = ShadeTable::new(&light);
        let far = t.at(10.0);
        let c = Rgb::new(200, 200, 200);
        assert!(far.apply(c).r < 10);
        // A full lamp gives back what fog leaves at that distance (e^-1 of the colour).
        let lit = far.lit(256).apply(c);
        let expect = 200.0 * (-1.0f64).exp();
        assert!(
            (f64::from(lit.r) - expect).abs() < 3.0,
            "{lit:?} vs {expect}"
        );
        // A lamp dimmer than the lantern changes nothing.
        let near = t.at(0.1);
        assert_eq!(near.lit(10), near);
        assert!(light.is_dark() && !Lighting::default().is_dark());
    }
}
