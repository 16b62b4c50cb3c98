//! Dither phases tied to surfaces: what the 256- and 16-colour encoders threshold against, so any
//! pattern they draw lies on the walls, floors and sprites and moves with them (walking past a wall
//! does not make it crawl), instead of staying fixed to the screen as an ordered dither does.
//!
//! A surface point's phase comes from a 4×4 ordered-dither matrix tiled over the surface's own
//! coordinates (a wall's fraction along and up, a floor's world position, a sprite's u and v) on a
//! lattice whose step is a power of two of the surface unit, the finest one that is still at least
//! one pixel on screen: finer than the pixels it would alias (a minified pattern crawls as the
//! camera moves), coarser it would blur less well. Any 4×4 window of the tiled matrix holds all 16
//! phases, so at a one-pixel step each 4×4 pixel block shows a threshold's exact share.

/// The 4×4 Bayer matrix: neighbouring entries are far apart, so any share of them is spread out.
const BAYER4: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

/// The phase (8..=248, steps of 16) of lattice point (u, v).
#[must_use]
#[inline]
pub fn at(u: i64, v: i64) -> u8 {
    BAYER4[(v & 3) as usize][(u & 3) as usize] * 16 + 8
}

/// Lattice points per surface unit for a unit spanning `px_per_unit` pixels on screen: the largest
/// power of two whose lattice step is still at least one pixel (between 2⁻²⁰ and 2²⁰).
#[must_use]
#[inline]
pub fn lattice(px_per_unit: f64) -> f64 {
    if !(px_per_unit.is_finite() && px_per_unit > 0.0) {
        return 1.0;
    }
    let k = px_per_unit.log2().floor().clamp(-20.0, 20.0);
    k.exp2()
}

/// The lattice index of surface coordinate `coord` at `per_unit` lattice points per unit.
#[must_use]
#[inline]
pub fn index(coord: f64, per_unit: f64) -> i64 {
    (coord * per_unit).floor() as i64
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
    fn the_lattice_step_stays_between_one_and_two_pixels() {
        for px in [0.3, 0.9, 1.0, 1.5, 2.0, 3.7, 64.0, 100.0] {
            let step_px = px / lattice(px);
            assert!((1.0..2.0).contains(&step_px), "{px}: {step_px}");
        }
        assert_eq!(lattice(0.0), 1.0);
        assert_eq!(lattice(f64::INFINITY), 1.0);
    }
}
