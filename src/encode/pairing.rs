//! Per-cell colour pairs: a half-block cell's two palette colours are chosen together, so that
//! their mix (in linear light, as the eye blurs them) keeps the cell's colour and hue.
//!
//! With one nearest colour per pixel, dark low-saturation colours (the default map's bricks) all
//! land on greys and the scene loses its hue. Here a cell may show a grey above and a reddish
//! colour below whose mix is the brick's red. [`choose`] depends only on the cell's two pixels —
//! never on where the cell is on screen — so a surface translated on screen by whole cells gives
//! the same cells translated.
//!
//! Where no single pair's mix is close (dark saturated colours), [`choose_alternating`] adds a
//! second pair and a share: cells whose dither phase (written by the rasterizer, tied to the
//! surface: [`crate::render::dither_phase`]) is below it show the second pair, so the mix over a few cells
//! lands near the pixels' and the pattern moves with the surface, never with the screen.

use crate::color::{lab_dist2, oklab, Linear, Rgb};

/// Nearest palette entries kept per lookup-table bin as first-choice candidates.
pub const NEAR: usize = 3;

/// Weight of each pixel's own error against the error of the cell's mixed colour (which the
/// eye sees at a normal viewing distance): low, so hue is kept, but enough to keep edges crisp.
/// Measured on the default map (256 colours): 0.3 keeps 0.49 of the chroma, 0.1 0.68, 0.01 0.88.
const PIXEL_WEIGHT: f32 = 0.01;

/// Extra cost (in squared OKLab units) of showing two different colours where one would do:
/// a bias towards uniform cells, which cost fewer bytes. Measured with [`GREY_SPLIT_COST`]
/// (256 colours; `halfcast bench` mean of its runs vs stock ratatui truecolor; chroma kept on the
/// default map's views; before the wide search): 0.0004 → 15.9 %, 0.88; 0.0006 → 15.6 %, 0.82.
/// A single cost for all cells reaches only 16.1 % at 0.81 or 15.9 % at 0.78. With the wide search
/// 0.0004 gives 15.5 %, 0.89 (0.0003 with 0.002 for grey: 15.9 %, 0.91, no better ΔE).
const SPLIT_COST: f32 = 0.000_4;

/// Below this OKLab chroma a cell counts as grey: splitting it buys only lightness, not hue, so it
/// pays more for the bytes.
const GREY_CHROMA: f32 = 0.02;

/// [`SPLIT_COST`] for grey cells (0.002 → 16.1 %, 0.004 → 15.9 % at the same chroma kept).
const GREY_SPLIT_COST: f32 = 0.004;

/// The tables a pair search reads; built once per colour level.
#[derive(Debug)]
pub struct PairTables {
    /// The `NEAR` nearest entries (OKLab) per 5-bit-per-channel bin, nearest first.
    pub near: Vec<[u8; NEAR]>,
    /// Linear-light RGB of every palette index.
    pub lin: Vec<Linear>,
    /// OKLab of every palette index.
    pub lab: Vec<[f32; 3]>,
    /// OKLab of the linear-light mix of indices p and q at `p * 256 + q` (the costly part of a
    /// pair's cost, so it is computed once per process rather than per cell).
    pub mix: Vec<[f32; 3]>,
    /// Whether the search is wide: the entries nearest the cell's mix, and the [`NEAR`] nearest
    /// to each complement, are candidates too (not only the nearest). That helps at 256 colours
    /// (default map: blurred ΔE 1.51 → 1.46, chroma kept 0.88 → 0.89, bytes 15.9 → 15.5 %), but at
    /// 16 it costs hue (chroma kept 0.85 → 0.67 for ΔE 6.42 → 6.17), so it is for 256 only.
    pub wide: bool,
}

impl PairTables {
    /// The tables for palette colours `rgb(i)` of indices 0–255, with candidates' `near` lists.
    #[must_use]
    pub fn new(near: Vec<[u8; NEAR]>, rgb: impl Fn(u8) -> Rgb, wide: bool) -> Self {
        let lin: Vec<Linear> = (0..=255u8).map(|i| rgb(i).linear()).collect();
        let lab = lin.iter().map(|&l| oklab(l)).collect();
        let mut mix = Vec::with_capacity(256 * 256);
        for lp in &lin {
            for lq in &lin {
                mix.push(oklab([0, 1, 2].map(|i| (lp[i] + lq[i]) * 0.5)));
            }
        }
        Self {
            near,
            lin,
            lab,
            mix,
            wide,
        }
    }
}

/// A linear channel value (0..=1) → the 8-bit sRGB value nearest to it (4096-step table).
fn to_srgb(v: f32) -> u8 {
    static TABLE: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    let t = TABLE.get_or_init(|| {
        (0..=4096)
            .map(|i| {
                let v = f64::from(i) / 4096.0;
                let s = if v <= 0.003_130_8 {
                    12.92 * v
                } else {
                    1.055 * v.powf(1.0 / 2.4) - 0.055
                };
                (s * 255.0).round().clamp(0.0, 255.0) as u8
            })
            .collect()
    });
    t[(v.clamp(0.0, 1.0) * 4096.0 + 0.5) as usize]
}

/// The candidate pairs of a cell, in the order they are tried: each pixel's nearest few entries
/// (and, with a wide search, those nearest the cell's mix), each shown whole and paired with the
/// entries nearest its complement `2·mean − a` in linear light (what brings the cell's mix back to
/// the pixels' mix). `consider(p, q)` is called for each (`p` above, `q` below).
fn for_each_candidate(
    t: &PairTables,
    near_of: &impl Fn(Rgb) -> [u8; NEAR],
    mean: Linear,
    (nt, nb, nm): ([u8; NEAR], [u8; NEAR], [u8; NEAR]),
    mut consider: impl FnMut(u8, u8),
) {
    let complement = |a: u8| -> [u8; NEAR] {
        let la = t.lin[usize::from(a)];
        let c = |i: usize| to_srgb(2.0 * mean[i] - la[i]);
        near_of(Rgb::new(c(0), c(1), c(2)))
    };
    let width = if t.wide { NEAR } else { 1 };
    let nm = if t.wide { nm } else { nt };
    for &a in nt.iter().chain(&nm) {
        consider(a, a);
        for q in complement(a).into_iter().take(width) {
            consider(a, q);
        }
    }
    for &a in nb.iter().chain(&nm) {
        consider(a, a);
        for p in complement(a).into_iter().take(width) {
            consider(p, a);
        }
    }
}

/// The mean of two linear colours.
fn mean_of(a: Linear, b: Linear) -> Linear {
    [0, 1, 2].map(|i| (a[i] + b[i]) * 0.5)
}

/// The palette entries nearest the cell's linear mix (the wide search's extra candidates).
fn near_mean(near_of: &impl Fn(Rgb) -> [u8; NEAR], mean: Linear) -> [u8; NEAR] {
    near_of(Rgb::new(
        to_srgb(mean[0]),
        to_srgb(mean[1]),
        to_srgb(mean[2]),
    ))
}

/// [`SPLIT_COST`] or [`GREY_SPLIT_COST`] for a cell whose mix is `lab_m`.
fn split_cost_of(lab_m: [f32; 3]) -> f32 {
    if lab_m[1].hypot(lab_m[2]) >= GREY_CHROMA {
        SPLIT_COST
    } else {
        GREY_SPLIT_COST
    }
}

/// The split cost of a cell in a frame with dither phases: at 256 colours (a wide search)
/// [`DITHERED_SPLIT_COST`], at 16 [`SPLIT_COST`] (there a split is what keeps the hue, and bytes
/// are few), or [`GREY_SPLIT_COST`] for grey cells.
fn split_cost_dithered(t: &PairTables, lab_m: [f32; 3]) -> f32 {
    if lab_m[1].hypot(lab_m[2]) < GREY_CHROMA {
        GREY_SPLIT_COST
    } else if t.wide {
        DITHERED_SPLIT_COST
    } else {
        SPLIT_COST
    }
}

/// The cell's `[top, bottom]` palette indices for pixels `top` and `bottom`.
///
/// `near_of` gives the candidate list of an sRGB colour (the table lookup). Among the candidates
/// (see [`for_each_candidate`]) the pair minimising the mix error plus [`PIXEL_WEIGHT`] × the
/// pixels' own errors plus a split cost wins (first found on ties: deterministic). This is the
/// choice for frames without dither phases (finished frames from elsewhere).
#[must_use]
pub fn choose(
    t: &PairTables,
    near_of: impl Fn(Rgb) -> [u8; NEAR],
    top: Rgb,
    bottom: Rgb,
) -> [u8; 2] {
    let (lt, lb) = (top.linear(), bottom.linear());
    let mean = mean_of(lt, lb);
    let (lab_t, lab_b, lab_m) = (oklab(lt), oklab(lb), oklab(mean));
    let split_cost = split_cost_of(lab_m);
    let cost = |p: u8, q: u8| -> f32 {
        let mix = t.mix[usize::from(p) * 256 + usize::from(q)];
        lab_dist2(mix, lab_m)
            + PIXEL_WEIGHT
                * (lab_dist2(t.lab[usize::from(p)], lab_t)
                    + lab_dist2(t.lab[usize::from(q)], lab_b))
            + if p == q { 0.0 } else { split_cost }
    };
    let (nt, nb) = (near_of(top), near_of(bottom));
    let nm = if t.wide {
        near_mean(&near_of, mean)
    } else {
        nt
    };
    let mut best = ([nt[0], nb[0]], cost(nt[0], nb[0]));
    for_each_candidate(t, &near_of, mean, (nt, nb, nm), |p, q| {
        let c = cost(p, q);
        if c < best.1 {
            best = ([p, q], c);
        }
    });
    best.0
}

/// Steps of a dither threshold: a cell's share of its second pair is a multiple of 1/16 (the 16
/// phases of [`crate::render::dither_phase`]).
pub const SHARES: u8 = 16;

/// The smallest share (in sixteenths) worth a second pair. One cell in sixteen buys a sixteenth
/// of the way between the two mixes, but each such cell costs a colour change in and one out, and
/// a surface's lattice shows it in some 4×4-pixel patches and not in others. Measured (256
/// colours, default map's eight views; `halfcast bench`): 1 → ΔE 1.214, 15.78 %; 2 → 1.212,
/// 15.78 % (at a split cost of 0.001: 1 → 1.200, 16.02 %; 2 → 1.199, 16.00 %; 3 → 1.200, 16.12 %).
/// 16 colours: blurred ΔE 4.82 → 4.81.
const MIN_SHARE: u8 = 2;

/// Weight of the alternation's own noise (the spread between the two pairs' mixes, which a
/// pattern about a cell fine mostly blurs away) against the mix error, at 16 colours.
const NOISE_WEIGHT: f32 = 0.05;

/// [`NOISE_WEIGHT`] at 256 colours. A surface's lattice is not the screen's: a 4×4-pixel patch
/// sees only some of the pattern's thresholds, so a share shows with some spread and a second pair
/// far from the first leaves visible error. Measured (default map's eight views, blurred ΔE and
/// chroma kept): with the quarter-octave lattice (Bayer pattern, split cost 0.0012, best pair kept
/// alone within ΔE 1) 0.02 → 1.22, 0.1 → 1.21, 0.2 → 1.19 (0.89), 0.3 → 1.31 (0.77); with the dash
/// pattern at split cost 0.001, 0.1 → 1.21 (0.96), 0.15 → 1.20 (0.94); at 0.0008, 0.1 → 1.19,
/// 0.2 → 1.17.
const NOISE_WEIGHT_256: f32 = 0.15;

/// Extra cost per colour the two pairs use beyond the two one fg/bg setting draws, at 16 colours:
/// each switch between them is then another colour change on the wire. At 256 colours a dash of
/// the pattern ([`crate::render::dither_phase::DASH4`]) already keeps switches few, and any cost
/// here bought fewer bytes than the same ΔE spent on [`DITHERED_SPLIT_COST`] (0.000 05: ΔE 1.215,
/// 15.8 %; none at a split cost of 0.0011: 1.214, 15.8 %).
const SWITCH_COST: f32 = 0.000_2;

/// Weight of the a/b (hue and chroma) part of a 16-colour alternation's error against its
/// lightness: with an equal weight the alternations buy lightness with greys and the scene loses
/// its hue. Measured (default map's eight views, 16 colours): 1 → ΔE 4.08, chroma kept 0.66;
/// 3 → 4.25, 0.63; 10 → 4.89, 0.85 (one pair per cell: 6.42, 0.85).
const HUE_WEIGHT_16: f32 = 10.0;

/// [`SPLIT_COST`] in frames with dither phases. Alternating pairs sends more colour changes, so
/// single cells pay more for splitting. This is the knob between blurred ΔE and bytes; measured
/// (256 colours, default map's eight views at 120×40; `halfcast bench` mean of its six runs vs
/// ratatui truecolor; quarter-octave lattice, dash pattern, [`NOISE_WEIGHT_256`]): 0.0008 → ΔE
/// 1.17, 16.5 %; 0.0009 → 1.19, 16.3 %; 0.001 → 1.200, 16.0 %; 0.00105 → 1.212, 15.9 %;
/// 0.0011 → 1.214, 15.8 %; 0.0012 → 1.22, 15.6 %. (Before both: 0.0008 → 1.30, 16.1 %; 0.0012 →
/// 1.34, 15.3 %.) With [`MIN_SHARE`] 2: 0.001 → 1.1992, 16.004 %; 0.00101 → 1.1998, 15.981 %;
/// 0.00102 → 1.2007, 15.95 %; 0.0011 → 1.212, 15.78 %. The setting is the lowest within the 16 %
/// budget, where blurred ΔE just reaches 1.2: both hold, with no margin.
const DITHERED_SPLIT_COST: f32 = 0.001_01;

/// A best pair whose mix is this close to the pixels' (squared OKLab, ΔE 2) is kept alone: an
/// alternation would gain little and cost bytes and time.
const CLOSE_ENOUGH: f32 = 4e-4;

/// A cell that shows pair `b` where its dither phase is below `share` sixteenths, else pair `a`:
/// over a few neighbouring cells the mix lands between the two pairs' mixes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Alternating {
    /// The best single pair (`[top, bottom]`).
    pub a: [u8; 2],
    /// The second pair.
    pub b: [u8; 2],
    /// Sixteenths of cells that show `b` (0 = always `a`).
    pub share: u8,
}

impl Alternating {
    /// The `[top, bottom]` indices for a cell whose dither phase is `phase`.
    #[must_use]
    #[inline]
    pub fn resolve(self, phase: u8) -> [u8; 2] {
        if phase >> 4 < self.share {
            self.b
        } else {
            self.a
        }
    }
}

/// How many colours pairs `a` and `b` use together beyond two: cells of either can be drawn with
/// one foreground and one background setting (`▀ ▄ █` and space) when this is 0.
fn extra_colours(a: [u8; 2], b: [u8; 2]) -> u8 {
    let mut set = [a[0], a[1], b[0], b[1]];
    set.sort_unstable();
    let distinct =
        1 + u8::from(set[1] != set[0]) + u8::from(set[2] != set[1]) + u8::from(set[3] != set[2]);
    distinct.saturating_sub(2)
}

/// The cell's best pair and, where alternating with a second pair brings the cells' blurred mix
/// closer to the pixels' mix, that pair and its share, for frames whose dither phases are tied to
/// their surfaces.
///
/// The first pair is [`choose`]'s. Every other candidate is tried as the second: the share is the
/// pixels' mix projected on the line between the two pairs' mixes (in OKLab, where nearby mixes
/// combine almost linearly), in sixteenths; the cost adds the alternation's noise
/// ([`NOISE_WEIGHT`], [`NOISE_WEIGHT_256`]) and at 16 colours [`SWITCH_COST`] per colour changed
/// to [`choose`]'s terms, weighted by
/// share. Ties keep the first found (deterministic).
#[must_use]
pub fn choose_alternating(
    t: &PairTables,
    near_of: impl Fn(Rgb) -> [u8; NEAR],
    top: Rgb,
    bottom: Rgb,
) -> Alternating {
    let (lt, lb) = (top.linear(), bottom.linear());
    let mean = mean_of(lt, lb);
    let (lab_t, lab_b, lab_m) = (oklab(lt), oklab(lb), oklab(mean));
    let split_cost = split_cost_dithered(t, lab_m);
    // A pair's own cost without the mix error: pixel errors and the split cost.
    let own = |p: u8, q: u8| -> f32 {
        PIXEL_WEIGHT
            * (lab_dist2(t.lab[usize::from(p)], lab_t) + lab_dist2(t.lab[usize::from(q)], lab_b))
            + if p == q { 0.0 } else { split_cost }
    };
    let mix = |pq: [u8; 2]| t.mix[usize::from(pq[0]) * 256 + usize::from(pq[1])];
    let (nt, nb) = (near_of(top), near_of(bottom));
    let nm = if t.wide {
        near_mean(&near_of, mean)
    } else {
        nt
    };
    let mut pairs = [[0u8; 2]; 64];
    let mut len = 0;
    let mut best = ([nt[0], nb[0]], f32::MAX);
    let mut consider = |p: u8, q: u8| {
        let c = lab_dist2(mix([p, q]), lab_m) + own(p, q);
        if c < best.1 {
            best = ([p, q], c);
        }
        if len < pairs.len() {
            pairs[len] = [p, q];
            len += 1;
        }
    };
    consider(nt[0], nb[0]);
    for_each_candidate(t, &near_of, mean, (nt, nb, nm), &mut consider);
    let (a, cost_a) = best;
    let single = Alternating { a, b: a, share: 0 };
    if lab_dist2(mix(a), lab_m) < CLOSE_ENOUGH {
        return single;
    }
    let lin_mix = |pq: [u8; 2]| mean_of(t.lin[usize::from(pq[0])], t.lin[usize::from(pq[1])]);
    let la_lin = lin_mix(a);
    // Pairs beyond the pixels' mix as seen from `a` (what a small share of cells can pull the
    // blurred mix back with): where no pair's mix is close, e.g. dark saturated colours.
    for k in [2.0f32, 4.0] {
        let x = [0, 1, 2].map(|i| (la_lin[i] + k * (mean[i] - la_lin[i])).clamp(0.0, 1.0));
        let xs = Rgb::new(to_srgb(x[0]), to_srgb(x[1]), to_srgb(x[2]));
        let n = near_of(xs)[0];
        let mut push = |pq: [u8; 2]| {
            if len < pairs.len() {
                pairs[len] = pq;
                len += 1;
            }
        };
        push([n, n]);
        for (p, top_fixed) in [(a[0], true), (a[1], false), (n, true)] {
            let lp = t.lin[usize::from(p)];
            let c = |i: usize| to_srgb(2.0 * x[i] - lp[i]);
            let q = near_of(Rgb::new(c(0), c(1), c(2)))[0];
            push(if top_fixed { [p, q] } else { [q, p] });
        }
    }
    let la = mix(a);
    let own_a = own(a[0], a[1]);
    let steps = f32::from(SHARES);
    let mut out = (single, cost_a);
    let md = [0, 1, 2].map(|i| mean[i] - la_lin[i]);
    // OKLab near the pixels' mix, linearised (columns: the change per unit of each channel), so
    // each candidate's error costs a few multiplications instead of three cube roots.
    let jacobian: [[f32; 3]; 3] = [0, 1, 2].map(|i| {
        let h = 1e-3;
        let mut m = mean;
        m[i] += h;
        let l = oklab(m);
        [0, 1, 2].map(|k| (l[k] - lab_m[k]) / h)
    });
    // The OKLab error of linear colour `x` against the pixels' mix.
    let offset = |x: Linear| -> [f32; 3] {
        let e = [0, 1, 2].map(|i| x[i] - mean[i]);
        [0, 1, 2].map(|k| jacobian[0][k] * e[0] + jacobian[1][k] * e[1] + jacobian[2][k] * e[2])
    };
    for &b in &pairs[..len] {
        if b == a {
            continue;
        }
        let lb_lin = lin_mix(b);
        let d = [0, 1, 2].map(|i| lb_lin[i] - la_lin[i]);
        let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if dd <= 1e-12 {
            continue;
        }
        let along = (md[0] * d[0] + md[1] * d[1] + md[2] * d[2]) / dd;
        let share = (along.clamp(0.0, 1.0) * steps).round() as u8;
        if share < MIN_SHARE {
            continue;
        }
        let s = f32::from(share) / steps;
        let shown = [0, 1, 2].map(|i| la_lin[i] + s * d[i]);
        // Colours beyond the two a run of these cells can draw with one fg/bg setting.
        let changed = extra_colours(a, b);
        // At 16 colours mixes lie far from the pixels', beyond the linearisation's reach; and
        // there the hue counts more than the lightness (see [`HUE_WEIGHT_16`]).
        let miss = if t.wide {
            let o = offset(shown);
            o[0] * o[0] + o[1] * o[1] + o[2] * o[2]
        } else {
            let l = oklab(shown);
            (l[0] - lab_m[0]).powi(2)
                + HUE_WEIGHT_16 * ((l[1] - lab_m[1]).powi(2) + (l[2] - lab_m[2]).powi(2))
        };
        let (noise, switch) = if t.wide {
            (NOISE_WEIGHT_256, 0.0)
        } else {
            (NOISE_WEIGHT, SWITCH_COST * f32::from(changed))
        };
        let c = miss
            + (1.0 - s) * own_a
            + s * own(b[0], b[1])
            + noise * s * (1.0 - s) * lab_dist2(la, mix(b))
            + switch;
        if c < out.1 {
            out = (Alternating { a, b, share }, c);
        }
    }
    out.0
}

#[cfg(test)]
mod tests {
    use super::super::level::ColorLevel;
    use super::super::palette::{xterm_rgb, Palette};
    use crate::color::{oklab, Rgb};

    fn chroma(c: [f32; 3]) -> f32 {
        c[1].hypot(c[2])
    }

    /// The OKLab colour of a cell's two codes mixed in linear light.
    fn mix(p: &Palette, codes: [u32; 2]) -> [f32; 3] {
        let (a, b) = (p.rgb(codes[0]).linear(), p.rgb(codes[1]).linear());
        oklab([0, 1, 2].map(|i| (a[i] + b[i]) / 2.0))
    }

    #[test]
    fn a_dark_brick_red_stays_red_where_the_nearest_colour_is_grey() {
        let p = Palette::new(ColorLevel::Ansi256, false);
        let brick = Rgb::new(104, 72, 64);
        let nearest = p.rgb(p.code(brick, 0, 0));
        assert_eq!(
            nearest.r, nearest.g,
            "the nearest xterm colour is a grey: {nearest:?}"
        );
        let source = oklab(brick.linear());
        let shown = mix(&p, p.cell(brick, brick, 0, 0));
        let kept = chroma(shown) / chroma(source);
        assert!((0.6..1.6).contains(&kept), "chroma kept {kept}");
        assert!(crate::color::lab_dist2(shown, source).sqrt() < 0.03);
    }

    #[test]
    fn palette_colours_are_shown_as_themselves() {
        let p = Palette::new(ColorLevel::Ansi256, false);
        for i in [16u8, 52, 88, 124, 160, 196, 100, 231, 240] {
            let c = xterm_rgb(i);
            let [a, b] = p.cell(c, c, 3, 4);
            assert_eq!((p.rgb(a), p.rgb(b)), (c, c), "index {i}");
        }
        let p = Palette::new(ColorLevel::Ansi16, false);
        assert_eq!(p.cell(Rgb::new(255, 0, 0), Rgb::new(0, 0, 0), 0, 0), [9, 0]);
    }

    #[test]
    fn a_colour_no_pair_reaches_is_reached_by_alternating_two() {
        // A dark saturated red: every single pair's mix is far off; a share of cells showing a
        // second pair brings the blurred mix closer than the best pair alone.
        let p = Palette::new(ColorLevel::Ansi256, false);
        let red = Rgb::new(40, 6, 3);
        let alt = p.cell_dithered(red, red).expect("256 colours pair cells");
        assert!(alt.share > 0 && alt.b != alt.a, "{alt:?}");
        let lin = |pq: [u8; 2]| {
            let (a, b) = (xterm_rgb(pq[0]).linear(), xterm_rgb(pq[1]).linear());
            [0, 1, 2].map(|i| (a[i] + b[i]) / 2.0)
        };
        let s = f32::from(alt.share) / f32::from(super::SHARES);
        let (la, lb) = (lin(alt.a), lin(alt.b));
        let blurred = oklab([0, 1, 2].map(|i| la[i] + s * (lb[i] - la[i])));
        let target = oklab(red.linear());
        let d = |c| crate::color::lab_dist2(c, target).sqrt();
        assert!(
            d(blurred) < 0.8 * d(oklab(la)),
            "{} vs {}",
            d(blurred),
            d(oklab(la))
        );
        // The phase decides: low phases show the second pair, high ones the first.
        assert_eq!(alt.resolve(0), alt.b);
        assert_eq!(alt.resolve(255), alt.a);
    }

    #[test]
    fn a_second_pair_shows_on_at_least_two_cells_in_sixteen() {
        // A single cell in sixteen buys little and costs two colour changes: no share of 1.
        let mut alternating = 0;
        for level in [ColorLevel::Ansi256, ColorLevel::Ansi16] {
            let p = Palette::new(level, false);
            for r in (0..=255u8).step_by(17) {
                for g in (0..=255u8).step_by(17) {
                    for b in (0..=255u8).step_by(51) {
                        let c = Rgb::new(r, g, b);
                        let alt = p.cell_dithered(c, c).unwrap();
                        assert!(alt.share != 1, "{level}: {c:?} → {alt:?}");
                        alternating += usize::from(alt.share >= super::MIN_SHARE);
                    }
                }
            }
        }
        assert!(alternating > 100, "only {alternating} colours alternate");
    }

    #[test]
    fn the_choice_depends_on_the_pixels_only() {
        let p = Palette::new(ColorLevel::Ansi16, false);
        let (t, b) = (Rgb::new(90, 60, 40), Rgb::new(70, 50, 45));
        let here = p.cell(t, b, 0, 0);
        for (x, y) in [(1, 0), (5, 2), (17, 31)] {
            assert_eq!(p.cell(t, b, x, y), here);
        }
    }
}
