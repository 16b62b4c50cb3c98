//! ⌊v⌋ for per-pixel coordinates (floor texels, surface lattices): the rasterizers call it for
//! every pixel, and `f64::floor` is a libm call on baseline x86-64.

/// ⌊v⌋ without a libm call (f64::floor is one on baseline x86-64); saturates far outside i64.
#[inline]
pub(crate) fn fast_floor(v: f64) -> i64 {
    let i = v as i64;
    if (i as f64) > v {
        i.saturating_sub(1)
    } else {
        i
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_floor_matches_floor() {
        for v in [0.0, 0.5, 1.0, -0.5, -1.0, -1.5, 3.999, -3.999, 1e12, -1e12] {
            assert_eq!(fast_floor(v), v.floor() as i64, "{v}");
        }
    }
}
