//! Ordered (Bayer 4×4) dithering: a fixed per-pixel offset so smooth walls don't band in few colours.

/// The 4×4 Bayer threshold matrix (values 0–15).
const BAYER4: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

/// The offset added to each channel of pixel (x, y): evenly spread over ±`amplitude`/2.
#[must_use]
#[inline]
pub fn bayer_offset(x: usize, y: usize, amplitude: i16) -> i16 {
    let t = i16::from(BAYER4[y & 3][x & 3]);
    ((2 * t + 1) * amplitude) / 32 - amplitude / 2
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_average_to_about_zero_and_stay_in_range() {
        let mut sum = 0i32;
        for y in 0..4 {
            for x in 0..4 {
                let o = bayer_offset(x, y, 40);
                assert!((-20..=20).contains(&o));
                sum += i32::from(o);
            }
        }
        assert!(sum.abs() <= 16, "{sum}");
    }
}
