//! Textures: column-major RGB texels, so a wall stripe reads memory in order.

pub(crate) mod builtin;
pub mod decode;
pub mod fallback;
pub mod generate;
pub(crate) mod key_tint;
pub(crate) mod pickup_art;
pub(crate) mod sheet;
pub mod sprite_art;

/// Edge length of one picture of the built-in sprite art (one view of one frame), shared by the
/// creatures' and the pickups' drawings.
pub const ART_SIZE: usize = 64;

use std::sync::Arc;

use crate::color::Rgb;

/// Levels kept per colour channel of a wall, floor or ceiling texel: 128 (7 bits), so a texel is
/// never more than one unit off its source — invisible. Procedural and photographic textures are
/// full of neighbours that differ by a single unit; merging them lets neighbouring terminal cells
/// share exact colours more often, which cuts the 24-bit stream by about 3 % of stock ratatui's
/// size (76.0 % → 73.6 % in `halfcast bench`). Coarser steps save far more truecolor bytes (16
/// levels: 59 %) at up to 8 units of error per channel; the 256-colour stream does not shrink.
pub const TEXEL_LEVELS: u16 = 128;

/// `v` rounded to the nearest of [`TEXEL_LEVELS`] evenly spaced levels (0 and 255 stay).
#[must_use]
#[inline]
pub fn posterize(v: u8) -> u8 {
    let steps = TEXEL_LEVELS - 1;
    let level = (u16::from(v) * steps + 127) / 255;
    (level * 255 / steps) as u8
}

/// A decoded image stored column by column (x-major), the order wall stripes read it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Texture {
    width: usize,
    height: usize,
    /// Shared: every clone of a world (one per SSH session) reads the same texels, so they are
    /// copied once and sit in the cache once.
    texels: Arc<[Rgb]>,
    /// Mean colour, kept for overviews (the minimap) that paint a whole surface in one colour.
    mean: Rgb,
}

impl Texture {
    /// Builds a texture from a function of (x, y), posterized to [`TEXEL_LEVELS`] per channel;
    /// generators, the decoder and tests all come through here.
    #[must_use]
    pub fn from_fn(width: usize, height: usize, mut f: impl FnMut(usize, usize) -> Rgb) -> Self {
        let mut texels = Vec::with_capacity(width * height);
        for x in 0..width {
            for y in 0..height {
                let c = f(x, y);
                texels.push(Rgb::new(posterize(c.r), posterize(c.g), posterize(c.b)));
            }
        }
        let mean = Rgb::mean(texels.iter().copied());
        Self {
            width,
            height,
            texels: texels.into(),
            mean,
        }
    }

    /// The mean colour of all texels.
    #[must_use]
    pub fn mean(&self) -> Rgb {
        self.mean
    }

    /// Decodes any image format the `image` crate was built with (PNG here), at most
    /// [`decode::MAX_TEXTURE_SIDE`] pixels a side (checked before decoding).
    ///
    /// # Errors
    /// The decoder's message when the bytes are not a readable image, or the image is empty or
    /// too large.
    pub fn decode(bytes: &[u8]) -> Result<Self, String> {
        let img = decode::decode_texture_image(bytes)?.to_rgb8();
        let (w, h) = (img.width() as usize, img.height() as usize);
        Ok(Self::from_fn(w, h, |x, y| {
            let p = img.get_pixel(x as u32, y as u32);
            Rgb::new(p[0], p[1], p[2])
        }))
    }

    /// Encodes as PNG (what the generator writes into `textures/`).
    ///
    /// # Errors
    /// The encoder's message (only on I/O-like failures inside `image`).
    pub fn to_png(&self) -> Result<Vec<u8>, String> {
        crate::png::rgb(self.width, self.height, |x, y| self.texel(x, y))
    }

    /// Width in texels.
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in texels.
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    /// The texel at (x, y); callers keep coordinates in range.
    #[must_use]
    #[inline]
    pub fn texel(&self, x: usize, y: usize) -> Rgb {
        self.texels[x * self.height + y]
    }

    /// Every texel, column after column (texel (x, y) at `x · height + y`): what a caster that
    /// keeps a texture's sizes across many pixels indexes.
    #[must_use]
    #[inline]
    pub fn texels(&self) -> &[Rgb] {
        &self.texels
    }

    /// One whole column, top to bottom: the slice a wall stripe samples.
    #[must_use]
    #[inline]
    pub fn column(&self, x: usize) -> &[Rgb] {
        &self.texels[x * self.height..(x + 1) * self.height]
    }

    /// Samples at (u, v) already reduced to [0, 1) (the floor caster's hot path).
    #[must_use]
    #[inline]
    pub fn sample_unit(&self, u: f64, v: f64) -> Rgb {
        let x = texel_index(u * self.width as f64);
        let y = texel_index(v * self.height as f64);
        self.texel(x.min(self.width - 1), y.min(self.height - 1))
    }

    /// Samples at texture coordinates (u, v) that wrap (floors repeat per cell).
    #[must_use]
    #[inline]
    pub fn sample_wrapped(&self, u: f64, v: f64) -> Rgb {
        let x = texel_index((u - u.floor()) * self.width as f64);
        let y = texel_index((v - v.floor()) * self.height as f64);
        self.texel(x.min(self.width - 1), y.min(self.height - 1))
    }
}

/// A texel index from a coordinate in texels, rounded down (0 for negatives and NaN). The
/// per-pixel samplers convert through this: `f64 as u32` is a clamp and one conversion on
/// x86-64, where `f64 as usize` is about eight instructions. Every caller keeps the index
/// within its texture (it clamps it, or the light map checks the coordinate first), so the two
/// agree wherever it matters: they differ only from 2³² up.
#[must_use]
#[inline]
pub fn texel_index(v: f64) -> usize {
    v as u32 as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_clone_reads_the_same_texels() {
        let a = Texture::from_fn(4, 3, |x, y| Rgb::new(x as u8 * 60, y as u8 * 60, 9));
        let b = a.clone();
        assert!(Arc::ptr_eq(&a.texels, &b.texels));
        assert_eq!(a, b);
        // So a world's clone (one per SSH session) copies no texels.
        let world = crate::World::default_world();
        let copy = world.clone();
        for (t, u) in world.textures.iter().zip(&copy.textures) {
            assert!(Arc::ptr_eq(&t.texels, &u.texels));
        }
    }

    #[test]
    fn texel_index_picks_what_a_usize_conversion_picks_once_clamped() {
        let values = [
            -1e300,
            -3.0,
            -0.5,
            -0.0,
            0.0,
            0.25,
            0.999,
            1.0,
            63.99,
            64.0,
            4e9,
            4294967296.5,
            1e19,
            1e300,
        ];
        for v in values
            .into_iter()
            .chain([f64::NAN, f64::INFINITY, f64::NEG_INFINITY])
        {
            for width in [1, 2, 64, 1 << 20] {
                assert_eq!(
                    texel_index(v).min(width - 1),
                    (v as usize).min(width - 1),
                    "{v} in {width}"
                );
            }
        }
    }

    #[test]
    fn columns_are_contiguous_top_to_bottom() {
        let t = Texture::from_fn(3, 4, |x, y| Rgb::new(x as u8 * 17, y as u8 * 17, 0));
        let p = posterize;
        assert_eq!(
            t.column(2),
            &[0, 17, 34, 51].map(|y| Rgb::new(p(34), p(y), 0))
        );
    }

    #[test]
    fn png_round_trip_keeps_every_texel() {
        let t = Texture::from_fn(5, 7, |x, y| Rgb::new((x * 40) as u8, (y * 30) as u8, 9));
        assert_eq!(Texture::decode(&t.to_png().unwrap()).unwrap(), t);
    }

    #[test]
    fn wrapped_sampling_repeats() {
        let t = Texture::from_fn(4, 4, |x, y| Rgb::new(x as u8 * 17, y as u8 * 17, 0));
        let p = posterize(17);
        assert_eq!(t.sample_wrapped(1.26, -0.74), Rgb::new(p, p, 0));
    }

    #[test]
    fn texels_keep_their_levels_per_channel_with_black_and_white_exact() {
        let levels: std::collections::BTreeSet<u8> = (0..=255u8).map(posterize).collect();
        assert_eq!(levels.len(), usize::from(TEXEL_LEVELS));
        assert_eq!((posterize(0), posterize(255)), (0, 255));
        let half_step = 255.0 / f64::from(TEXEL_LEVELS - 1) / 2.0;
        for v in 0..=255u8 {
            // The nearest level: never more than half a step away (one unit at 128 levels).
            let err = f64::from(posterize(v).abs_diff(v));
            assert!(err <= half_step.ceil(), "{v} -> {}", posterize(v));
            assert_eq!(
                posterize(posterize(v)),
                posterize(v),
                "levels are fixed points"
            );
        }
        let t = Texture::from_fn(1, 1, |_, _| Rgb::new(100, 7, 250));
        let c = t.texel(0, 0);
        assert!(c.r.abs_diff(100) <= 1 && c.g.abs_diff(7) <= 1 && c.b.abs_diff(250) <= 1);
        assert_eq!(c, Rgb::new(posterize(100), posterize(7), posterize(250)));
    }

    #[test]
    fn garbage_bytes_are_an_error_not_a_panic() {
        assert!(Texture::decode(b"not an image").is_err());
    }
}
