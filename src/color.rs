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

/// The RGB an xterm shows for a 256-colour index (16 system colours, 6×6×6 cube, 24 greys).
#[must_use]
pub fn xterm_rgb(n: u8) -> Rgb {
    const SYSTEM: [(u8, u8, u8); 16] = [
        (0, 0, 0),
        (205, 0, 0),
        (0, 205, 0),
        (205, 205, 0),
        (0, 0, 238),
        (205, 0, 205),
        (0, 205, 205),
        (229, 229, 229),
        (127, 127, 127),
        (255, 0, 0),
        (0, 255, 0),
        (255, 255, 0),
        (92, 92, 255),
        (255, 0, 255),
        (0, 255, 255),
        (255, 255, 255),
    ];
    match n {
        0..=15 => {
            let (r, g, b) = SYSTEM[usize::from(n)];
            Rgb::new(r, g, b)
        }
        16..=231 => {
            let i = n - 16;
            let level = |v: u8| if v == 0 { 0 } else { 55 + 40 * v };
            Rgb::new(level(i / 36), level(i / 6 % 6), level(i % 6))
        }
        _ => {
            let v = 8 + 10 * (n - 232);
            Rgb::new(v, v, v)
        }
    }
}

#[cfg(test)]
mod xterm_tests {
    use super::*;

    #[test]
    fn xterm_palette_corners() {
        assert_eq!(xterm_rgb(16), Rgb::new(0, 0, 0));
        assert_eq!(xterm_rgb(231), Rgb::new(255, 255, 255));
        assert_eq!(xterm_rgb(196), Rgb::new(255, 0, 0));
        assert_eq!(xterm_rgb(232), Rgb::new(8, 8, 8));
        assert_eq!(xterm_rgb(255), Rgb::new(238, 238, 238));
    }
}
