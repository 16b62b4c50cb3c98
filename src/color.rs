//! The one pixel type: 8-bit sRGB, what terminals and PNGs both speak.

/// An RGB colour; framebuffers, textures and map colours all use it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize)]
pub struct Rgb {
    /// Red, 0–255.
    pub r: u8,
    /// Green, 0–255.
    pub g: u8,
    /// Blue, 0–255.
    pub b: u8,
}

impl Rgb {
    /// Builds a colour; `const` so palettes can be constants.
    #[must_use]
    pub const fn new(r: u8, g: u8, b: u8) -> Self {
        Self { r, g, b }
    }

    /// Scales brightness by `k`/256 with integer maths (used per pixel for shading).
    #[must_use]
    #[inline]
    pub fn scaled(self, k: u16) -> Self {
        let s = |c: u8| ((u16::from(c) * k) >> 8).min(255) as u8;
        Self::new(s(self.r), s(self.g), s(self.b))
    }

    /// The mean of some colours per channel (black for none): one colour standing for a surface.
    #[must_use]
    pub fn mean(colours: impl IntoIterator<Item = Rgb>) -> Rgb {
        let (mut r, mut g, mut b, mut n) = (0u64, 0u64, 0u64, 0u64);
        for c in colours {
            r += u64::from(c.r);
            g += u64::from(c.g);
            b += u64::from(c.b);
            n += 1;
        }
        let n = n.max(1);
        Rgb::new((r / n) as u8, (g / n) as u8, (b / n) as u8)
    }

    /// Relative luminance in 0..=255 (Rec. 709 weights), for ASCII shade ramps.
    #[must_use]
    pub fn luma(self) -> u8 {
        let l = 54 * u32::from(self.r) + 183 * u32::from(self.g) + 19 * u32::from(self.b);
        (l >> 8) as u8
    }
}

/// Linear-light RGB in 0..=1: where colours mix the way light (and a blurring eye) mixes them.
pub type Linear = [f32; 3];

/// An 8-bit sRGB channel in linear light (the sRGB transfer curve), from a table built once.
#[must_use]
#[inline]
pub fn channel_to_linear(v: u8) -> f32 {
    static TABLE: std::sync::OnceLock<[f32; 256]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t = [0.0f32; 256];
        for (i, x) in t.iter_mut().enumerate() {
            let v = i as f64 / 255.0;
            *x = if v <= 0.040_45 {
                (v / 12.92) as f32
            } else {
                ((v + 0.055) / 1.055).powf(2.4) as f32
            };
        }
        t
    })[usize::from(v)]
}

impl Rgb {
    /// This colour in linear light.
    #[must_use]
    #[inline]
    pub fn linear(self) -> Linear {
        [
            channel_to_linear(self.r),
            channel_to_linear(self.g),
            channel_to_linear(self.b),
        ]
    }
}

/// Linear RGB → OKLab (Björn Ottosson's perceptual space): `[L, a, b]`, chroma = |(a, b)|.
///
/// Negative LMS responses (only from out-of-gamut input) clamp to 0, as the fidelity tool does.
#[must_use]
#[inline]
pub fn oklab(c: Linear) -> [f32; 3] {
    let [r, g, b] = c;
    let l = cbrt((0.412_221_46 * r + 0.536_332_55 * g + 0.051_445_995 * b).max(0.0));
    let m = cbrt((0.211_903_5 * r + 0.680_699_5 * g + 0.107_396_96 * b).max(0.0));
    let s = cbrt((0.088_302_46 * r + 0.281_718_85 * g + 0.629_978_7 * b).max(0.0));
    [
        0.210_454_26 * l + 0.793_617_8 * m - 0.004_072_047 * s,
        1.977_998_5 * l - 2.428_592_2 * m + 0.450_593_7 * s,
        0.025_904_037 * l + 0.782_771_77 * m - 0.808_675_77 * s,
    ]
}

/// Squared distance between two OKLab colours.
#[must_use]
#[inline]
pub fn lab_dist2(a: [f32; 3], b: [f32; 3]) -> f32 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)
}

/// Cube root of a non-negative f32: a bit-level first guess and two Newton steps (relative error
/// below 1e-6), several times cheaper than `f32::cbrt`, which matters once per cell candidate.
#[must_use]
#[inline]
fn cbrt(x: f32) -> f32 {
    if x <= 1e-30 {
        return 0.0;
    }
    let mut y = f32::from_bits(x.to_bits() / 3 + 0x2A51_2CE3);
    y = (2.0 * y + x / (y * y)) / 3.0;
    y = (2.0 * y + x / (y * y)) / 3.0;
    (2.0 * y + x / (y * y)) / 3.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaling_by_256_is_identity_and_by_128_halves() {
        let c = Rgb::new(200, 100, 3);
        assert_eq!(c.scaled(256), c);
        assert_eq!(c.scaled(128), Rgb::new(100, 50, 1));
    }

    #[test]
    fn oklab_matches_reference_values() {
        // Ottosson's published values: white is L = 1, a = b = 0; pure sRGB red is (0.628, 0.225, 0.126).
        let w = oklab(Rgb::new(255, 255, 255).linear());
        assert!(
            (w[0] - 1.0).abs() < 1e-3 && w[1].abs() < 1e-3 && w[2].abs() < 1e-3,
            "{w:?}"
        );
        let r = oklab(Rgb::new(255, 0, 0).linear());
        assert!((r[0] - 0.628).abs() < 1e-3, "{r:?}");
        assert!(
            (r[1] - 0.2249).abs() < 1e-3 && (r[2] - 0.1258).abs() < 1e-3,
            "{r:?}"
        );
        assert_eq!(oklab([0.0; 3]), [0.0; 3]);
    }

    #[test]
    fn fast_cube_root_is_accurate() {
        for x in [1e-9f32, 1e-4, 0.003, 0.2, 0.5, 1.0, 2.7] {
            assert!((cbrt(x) - x.cbrt()).abs() <= 1e-5 * x.cbrt(), "{x}");
        }
    }

    #[test]
    fn luma_of_white_is_255() {
        assert_eq!(Rgb::new(255, 255, 255).luma(), 255);
        assert_eq!(Rgb::new(0, 0, 0).luma(), 0);
    }
}
