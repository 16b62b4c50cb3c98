//! Framebuffer → one (top, bottom) code pair per cell at a colour level (mono: the shade character).

use super::level::ColorLevel;
use super::pairing::Alternating;
use super::palette::{Code, Palette};
use crate::encode::shade::shade_char;
use crate::render::framebuffer::Framebuffer;

/// The mono glyph of a cell: the shade-ramp character of its two pixels' mean luminance.
#[must_use]
#[inline]
pub fn mono_char(top: crate::Rgb, bottom: crate::Rgb) -> char {
    shade_char(((u16::from(top.luma()) + u16::from(bottom.luma())) / 2) as u8)
}

/// Slots in a [`CellCache`] (a power of two): 128 KiB, enough for a frame's common pixel pairs.
const CACHE_SLOTS: usize = 1 << 13;

/// Remembers recent (top, bottom) pixel pairs and their codes: the per-cell pair choice costs a
/// few hundred ns, and a frame repeats many pairs (flat floors, texels stretched over several cells).
/// The answer depends only on the pixels, so caching never changes the output.
#[derive(Debug, Clone)]
pub struct CellCache {
    slots: Vec<(u64, [Code; 2])>,
    /// The same for frames with dither phases: colours and shares, resolved per cell's phases.
    dithered: Vec<(u64, Alternating)>,
}

impl Default for CellCache {
    fn default() -> Self {
        Self {
            slots: vec![(u64::MAX, [0; 2]); CACHE_SLOTS],
            dithered: Vec::new(),
        }
    }
}

/// The cache key of a pixel pair and its slot.
#[inline]
fn key_of(t: crate::Rgb, b: crate::Rgb) -> (u64, usize) {
    let key = (u64::from(t.r) << 40)
        | (u64::from(t.g) << 32)
        | (u64::from(t.b) << 24)
        | (u64::from(b.r) << 16)
        | (u64::from(b.g) << 8)
        | u64::from(b.b);
    (
        key,
        (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - 13)) as usize,
    )
}

impl CellCache {
    /// The codes of pixels (`t`, `b`) at (x, y), from the cache or computed and stored.
    #[inline]
    fn cell(
        &mut self,
        palette: &Palette,
        t: crate::Rgb,
        b: crate::Rgb,
        x: usize,
        y: usize,
    ) -> [Code; 2] {
        if !palette.pairs_cells() {
            return palette.cell(t, b, x, y);
        }
        let (key, slot) = key_of(t, b);
        let entry = &mut self.slots[slot];
        if entry.0 != key {
            *entry = (key, palette.cell(t, b, x, y));
        }
        entry.1
    }

    /// The codes of pixels (`t`, `b`) with dither phases `phases`, when the palette pairs cells.
    #[inline]
    fn cell_dithered(
        &mut self,
        palette: &Palette,
        t: crate::Rgb,
        b: crate::Rgb,
        phase: u8,
    ) -> Option<[Code; 2]> {
        if !palette.pairs_cells() {
            return None;
        }
        if self.dithered.is_empty() {
            let none = Alternating {
                a: [0; 2],
                b: [0; 2],
                share: 0,
            };
            self.dithered = vec![(u64::MAX, none); CACHE_SLOTS];
        }
        let (key, slot) = key_of(t, b);
        let entry = &mut self.dithered[slot];
        if entry.0 != key {
            *entry = (key, palette.cell_dithered(t, b)?);
        }
        Some(entry.1.resolve(phase).map(u32::from))
    }
}

/// Fills `cells` (row-major, `width × cell_rows`) with what each cell should show.
///
/// Colour levels give `[top code, bottom code]`; mono gives `[char, 0]`. At 256 and 16 colours a
/// frame with dither phases (a rendered one) is drawn with [`Palette::cell_dithered`], thresholded
/// by each pixel's phase, so its patterns lie on the surfaces; a frame without (a finished frame
/// from elsewhere) gets one fixed pair per cell ([`Palette::cell`]).
pub fn quantize(palette: &Palette, fb: &Framebuffer, cells: &mut Vec<[Code; 2]>) {
    quantize_with(palette, fb, cells, &mut CellCache::default());
}

/// [`quantize`] reusing a cache across frames (what the live encoder does).
pub fn quantize_with(
    palette: &Palette,
    fb: &Framebuffer,
    cells: &mut Vec<[Code; 2]>,
    cache: &mut CellCache,
) {
    let (w, rows) = (fb.width(), fb.cell_rows());
    cells.clear();
    cells.reserve(w * rows);
    for cy in 0..rows {
        let (top, bottom) = (fb.row(2 * cy), fb.row(2 * cy + 1));
        match palette.level() {
            ColorLevel::Mono => cells.extend(
                top.iter()
                    .zip(bottom)
                    .map(|(&t, &b)| [u32::from(mono_char(t, b)), 0]),
            ),
            _ => match fb.phases() {
                Some(phases) if palette.pairs_cells() => {
                    let pt = &phases[2 * cy * w..];
                    cells.extend(top.iter().zip(bottom).enumerate().map(|(x, (&t, &b))| {
                        cache
                            .cell_dithered(palette, t, b, pt[x])
                            .unwrap_or_else(|| cache.cell(palette, t, b, x, 2 * cy))
                    }));
                }
                _ => cells.extend(
                    top.iter()
                        .zip(bottom)
                        .enumerate()
                        .map(|(x, (&t, &b))| cache.cell(palette, t, b, x, 2 * cy)),
                ),
            },
        }
    }
}
