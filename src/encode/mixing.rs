//! Per-pixel palette mixes read from one lookup table shared by every encoder and SSH session.
//!
//! Each colour is shown as palette entry `a`, or `b` on a share of its pixels (in sixteenths),
//! chosen to look right to a person at a terminal (see `docs/colour.md`): at a normal seat the eye
//! resolves single half-block pixels in lightness but blurs colour over a few, so `a` and `b` are
//! kept close to the colour in lightness (each pixel's own error is what shows) and their mix
//! carries its hue and chroma. Which pixels show `b` is decided by a threshold per pixel tied to the
//! surface it shows ([`crate::render::dither_phase`]), or, where no surface wrote one, by the
//! pixel's half of its cell — never by where the cell is on screen.
//!
//! The answer depends on the colour only, so it is computed once per colour bin, on first use, and
//! kept in a table of atomics: no lock, and every session shares the work.

use std::sync::atomic::{AtomicU32, Ordering};

use crate::color::Rgb;

/// Bits per channel of the table index (64³ bins of 4×4×4 sRGB values: 1 MiB).
const BITS: u32 = 6;

/// An empty table slot (no mix packs to this: shares stop at 16).
const EMPTY: u32 = u32::MAX;

/// Steps of a share: thresholds and shares are in sixteenths.
pub const SHARES: u8 = 16;

/// A colour's mix: entry `a`, and entry `b` on `share` sixteenths of the pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mix {
    /// The entry most pixels show.
    pub a: u8,
    /// The entry shown where a pixel's threshold is below `share`.
    pub b: u8,
    /// Sixteenths of pixels that show `b` (0 = all `a`).
    pub share: u8,
}

impl Mix {
    /// The entry a pixel with threshold `t` (0–15) shows.
    #[must_use]
    #[inline]
    pub fn pick(self, t: u8) -> u8 {
        if t < self.share {
            self.b
        } else {
            self.a
        }
    }

    fn pack(self) -> u32 {
        u32::from(self.a) | (u32::from(self.b) << 8) | (u32::from(self.share) << 16)
    }

    fn unpack(v: u32) -> Self {
        Self {
            a: v as u8,
            b: (v >> 8) as u8,
            share: (v >> 16) as u8,
        }
    }
}

/// How a mix is judged: weights of squared CIELAB errors, per pixel (what the eye resolves) and
/// of the mix (what it blurs), lightness apart from chroma.
#[derive(Debug, Clone, Copy)]
pub struct Weights {
    /// Each pixel's own lightness error.
    pub pixel_l: f32,
    /// Each pixel's own a/b (hue and chroma) error.
    pub pixel_ab: f32,
    /// The mix's lightness error.
    pub mix_l: f32,
    /// The mix's a/b error.
    pub mix_ab: f32,
    /// Palette entries nearest the colour among which `a` and `b` are sought.
    pub candidates: usize,
    /// Weight of a/b against lightness in that nearness: low, so entries of about the same
    /// lightness in many hues are candidates (what a mix that keeps lightness per pixel needs).
    pub candidate_ab: f32,
    /// Extra cost of a share of a half (uniform runs of cells on a surface: few colour changes).
    pub half_cost: f32,
    /// Extra cost of any other share but none or all (a colour change every cell or two).
    pub fine_cost: f32,
}

/// A palette entry as the search reads it.
#[derive(Debug, Clone, Copy)]
struct Entry {
    index: u8,
    lin: [f32; 3],
    lab: [f32; 3],
}

/// The shared table of one palette: entries and the lazily filled bins.
#[derive(Debug)]
pub struct MixTable {
    entries: Vec<Entry>,
    weights: Weights,
    /// The shares (sixteenths) a mix may use.
    shares: &'static [u8],
    bins: Vec<AtomicU32>,
}

/// Every share: for pixels whose thresholds come from a surface's 4×4 pattern.
pub const FINE_SHARES: [u8; 17] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16];

/// None, half or all: for cells whose two pixels are each other's only pattern.
pub const HALF_SHARES: [u8; 3] = [0, 8, 16];

/// How 256-colour mixes are judged (see `docs/colour.md` for the figures behind them).
pub const MIX_256: Weights = Weights {
    pixel_l: 1.0,
    pixel_ab: 0.05,
    mix_l: 1.0,
    mix_ab: 2.0,
    candidates: 16,
    candidate_ab: 0.1,
    half_cost: 3.0,
    fine_cost: 8.0,
};

/// How 16-colour mixes are judged.
pub const MIX_16: Weights = Weights {
    pixel_l: 1.0,
    pixel_ab: 0.05,
    mix_l: 0.3,
    mix_ab: 2.0,
    candidates: 16,
    candidate_ab: 1.0,
    half_cost: 0.0,
    fine_cost: 0.0,
};

/// An sRGB value (0–255, fractional allowed) in linear light.
fn to_linear(v: f32) -> f32 {
    let a = v / 255.0;
    if a <= 0.040_45 {
        a / 12.92
    } else {
        ((a + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear sRGB → CIELAB (D65).
#[must_use]
pub fn lab(l: [f32; 3]) -> [f32; 3] {
    const M: [[f32; 3]; 3] = [
        [0.4124, 0.3576, 0.1805],
        [0.2126, 0.7152, 0.0722],
        [0.0193, 0.1192, 0.9505],
    ];
    let xyz = M.map(|row| row[0] * l[0] + row[1] * l[1] + row[2] * l[2]);
    let white = M.map(|row| row[0] + row[1] + row[2]);
    let f = |t: f32| {
        if t > 0.008_856 {
            t.max(0.0).cbrt()
        } else {
            t / 0.128_418 + 4.0 / 29.0
        }
    };
    let (fx, fy, fz) = (
        f(xyz[0] / white[0]),
        f(xyz[1] / white[1]),
        f(xyz[2] / white[2]),
    );
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

impl MixTable {
    /// The table for palette entries `indices` whose colours are `rgb(i)`, judged by `weights`,
    /// with mixes of `shares` sixteenths.
    #[must_use]
    pub fn new(
        indices: &[u8],
        rgb: impl Fn(u8) -> Rgb,
        weights: Weights,
        shares: &'static [u8],
    ) -> Self {
        let entries = indices
            .iter()
            .map(|&index| {
                let c = rgb(index);
                let lin = [c.r, c.g, c.b].map(|v| to_linear(f32::from(v)));
                Entry {
                    index,
                    lin,
                    lab: lab(lin),
                }
            })
            .collect();
        let n = 1usize << (3 * BITS);
        Self {
            entries,
            weights,
            shares,
            bins: (0..n).map(|_| AtomicU32::new(EMPTY)).collect(),
        }
    }

    /// The mix of colour `c` (from the table, or worked out and stored on first use).
    #[must_use]
    #[inline]
    pub fn mix(&self, c: Rgb) -> Mix {
        let shift = 8 - BITS;
        let k = (usize::from(c.r >> shift) << (2 * BITS))
            | (usize::from(c.g >> shift) << BITS)
            | usize::from(c.b >> shift);
        let v = self.bins[k].load(Ordering::Relaxed);
        if v != EMPTY {
            return Mix::unpack(v);
        }
        // The bin's centre: every colour in it gets the same answer, whoever asks first.
        let half = f32::from(1u8 << shift) / 2.0 - 0.5;
        let centre = [c.r, c.g, c.b].map(|v| f32::from(v >> shift << shift) + half);
        let m = self.solve(centre);
        self.bins[k].store(m.pack(), Ordering::Relaxed);
        m
    }

    /// The best mix for an sRGB colour (channels 0–255): among the [`Weights::candidates`]
    /// entries nearest it, the pair and share with the least weighted error (first found on
    /// ties, so the answer is deterministic).
    fn solve(&self, srgb: [f32; 3]) -> Mix {
        let w = self.weights;
        let lin = srgb.map(to_linear);
        let target = lab(lin);
        let d2 = |a: [f32; 3]| {
            let (dl, da, db) = (a[0] - target[0], a[1] - target[1], a[2] - target[2]);
            (dl * dl, da * da + db * db)
        };
        let mut near: Vec<(f32, usize)> = self
            .entries
            .iter()
            .enumerate()
            .map(|(i, e)| {
                let (l, ab) = d2(e.lab);
                (l + w.candidate_ab * ab, i)
            })
            .collect();
        near.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        near.truncate(w.candidates.max(1));
        let pixel = |e: &Entry| {
            let (l, ab) = d2(e.lab);
            w.pixel_l * l + w.pixel_ab * ab
        };
        let first = &self.entries[near[0].1];
        let mut best = (
            pixel(first) + {
                let (l, ab) = d2(first.lab);
                w.mix_l * l + w.mix_ab * ab
            },
            Mix {
                a: first.index,
                b: first.index,
                share: 0,
            },
        );
        for (i, &(_, ia)) in near.iter().enumerate() {
            let ea = &self.entries[ia];
            let pa = pixel(ea);
            for &(_, ib) in &near[i + 1..] {
                let eb = &self.entries[ib];
                let pb = pixel(eb);
                for &share in self.shares {
                    let s = f32::from(share) / f32::from(SHARES);
                    let mixed = lab([0, 1, 2].map(|k| ea.lin[k] + s * (eb.lin[k] - ea.lin[k])));
                    let (l, ab) = d2(mixed);
                    let bytes = match share % SHARES {
                        0 => 0.0,
                        8 => w.half_cost,
                        _ => w.fine_cost,
                    };
                    let cost = (1.0 - s) * pa + s * pb + w.mix_l * l + w.mix_ab * ab + bytes;
                    if cost < best.0 {
                        best = (
                            cost,
                            Mix {
                                a: ea.index,
                                b: eb.index,
                                share,
                            },
                        );
                    }
                }
            }
        }
        let m = best.1;
        // One entry shown whole is one entry, not a mix (fewer colour changes on the wire).
        match m.share {
            0 => Mix { b: m.a, ..m },
            SHARES => Mix {
                a: m.b,
                share: 0,
                ..m
            },
            _ => m,
        }
    }
}
