//! Dither phases tied to surfaces: what the 256- and 16-colour encoders threshold against, so any
//! pattern they draw lies on the walls, floors and sprites and moves with them (walking past a wall
//! does not make it crawl), instead of staying fixed to the screen as an ordered dither does.
//!
//! A surface point's phase comes from a 4×4 threshold matrix ([`DASH4`]) tiled over the surface's
//! own coordinates (a wall's fraction along and up, a sprite's u and v) on a lattice whose step is
//! a power of 2^¼ of the surface unit, the finest one that is still at least one pixel on screen:
//! finer than the pixels it would alias (a minified pattern crawls as the camera moves), coarser it
//! would blur less well. Quarter-octave levels keep the step within 1–1.19 pixels (whole octaves let
//! it reach 2, so a 4×4-pixel patch of a wall saw as few as two thresholds): on the default map's
//! eight views at 256 colours blurred ΔE 1.35 → 1.25. The price is that the pattern is re-laid
//! four times as often (every 19 % change of distance instead of every doubling) while walking
//! towards a wall; strafing along it never re-lays it.

/// The 4×4 threshold matrix, in sixteenths. Each row holds its four thresholds in rising order
/// (cyclically), so the cells below any threshold form one run per row period — a dash along the
/// row, which costs one colour change in and one out, where an ordered-dither (Bayer) row of
/// isolated dots costs up to four (256 colours, `halfcast bench`: 16.4 → 15.6 % of ratatui's
/// truecolor bytes at blurred ΔE 1.21 → 1.22). Any two consecutive rows still hold eight thresholds
/// spread evenly (all even or all odd sixteenths, or interleaved), so a 4-wide, 2-cell-tall patch —
/// what a 4×4-pixel blur sees — shows a threshold's share within half a cell.
pub const DASH4: [[u8; 4]; 4] = [[0, 2, 4, 6], [12, 14, 8, 10], [7, 1, 3, 5], [13, 15, 9, 11]];

/// Lattice levels per doubling of the on-screen size (see the module note).
const LEVELS_PER_OCTAVE: f64 = 4.0;

/// The phase (8..=248, steps of 16) of lattice point (u, v).
#[must_use]
#[inline]
pub fn at(u: i64, v: i64) -> u8 {
    DASH4[(v & 3) as usize][(u & 3) as usize] * 16 + 8
}

/// 2^(q/4) for q = 1..4: where the quarter-octave levels start within one doubling.
const QUARTERS: [f64; 3] = [
    1.189_207_115_002_721,
    std::f64::consts::SQRT_2,
    1.681_792_830_507_429,
];

/// The lowest and highest lattice levels (2⁻²⁰ and 2²⁰ in quarter octaves).
const LEVEL_RANGE: (i64, i64) = (-80, 80);

/// Lattice points per surface unit for a unit spanning `px_per_unit` pixels on screen: the largest
/// power of 2^¼ whose lattice step is still at least one pixel (between 2⁻²⁰ and 2²⁰), i.e.
/// 2^(⌊4·log2 px⌋ / 4).
///
/// Every face of every column asks (several per column on maps with heights), so the level is read
/// off the float's exponent and mantissa and its power from a table, with `log2` only where the
/// mantissa is within rounding of a level's start: the results are those of the formula, bit for bit.
#[must_use]
#[inline]
pub fn lattice(px_per_unit: f64) -> f64 {
    if !(px_per_unit.is_finite() && px_per_unit > 0.0) {
        return 1.0;
    }
    let level = if px_per_unit < f64::MIN_POSITIVE {
        LEVEL_RANGE.0
    } else {
        let bits = px_per_unit.to_bits();
        let exponent = ((bits >> 52) & 0x7ff) as i64 - 1023;
        // The mantissa as a number in [1, 2).
        let m = f64::from_bits((bits & ((1 << 52) - 1)) | (1023 << 52));
        let near = |edge: f64| (m - edge).abs() < 1e-9;
        if near(1.0) || near(2.0) || QUARTERS.iter().any(|&q| near(q)) {
            (px_per_unit.log2() * LEVELS_PER_OCTAVE).floor() as i64
        } else {
            exponent * LEVELS_PER_OCTAVE as i64
                + QUARTERS.iter().filter(|&&q| m >= q).count() as i64
        }
    };
    let level = level.clamp(LEVEL_RANGE.0, LEVEL_RANGE.1);
    level_powers()[(level - LEVEL_RANGE.0) as usize]
}

/// 2^(level / 4) for every level in [`LEVEL_RANGE`], computed once with `exp2`.
fn level_powers() -> &'static [f64] {
    static POWERS: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    POWERS.get_or_init(|| {
        (LEVEL_RANGE.0..=LEVEL_RANGE.1)
            .map(|l| (l as f64 / LEVELS_PER_OCTAVE).exp2())
            .collect()
    })
}

/// The lattice index of surface coordinate `coord` at `per_unit` lattice points per unit.
#[must_use]
#[inline]
pub fn index(coord: f64, per_unit: f64) -> i64 {
    // `floor` without the libm call (baseline x86-64 has no rounding instruction).
    crate::render::fast_floor::fast_floor(coord * per_unit)
}

/// Writes the phases of an upright surface (a wall, a step's or a lintel's face) in column `x`
/// of a `width`-wide phase plane, rows `rows.0..rows.1`: the lattice column of `along` (the
/// fraction across the surface) at `px_along` pixels per unit, and the lattice row of `down(y)`
/// (the fraction down it at pixel row `y`) at `px_up` pixels per unit, a lattice step being at
/// least a cell (two pixel rows) upright, so a cell reads its upper pixel's phase.
pub fn write_upright(
    phases: &mut [u8],
    (width, x): (usize, usize),
    rows: (usize, usize),
    (along, px_along): (f64, f64),
    px_up: f64,
    down: impl Fn(usize) -> f64,
) {
    let u = index(along, lattice(px_along));
    let per_v = lattice(px_up / 2.0);
    for y in rows.0..rows.1 {
        phases[y * width + x] = at(u, index(down(y), per_v));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_four_by_four_window_holds_every_phase() {
        for (u0, v0) in [(0, 0), (1, 3), (-2, 5), (7, -9)] {
            let mut seen: Vec<u8> = (0..4)
                .flat_map(|dv| (0..4).map(move |du| at(u0 + du, v0 + dv)))
                .collect();
            seen.sort_unstable();
            assert_eq!(seen, (0..16).map(|k| k * 16 + 8).collect::<Vec<u8>>());
        }
    }

    #[test]
    fn the_lattice_is_the_largest_quarter_power_of_two_at_most_the_pixels_per_unit() {
        // Against the definition: 2^(floor(4·log2 px) / 4).
        let mut px = 1e-7;
        while px < 1e7 {
            let k = (f64::log2(px) * 4.0).floor() / 4.0;
            let want = k.clamp(-20.0, 20.0).exp2();
            assert_eq!(lattice(px).to_bits(), want.to_bits(), "{px}");
            // Right at and beside the levels' starts, where rounding decides.
            let edge = k.exp2();
            for p in [
                edge,
                f64::from_bits(edge.to_bits() - 1),
                f64::from_bits(edge.to_bits() + 1),
            ] {
                let k = (f64::log2(p) * 4.0).floor() / 4.0;
                assert_eq!(
                    lattice(p).to_bits(),
                    k.clamp(-20.0, 20.0).exp2().to_bits(),
                    "{p}"
                );
            }
            px *= 1.013;
        }
        assert_eq!(lattice(1.0), 1.0);
        assert_eq!(lattice(64.0), 64.0);
        assert_eq!(lattice(1e-300), 2f64.powi(-20));
        assert_eq!(lattice(1e300), 2f64.powi(20));
    }

    #[test]
    fn the_lattice_step_stays_within_a_fifth_of_a_pixel_of_one() {
        for px in [0.3, 0.9, 1.0, 1.5, 1.9, 2.0, 3.7, 64.0, 100.0, 127.0] {
            let step_px = px / lattice(px);
            assert!((1.0..1.19).contains(&step_px), "{px}: {step_px}");
        }
        assert_eq!(lattice(0.0), 1.0);
        assert_eq!(lattice(f64::INFINITY), 1.0);
    }

    #[test]
    fn cells_below_any_share_form_one_dash_per_row_period() {
        for share in 0..=16u8 {
            for v in 0..4 {
                let below: Vec<bool> = (0..4).map(|u| at(u, v) >> 4 < share).collect();
                let changes = (0..4).filter(|&u| below[u] != below[(u + 1) % 4]).count();
                assert!(changes <= 2, "share {share} row {v}: {below:?}");
            }
        }
    }

    #[test]
    fn a_four_by_two_patch_shows_a_share_within_half_a_cell() {
        for share in 0..=16u8 {
            for (u0, v0) in [(0, 0), (1, 1), (-3, 2), (6, 3), (2, -1)] {
                let n = (0..2)
                    .flat_map(|dv| (0..4).map(move |du| at(u0 + du, v0 + dv)))
                    .filter(|p| p >> 4 < share)
                    .count();
                let want = f64::from(share) / 2.0;
                assert!(
                    (n as f64 - want).abs() <= 0.5,
                    "share {share} at ({u0}, {v0}): {n} of 8"
                );
            }
        }
    }
}
