//! The search behind the shipped mix tables ([`super::mix_table`]): for a colour, the pair of
//! palette entries and the share of the second that look closest to it to a person at a terminal
//! (see `docs/colour.md` and [`super::mixing`]). It runs ahead of time only, so it is built for the
//! tests: one writes the tables (`cargo test --release --lib -- --ignored write_mix_tables`), one
//! checks the shipped ones against it.

use super::level::ColorLevel;
use super::mix_table::{entries, shipped, MixTable};
use super::mixing::{Mix, BINS, BITS, SHARES};
use super::palette::xterm_rgb;
use crate::color::Rgb;

/// The sRGB colour (channels 0–255, fractional) at the centre of bin `k`: every colour in the bin
/// gets its answer.
#[must_use]
pub fn bin_centre(k: usize) -> [f32; 3] {
    let shift = 8 - BITS;
    let half = f32::from(1u8 << shift) / 2.0 - 0.5;
    let side = (1usize << BITS) - 1;
    [2 * BITS, BITS, 0].map(|s| (((k >> s) & side) << shift) as f32 + half)
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
    /// Weight of the a/b distance between the two entries across the colour's chroma direction
    /// (all of it for a grey), squared, times s·(1−s): two hues side by side read as confetti,
    /// one hue at two chromas as texture, so only the first is charged.
    pub pair_hue: f32,
}

/// A palette entry as the search reads it.
#[derive(Debug, Clone, Copy)]
struct Entry {
    index: u8,
    lin: [f32; 3],
    lab: [f32; 3],
}

/// Works out mixes for one palette: its entries, and the linear-light mix of every pair at every
/// share (the same for any colour, so computed once).
#[derive(Debug)]
pub struct Solver {
    entries: Vec<Entry>,
    weights: Weights,
    /// The shares (sixteenths) a mix may use.
    shares: &'static [u8],
    /// CIELAB of entry i mixed with entry j at share k: `[(i * n + j) * shares + k]`.
    mixed: Vec<[f32; 3]>,
}

/// Every share: for pixels whose thresholds come from a surface's 4×4 pattern.
pub const FINE_SHARES: [u8; 17] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16];

/// None, half or all: for cells whose two pixels are each other's only pattern.
pub const HALF_SHARES: [u8; 3] = [0, 8, 16];

/// How 256-colour mixes are judged (see `docs/colour.md` for the figures behind them).
pub const MIX_256: Weights = Weights {
    pixel_l: 1.3,
    pixel_ab: 0.0,
    mix_l: 0.3,
    mix_ab: 2.0,
    candidates: 32,
    candidate_ab: 0.1,
    half_cost: 3.0,
    fine_cost: 8.0,
    pair_hue: 1.0,
};

/// How 256-colour mixes are judged where no surface wrote thresholds (floors, ceilings, frames
/// from elsewhere): as [`MIX_256`], but each pixel's own a/b error counts too. There a half share
/// shows as alternate pixel rows fixed to the screen, and two entries far apart in colour (grey
/// and orange for a warm floor) drew stripes a person sees at once; the charge keeps a half mix
/// to entries near the colour.
pub const MIX_256_HALVES: Weights = Weights {
    pixel_ab: 0.2,
    ..MIX_256
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
    pair_hue: 0.0,
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

impl Solver {
    /// The solver for palette entries `indices` whose colours are `rgb(i)`, judged by `weights`,
    /// with mixes of `shares` sixteenths.
    #[must_use]
    pub fn new(
        indices: &[u8],
        rgb: impl Fn(u8) -> Rgb,
        weights: Weights,
        shares: &'static [u8],
    ) -> Self {
        let entries: Vec<Entry> = indices
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
        let mut mixed = Vec::with_capacity(entries.len() * entries.len() * shares.len());
        for ea in &entries {
            for eb in &entries {
                for &share in shares {
                    let s = f32::from(share) / f32::from(SHARES);
                    mixed.push(lab(
                        [0, 1, 2].map(|k| ea.lin[k] + s * (eb.lin[k] - ea.lin[k]))
                    ));
                }
            }
        }
        Self {
            entries,
            weights,
            shares,
            mixed,
        }
    }

    /// The answer for every bin, packed ([`Mix::pack`]), in bin order; `threads` share the work.
    #[must_use]
    pub fn table(&self, threads: usize) -> Vec<u32> {
        let mut out = vec![0u32; BINS];
        let chunk = BINS.div_ceil(threads.max(1));
        std::thread::scope(|scope| {
            for (i, part) in out.chunks_mut(chunk).enumerate() {
                scope.spawn(move || {
                    for (j, v) in part.iter_mut().enumerate() {
                        *v = self.solve(bin_centre(i * chunk + j)).pack();
                    }
                });
            }
        });
        out
    }

    /// The best mix for an sRGB colour (channels 0–255): among the [`Weights::candidates`]
    /// entries nearest it, the pair and share with the least weighted error (first found on
    /// ties, so the answer is deterministic).
    #[must_use]
    pub fn solve(&self, srgb: [f32; 3]) -> Mix {
        self.search(srgb).1
    }

    /// What [`Solver::solve`] minimises, for mix `m` of colour `srgb` (`None` when `m` holds an
    /// entry or share this solver does not use).
    #[must_use]
    pub fn cost(&self, srgb: [f32; 3], m: Mix) -> Option<f32> {
        let find = |index: u8| self.entries.iter().position(|e| e.index == index);
        let (a, b) = (find(m.a)?, find(m.b)?);
        let k = self.shares.iter().position(|&s| s == m.share)?;
        let target = lab(srgb.map(to_linear));
        Some(self.judge(target, a, b, k))
    }

    /// The cost of entry `a` with `b` on share `self.shares[k]` for `target` (CIELAB).
    #[inline]
    fn judge(&self, target: [f32; 3], a: usize, b: usize, k: usize) -> f32 {
        let w = &self.weights;
        let (ea, eb) = (&self.entries[a], &self.entries[b]);
        let d2 = |p: [f32; 3]| {
            let (dl, da, db) = (p[0] - target[0], p[1] - target[1], p[2] - target[2]);
            (dl * dl, da * da + db * db)
        };
        let share = self.shares[k];
        let s = f32::from(share) / f32::from(SHARES);
        let pixel = |e: &Entry| {
            let (l, ab) = d2(e.lab);
            w.pixel_l * l + w.pixel_ab * ab
        };
        let mixed = self.mixed[(a * self.entries.len() + b) * self.shares.len() + k];
        let (l, ab) = d2(mixed);
        let bytes = match share % SHARES {
            0 => 0.0,
            8 => w.half_cost,
            _ => w.fine_cost,
        };
        let chroma = target[1].hypot(target[2]);
        let (da, db) = (ea.lab[1] - eb.lab[1], ea.lab[2] - eb.lab[2]);
        // Below this chroma (CIELAB) a colour has no hue to keep: any difference is across.
        let across = if chroma < 4.0 {
            da * da + db * db
        } else {
            ((da * target[2] - db * target[1]) / chroma).powi(2)
        };
        (1.0 - s) * pixel(ea)
            + s * pixel(eb)
            + w.mix_l * l
            + w.mix_ab * ab
            + bytes
            + w.pair_hue * s * (1.0 - s) * across
    }

    /// The search behind [`Solver::solve`]: the least cost and its mix.
    fn search(&self, srgb: [f32; 3]) -> (f32, Mix) {
        let w = &self.weights;
        let target = lab(srgb.map(to_linear));
        let mut near: Vec<(f32, usize)> = self
            .entries
            .iter()
            .enumerate()
            .map(|(i, e)| {
                let (dl, da, db) = (
                    e.lab[0] - target[0],
                    e.lab[1] - target[1],
                    e.lab[2] - target[2],
                );
                (dl * dl + w.candidate_ab * (da * da + db * db), i)
            })
            .collect();
        let n = w.candidates.clamp(1, near.len());
        let order = |x: &(f32, usize), y: &(f32, usize)| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1));
        if n < near.len() {
            near.select_nth_unstable_by(n - 1, order);
            near.truncate(n);
        }
        near.sort_by(order);
        let solid = self.shares.iter().position(|&s| s == 0).unwrap_or(0);
        let first = near[0].1;
        let mut best = (
            self.judge(target, first, first, solid),
            Mix {
                a: self.entries[first].index,
                b: self.entries[first].index,
                share: 0,
            },
        );
        for (i, &(_, ia)) in near.iter().enumerate() {
            for &(_, ib) in &near[i + 1..] {
                for (k, &share) in self.shares.iter().enumerate() {
                    let cost = self.judge(target, ia, ib, k);
                    if cost < best.0 {
                        best = (
                            cost,
                            Mix {
                                a: self.entries[ia].index,
                                b: self.entries[ib].index,
                                share,
                            },
                        );
                    }
                }
            }
        }
        let (cost, m) = best;
        // One entry shown whole is one entry, not a mix (fewer colour changes on the wire).
        let m = match m.share {
            0 => Mix { b: m.a, ..m },
            SHARES => Mix {
                a: m.b,
                share: 0,
                ..m
            },
            _ => m,
        };
        (cost, m)
    }
}

/// The weights a level's mixes are judged by: its fine table's, then its halves table's.
fn weights_of(level: ColorLevel) -> [Weights; 2] {
    match level {
        ColorLevel::Ansi16 => [MIX_16, MIX_16],
        _ => [MIX_256, MIX_256_HALVES],
    }
}

/// The solvers behind a level's two shipped tables: every share (pixels whose surface wrote a
/// threshold), and none/half/all (the rest).
#[must_use]
pub(crate) fn solvers(level: ColorLevel) -> [Solver; 2] {
    let (e, [fine, halves]) = (entries(level), weights_of(level));
    [
        Solver::new(&e, xterm_rgb, fine, &FINE_SHARES),
        Solver::new(&e, xterm_rgb, halves, &HALF_SHARES),
    ]
}

/// Where a level's shipped tables live (fine, then halves), under `src/encode/`.
const FILES: [(ColorLevel, [&str; 2]); 2] = [
    (
        ColorLevel::Ansi256,
        ["mixes/256-fine.deflate", "mixes/256-halves.deflate"],
    ),
    (
        ColorLevel::Ansi16,
        ["mixes/16-fine.deflate", "mixes/16-halves.deflate"],
    ),
];

mod tests {
    use super::*;

    #[test]
    #[ignore = "writes the shipped tables; run after changing the weights (release, about a minute)"]
    fn write_mix_tables() {
        let threads = std::thread::available_parallelism().map_or(1, usize::from);
        for (level, files) in FILES {
            for (solver, file) in solvers(level).iter().zip(files) {
                let table = MixTable::from_bins(solver.table(threads));
                let path = format!("{}/src/encode/{file}", env!("CARGO_MANIFEST_DIR"));
                std::fs::write(&path, table.to_bytes()).expect("the table is written");
            }
        }
    }

    #[test]
    fn the_shipped_tables_are_what_the_solver_finds() {
        // Every 997th bin of each table (a few hundred, spread over the cube): the shipped mix is
        // the solver's, or (float rounding on another machine) one that costs as little.
        for (level, _) in FILES {
            for (solver, bytes) in solvers(level).iter().zip(shipped(level)) {
                let table = MixTable::from_bytes(bytes);
                for k in (0..BINS).step_by(997) {
                    let centre = bin_centre(k);
                    let (got, want) = (table.bin(k), solver.solve(centre));
                    if got != want {
                        let (g, w) = (solver.cost(centre, got), solver.cost(centre, want));
                        let (g, w) = (g.expect("a mix the solver allows"), w.unwrap());
                        assert!(
                            g <= w + 1e-3 * w.abs().max(1.0),
                            "{level}: bin {k}: {got:?} costs {g}, {want:?} {w}"
                        );
                    }
                }
            }
        }
    }
}
