//! Per-pixel palette mixes read from one lookup table shared by every encoder and SSH session.
//!
//! Each colour is shown as palette entry `a`, or `b` on a share of its pixels (in sixteenths),
//! chosen to look right to a person at a terminal (see `docs/colour.md`): at a normal seat the eye
//! resolves single half-block pixels in lightness but blurs colour over a few, so `a` and `b` are
//! kept close to the colour in lightness (each pixel's own error is what shows) and their mix
//! carries its hue and chroma. Which pixels show `b` is decided by a threshold per pixel tied to the
//! surface it shows ([`crate::render::dither_phase`]), or, where no surface wrote one, by the
//! pixel's half of its cell — never by where the cell is on screen.
//!
//! The answer depends on the colour only: the search (`mix_solver`, in the tests) works it out for
//! every 6-bit-per-channel bin ahead of time, and [`super::mix_table`] ships the answers in the
//! binary, so encoding reads a table and never searches.

use crate::color::Rgb;

/// Bits per channel of a table index (64³ bins of 4×4×4 sRGB values).
pub const BITS: u32 = 6;

/// Bins in a table.
pub const BINS: usize = 1 << (3 * BITS);

/// The bin of colour `c`.
#[must_use]
#[inline]
pub fn bin_of(c: Rgb) -> usize {
    let shift = 8 - BITS;
    (usize::from(c.r >> shift) << (2 * BITS))
        | (usize::from(c.g >> shift) << BITS)
        | usize::from(c.b >> shift)
}

/// Steps of a share: thresholds and shares are in sixteenths.
pub const SHARES: u8 = 16;

/// A colour's mix: entry `a`, and entry `b` on `share` sixteenths of the pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mix {
    /// The entry most pixels show.
    pub a: u8,
    /// The entry shown where a pixel's threshold is below `share`.
    pub b: u8,
    /// Sixteenths of pixels that show `b` (0 = all `a`).
    pub share: u8,
}

impl Mix {
    /// The entry a pixel with threshold `t` (0–15) shows.
    #[must_use]
    #[inline]
    pub fn pick(self, t: u8) -> u8 {
        if t < self.share {
            self.b
        } else {
            self.a
        }
    }

    /// The mix as `a | b << 8 | share << 16`.
    #[must_use]
    pub fn pack(self) -> u32 {
        u32::from(self.a) | (u32::from(self.b) << 8) | (u32::from(self.share) << 16)
    }

    /// The mix [`Mix::pack`] packed.
    #[must_use]
    #[inline]
    pub fn unpack(v: u32) -> Self {
        Self {
            a: v as u8,
            b: (v >> 8) as u8,
            share: (v >> 16) as u8,
        }
    }
}
