//! Sprite sheets: RGBA texels (column-major, like wall textures) cut into views × frames.
//!
//! Walls stay on the opaque [`super::Texture`]; only sprites pay for alpha. A sheet of
//! `views` columns and `frames` rows holds one picture per (view, frame), all the same size.

use std::sync::Arc;

use crate::color::Rgb;
use crate::map::ColourKey;

/// A sprite image with transparency, possibly holding several views and animation frames.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SpriteSheet {
    width: usize,
    height: usize,
    /// Shared between clones, as [`super::Texture`]'s are.
    texels: Arc<[Rgb]>,
    /// 0 = see-through, 255 = opaque; same layout as `texels`.
    alpha: Arc<[u8]>,
    /// Mean colour of the mostly opaque texels, for overviews (the minimap).
    mean: Rgb,
    /// Per column, the rows from its first to its last texel that is not fully clear (empty
    /// for a clear column): a sprite stripe need not walk the clear rows above and below.
    opaque: Arc<[(u32, u32)]>,
}

impl SpriteSheet {
    /// Builds a sheet from a function of (x, y) giving colour and alpha (generators, tests).
    #[must_use]
    pub fn from_fn(
        width: usize,
        height: usize,
        mut f: impl FnMut(usize, usize) -> (Rgb, u8),
    ) -> Self {
        let mut texels = Vec::with_capacity(width * height);
        let mut alpha = Vec::with_capacity(width * height);
        for x in 0..width {
            for y in 0..height {
                let (c, a) = f(x, y);
                texels.push(c);
                alpha.push(a);
            }
        }
        let mostly = texels.iter().zip(&alpha).filter(|&(_, &a)| a >= 128);
        let mean = Rgb::mean(mostly.map(|(&c, _)| c));
        let opaque = alpha
            .chunks(height.max(1))
            .map(|column| {
                let first = column.iter().position(|&a| a > 0).unwrap_or(0);
                let end = column.iter().rposition(|&a| a > 0).map_or(0, |i| i + 1);
                (first as u32, end as u32)
            })
            .collect();
        Self {
            width,
            height,
            texels: texels.into(),
            alpha: alpha.into(),
            mean,
            opaque,
        }
    }

    /// The mean colour of the texels that are at least half opaque.
    #[must_use]
    pub fn mean(&self) -> Rgb {
        self.mean
    }

    /// Decodes an image; without an alpha channel `key` (black under [`ColourKey::Auto`]) is clear.
    ///
    /// # Errors
    /// The decoder's message, "image has no pixels", or an image over the size limit.
    pub fn decode(bytes: &[u8], key: ColourKey) -> Result<Self, String> {
        let img = super::decode::decode_texture_image(bytes)?;
        let has_alpha = img.color().has_alpha();
        let img = img.to_rgba8();
        let (w, h) = (img.width() as usize, img.height() as usize);
        let key = match key {
            ColourKey::Auto if !has_alpha => Some(Rgb::default()),
            ColourKey::Colour(c) => Some(c),
            _ => None,
        };
        Ok(Self::from_fn(w, h, |x, y| {
            let p = img.get_pixel(x as u32, y as u32);
            let c = Rgb::new(p[0], p[1], p[2]);
            let a = if key == Some(c) { 0 } else { p[3] };
            (c, a)
        }))
    }

    /// Encodes as an RGBA PNG (what the generator writes into `textures/sprites/`).
    ///
    /// # Errors
    /// The encoder's message.
    pub fn to_png(&self) -> Result<Vec<u8>, String> {
        crate::png::rgba(self.width, self.height, |x, y| self.texel(x, y))
    }

    /// Width in texels (all views side by side).
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in texels (all frames stacked).
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    /// Colour and alpha at (x, y).
    #[must_use]
    #[inline]
    pub fn texel(&self, x: usize, y: usize) -> (Rgb, u8) {
        let i = x * self.height + y;
        (self.texels[i], self.alpha[i])
    }

    /// One column's colours and alphas, top to bottom (the slice a sprite stripe reads).
    #[must_use]
    #[inline]
    pub fn column(&self, x: usize) -> (&[Rgb], &[u8]) {
        let r = x * self.height..(x + 1) * self.height;
        (&self.texels[r.clone()], &self.alpha[r])
    }

    /// The rows of column `x` from its first to its last texel that is not fully clear, as a
    /// range (empty when the whole column is clear).
    #[must_use]
    #[inline]
    pub fn opaque_rows(&self, x: usize) -> std::ops::Range<usize> {
        let (first, end) = self.opaque.get(x).copied().unwrap_or_default();
        first as usize..end as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_column_knows_its_rows_from_the_first_to_the_last_texel_not_clear() {
        // Column 0 clear; column 1 faint at rows 1 and 4 (clear between); column 2 all opaque.
        let s = SpriteSheet::from_fn(3, 6, |x, y| {
            let a = match x {
                0 => 0,
                1 if y == 1 || y == 4 => 3,
                1 => 0,
                _ => 255,
            };
            (Rgb::new(1, 2, 3), a)
        });
        assert!(s.opaque_rows(0).is_empty());
        assert_eq!(s.opaque_rows(1), 1..5);
        assert_eq!(s.opaque_rows(2), 0..6);
        assert!(s.opaque_rows(3).is_empty(), "past the last column");
    }

    #[test]
    fn a_clone_reads_the_same_texels() {
        let a = SpriteSheet::from_fn(4, 3, |x, y| (Rgb::new(x as u8, y as u8, 0), 200));
        let b = a.clone();
        assert!(Arc::ptr_eq(&a.texels, &b.texels) && Arc::ptr_eq(&a.alpha, &b.alpha));
        assert_eq!(a, b);
    }

    #[test]
    fn png_round_trip_keeps_alpha() {
        let s = SpriteSheet::from_fn(3, 2, |x, y| {
            (Rgb::new(x as u8, y as u8, 7), (x * 100) as u8)
        });
        assert_eq!(
            SpriteSheet::decode(&s.to_png().unwrap(), ColourKey::Auto).unwrap(),
            s
        );
    }

    #[test]
    fn images_without_alpha_use_the_key_colour() {
        let t = crate::texture::Texture::from_fn(2, 1, |x, _| {
            if x == 0 {
                Rgb::default()
            } else {
                Rgb::new(255, 0, 255)
            }
        });
        let png = t.to_png().unwrap();
        let auto = SpriteSheet::decode(&png, ColourKey::Auto).unwrap();
        assert_eq!((auto.texel(0, 0).1, auto.texel(1, 0).1), (0, 255));
        let magenta = SpriteSheet::decode(&png, ColourKey::Colour(Rgb::new(255, 0, 255))).unwrap();
        assert_eq!((magenta.texel(0, 0).1, magenta.texel(1, 0).1), (255, 0));
        let none = SpriteSheet::decode(&png, ColourKey::None).unwrap();
        assert_eq!((none.texel(0, 0).1, none.texel(1, 0).1), (255, 255));
    }
}
