//! The one pixel type: 8-bit sRGB, what terminals and PNGs both speak.

/// An RGB colour; framebuffers, textures and map colours all use it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize)]
pub struct Rgb {
    pub r: u8,
    pub g: u8,
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
    fn luma_of_white_is_255() {
        assert_eq!(Rgb::new(255, 255, 255).luma(), 255);
        assert_eq!(Rgb::new(0, 0, 0).luma(), 0);
    }
}
