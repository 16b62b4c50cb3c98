//! Per-cell colour pairs: a half-block cell's two palette colours are chosen together, so that
//! their mix (in linear light, as the eye blurs them) keeps the cell's colour and hue.
//!
//! With one nearest colour per pixel, dark low-saturation colours (the default map's bricks) all
//! land on greys and the scene loses its hue. Here a cell may show a grey above and a reddish
//! colour below whose mix is the brick's red. The choice depends only on the cell's two pixels —
//! never on where the cell is on screen — so there is no dither pattern that could stay put while
//! the picture moves: a surface translated on screen by whole cells gives the same cells translated.

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

/// The cell's `[top, bottom]` palette indices for pixels `top` and `bottom`.
///
/// `near_of` gives the candidate list of an sRGB colour (the table lookup). Candidates: each
/// pixel's nearest few entries (and, with a wide search, those nearest the cell's mix), each shown
/// whole and paired with the entries nearest its complement `2·mean − a` in linear light (what
/// brings the cell's mix back to the pixels' mix); the pair minimising the mix error plus
/// [`PIXEL_WEIGHT`] × the pixels' own errors plus a split cost wins (first found on ties:
/// deterministic).
#[must_use]
pub fn choose(
    t: &PairTables,
    near_of: impl Fn(Rgb) -> [u8; NEAR],
    top: Rgb,
    bottom: Rgb,
) -> [u8; 2] {
    let (lt, lb) = (top.linear(), bottom.linear());
    let mean = [
        (lt[0] + lb[0]) * 0.5,
        (lt[1] + lb[1]) * 0.5,
        (lt[2] + lb[2]) * 0.5,
    ];
    let (lab_t, lab_b, lab_m) = (oklab(lt), oklab(lb), oklab(mean));
    let complement = |a: u8| -> [u8; NEAR] {
        let la = t.lin[usize::from(a)];
        let c = |i: usize| to_srgb(2.0 * mean[i] - la[i]);
        near_of(Rgb::new(c(0), c(1), c(2)))
    };
    let split_cost = if lab_m[1].hypot(lab_m[2]) >= GREY_CHROMA {
        SPLIT_COST
    } else {
        GREY_SPLIT_COST
    };
    let cost = |p: u8, q: u8| -> f32 {
        let mix = t.mix[usize::from(p) * 256 + usize::from(q)];
        lab_dist2(mix, lab_m)
            + PIXEL_WEIGHT
                * (lab_dist2(t.lab[usize::from(p)], lab_t)
                    + lab_dist2(t.lab[usize::from(q)], lab_b))
            + if p == q { 0.0 } else { split_cost }
    };
    let (nt, nb) = (near_of(top), near_of(bottom));
    let mut best = ([nt[0], nb[0]], cost(nt[0], nb[0]));
    let mut consider = |p: u8, q: u8| {
        let c = cost(p, q);
        if c < best.1 {
            best = ([p, q], c);
        }
    };
    let width = if t.wide { NEAR } else { 1 };
    let nm = if t.wide {
        near_of(Rgb::new(
            to_srgb(mean[0]),
            to_srgb(mean[1]),
            to_srgb(mean[2]),
        ))
    } else {
        nt
    };
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
    best.0
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
    fn the_choice_depends_on_the_pixels_only() {
        let p = Palette::new(ColorLevel::Ansi16, false);
        let (t, b) = (Rgb::new(90, 60, 40), Rgb::new(70, 50, 45));
        let here = p.cell(t, b, 0, 0);
        for (x, y) in [(1, 0), (5, 2), (17, 31)] {
            assert_eq!(p.cell(t, b, x, y), here);
        }
    }
}
