//! Colour codes per level: exact 24-bit, or xterm-256 / ANSI-16 entries from shared lookup tables:
//! the nearest entry for single colours, mixes (`super::mixing`) for pictures.

use std::sync::{Arc, OnceLock};

use super::level::ColorLevel;
use super::mix_table::{self, MixTable};
use super::mixing::{Mix, SHARES};
use crate::color::Rgb;

/// A colour as the terminal is told it: packed `0xRRGGBB` at truecolor, a palette index otherwise.
pub type Code = u32;

/// The terminal's default colour (after `ESC[m`); never produced from a pixel.
pub const DEFAULT: Code = 0xFFFF_FFFE;

/// A colour the encoder does not know (after `invalidate`); never equal to a real one.
pub const UNKNOWN: Code = 0xFFFF_FFFF;

/// Bits per channel of the lookup table index (32 × 32 × 32 entries, 32 KiB: fits in cache).
const LUT_BITS: u32 = 5;
const LUT_SIDE: usize = 1 << LUT_BITS;

/// The six channel levels of the xterm 6×6×6 cube (indices 16–231).
pub const CUBE_LEVELS: [u8; 6] = [0, 95, 135, 175, 215, 255];

/// xterm's default RGB for the 16 ANSI colours (what the 16-colour level matches against).
pub const ANSI16: [Rgb; 16] = [
    Rgb::new(0, 0, 0),
    Rgb::new(205, 0, 0),
    Rgb::new(0, 205, 0),
    Rgb::new(205, 205, 0),
    Rgb::new(0, 0, 238),
    Rgb::new(205, 0, 205),
    Rgb::new(0, 205, 205),
    Rgb::new(229, 229, 229),
    Rgb::new(127, 127, 127),
    Rgb::new(255, 0, 0),
    Rgb::new(0, 255, 0),
    Rgb::new(255, 255, 0),
    Rgb::new(92, 92, 255),
    Rgb::new(255, 0, 255),
    Rgb::new(0, 255, 255),
    Rgb::new(255, 255, 255),
];

/// The xterm RGB of palette index `i` (0–15 as [`ANSI16`], then cube, then greys).
#[must_use]
pub fn xterm_rgb(i: u8) -> Rgb {
    match i {
        0..=15 => ANSI16[usize::from(i)],
        16..=231 => {
            let n = usize::from(i - 16);
            Rgb::new(
                CUBE_LEVELS[n / 36],
                CUBE_LEVELS[(n / 6) % 6],
                CUBE_LEVELS[n % 6],
            )
        }
        _ => {
            let g = 8 + 10 * (i - 232);
            Rgb::new(g, g, g)
        }
    }
}

/// Maps pixels to codes for one level. The lookup tables are built once per process and shared,
/// so every encoder and SSH session reuses them.
#[derive(Debug, Clone)]
pub struct Palette {
    level: ColorLevel,
    /// The nearest entry per 5-bit-per-channel bin and the level's mix tables (`None` at
    /// truecolor and mono).
    tables: Option<Arc<Tables>>,
    /// Channel value → lookup-table bin (rounded, so 0 and 255 sit on bin centres).
    bin: [u8; 256],
}

/// A level's shared tables.
#[derive(Debug)]
struct Tables {
    /// The nearest entry (OKLab) per 5-bit-per-channel bin: single colours (interface text,
    /// stock ratatui's reference).
    near: Vec<u8>,
    /// Mixes in sixteenths, for pixels whose surface wrote a threshold.
    fine: MixTable,
    /// Mixes of none, half or all, for pixels no surface wrote a threshold for (floors,
    /// ceilings, frames from elsewhere): each cell's upper pixel shows `b` at half and over, its
    /// lower one at all.
    halves: MixTable,
}

impl Palette {
    /// The palette for `level`.
    #[must_use]
    pub fn new(level: ColorLevel) -> Self {
        static LUT_256: OnceLock<Arc<Tables>> = OnceLock::new();
        static LUT_16: OnceLock<Arc<Tables>> = OnceLock::new();
        let tables: Option<Arc<Tables>> = match level {
            ColorLevel::Ansi256 => Some(Arc::clone(
                LUT_256.get_or_init(|| Arc::new(build_tables(ColorLevel::Ansi256))),
            )),
            ColorLevel::Ansi16 => Some(Arc::clone(
                LUT_16.get_or_init(|| Arc::new(build_tables(ColorLevel::Ansi16))),
            )),
            ColorLevel::TrueColor | ColorLevel::Mono => None,
        };
        let mut bin = [0u8; 256];
        for (v, b) in bin.iter_mut().enumerate() {
            *b = ((v * (LUT_SIDE - 1) + 127) / 255) as u8;
        }
        Self { level, tables, bin }
    }

    /// The level this palette serves.
    #[must_use]
    pub fn level(&self) -> ColorLevel {
        self.level
    }

    /// The code for a single colour `c`: exact at truecolor, else the nearest palette entry.
    #[must_use]
    #[inline]
    pub fn code(&self, c: Rgb) -> Code {
        let Some(t) = &self.tables else {
            return (u32::from(c.r) << 16) | (u32::from(c.g) << 8) | u32::from(c.b);
        };
        u32::from(t.near[self.bin_of(c)])
    }

    /// The lookup-table bin of a colour.
    #[inline]
    fn bin_of(&self, c: Rgb) -> usize {
        let bin = |v: u8| usize::from(self.bin[usize::from(v)]);
        (bin(c.r) << (2 * LUT_BITS)) | (bin(c.g) << LUT_BITS) | bin(c.b)
    }

    /// Whether cells are drawn with mixes ([`Palette::cell_at`]): [`ColorLevel::mixes`].
    #[must_use]
    #[inline]
    pub fn mixes(&self) -> bool {
        self.level.mixes()
    }

    /// The `[top, bottom]` codes of a cell showing pixels `top` over `bottom` whose upper pixel
    /// has dither phase `phase` (written by the surface it shows, or
    /// `NEUTRAL_PHASE` where none did).
    ///
    /// The answer depends on the pixels and the phase only, never on the cell's position; at
    /// truecolor (and mono) each pixel gets [`Palette::code`].
    #[must_use]
    #[inline]
    pub fn cell_at(&self, top: Rgb, bottom: Rgb, phase: u8) -> [Code; 2] {
        match &self.tables {
            Some(t) => {
                if phase == crate::render::framebuffer::NEUTRAL_PHASE {
                    [
                        u32::from(t.halves.mix(top).pick(HALF_TOP)),
                        u32::from(t.halves.mix(bottom).pick(HALF_BOTTOM)),
                    ]
                } else {
                    let th = phase >> 4;
                    [
                        u32::from(t.fine.mix(top).pick(th)),
                        u32::from(t.fine.mix(bottom).pick((th + SHARES / 2) % SHARES)),
                    ]
                }
            }
            None => [self.code(top), self.code(bottom)],
        }
    }

    /// [`Palette::cell_at`] for a cell no surface wrote a phase for (a frame from elsewhere).
    #[must_use]
    #[inline]
    pub fn cell(&self, top: Rgb, bottom: Rgb) -> [Code; 2] {
        self.cell_at(top, bottom, crate::render::framebuffer::NEUTRAL_PHASE)
    }

    /// The mix of colour `c` where a surface wrote thresholds (`None` at truecolor and mono).
    #[must_use]
    pub fn mix_of(&self, c: Rgb) -> Option<Mix> {
        self.tables.as_ref().map(|t| t.fine.mix(c))
    }

    /// The mix of colour `c` where no surface wrote thresholds: none, half or all of the pixels
    /// show `b` (`None` at truecolor and mono).
    #[must_use]
    pub fn half_mix_of(&self, c: Rgb) -> Option<Mix> {
        self.tables.as_ref().map(|t| t.halves.mix(c))
    }

    /// The RGB a code shows (the xterm default for palette indices).
    #[must_use]
    #[inline]
    pub fn rgb(&self, code: Code) -> Rgb {
        if self.tables.is_none() {
            Rgb::new((code >> 16) as u8, (code >> 8) as u8, code as u8)
        } else {
            xterm_rgb(code as u8)
        }
    }
}

/// Thresholds of a cell's upper and lower pixel where no surface wrote one (with the
/// none/half/all mixes: the upper pixel shows `b` from half, the lower one only at all).
const HALF_TOP: u8 = 0;
const HALF_BOTTOM: u8 = SHARES / 2;

/// For every bin centre, the nearest entry in OKLab; and the mix tables.
fn build_tables(level: ColorLevel) -> Tables {
    let candidates = &mix_table::entries(level);
    let labs: Vec<[f32; 3]> = candidates.iter().map(|&i| oklab(xterm_rgb(i))).collect();
    let centre = |i: usize| ((i * 255 + (LUT_SIDE - 1) / 2) / (LUT_SIDE - 1)) as u8;
    let mut near = vec![0u8; LUT_SIDE * LUT_SIDE * LUT_SIDE];
    for r in 0..LUT_SIDE {
        for g in 0..LUT_SIDE {
            for b in 0..LUT_SIDE {
                let lab = oklab(Rgb::new(centre(r), centre(g), centre(b)));
                // Strict `<` keeps the lower index on ties.
                let mut best = (f32::MAX, candidates[0]);
                for (k, p) in labs.iter().enumerate() {
                    let d = crate::color::lab_dist2(lab, *p);
                    if d < best.0 {
                        best = (d, candidates[k]);
                    }
                }
                near[(r * LUT_SIDE + g) * LUT_SIDE + b] = best.1;
            }
        }
    }
    Tables {
        near,
        fine: MixTable::from_bytes(mix_table::shipped(level)[0]),
        halves: MixTable::from_bytes(mix_table::shipped(level)[1]),
    }
}

/// sRGB → OKLab (Björn Ottosson's perceptual space), for nearest-colour matching.
#[must_use]
pub fn oklab(c: Rgb) -> [f32; 3] {
    crate::color::oklab(c.linear())
}

/// A cheap perceptual distance ("redmean" weighted RGB), scaled so black↔white ≈ 255.
///
/// Used per cell by the lossy `delta` lever, where OKLab would be too slow.
#[must_use]
#[inline]
pub fn distance(a: Rgb, b: Rgb) -> u32 {
    let rmean = (u32::from(a.r) + u32::from(b.r)) / 2;
    let dr = i32::from(a.r) - i32::from(b.r);
    let dg = i32::from(a.g) - i32::from(b.g);
    let db = i32::from(a.b) - i32::from(b.b);
    let d2 = (((512 + rmean) * (dr * dr) as u32) >> 8)
        + 4 * (dg * dg) as u32
        + (((767 - rmean) * (db * db) as u32) >> 8);
    // d2 of black↔white is 9·255²; divide by 9 to land on a 0..255 scale.
    ((d2 / 9) as f64).sqrt() as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_256_level_never_uses_the_theme_colours() {
        let p = Palette::new(ColorLevel::Ansi256);
        for v in (0..=255).step_by(5) {
            for c in [
                Rgb::new(v, 0, 0),
                Rgb::new(v, v, v),
                Rgb::new(0, v, 255 - v),
            ] {
                assert!(p.code(c) >= 16);
            }
        }
    }

    #[test]
    fn palette_colours_map_to_themselves_or_a_near_twin() {
        // Two entries can share a table bin (cube grey 95 and ramp grey 98), so a few map to a twin.
        let p = Palette::new(ColorLevel::Ansi256);
        let mut exact = 0;
        for i in 16..=255u8 {
            let c = xterm_rgb(i);
            let got = p.rgb(p.code(c));
            assert!(distance(got, c) <= 8, "index {i}: {got:?}");
            exact += usize::from(got == c);
        }
        assert!(exact >= 225, "{exact}");
        let p = Palette::new(ColorLevel::Ansi16);
        assert_eq!(p.code(Rgb::new(0, 0, 0)), 0);
        assert_eq!(p.code(Rgb::new(255, 255, 255)), 15);
        assert_eq!(p.code(Rgb::new(250, 10, 10)), 9);
    }

    #[test]
    fn truecolor_codes_are_exact() {
        let p = Palette::new(ColorLevel::TrueColor);
        let c = Rgb::new(1, 2, 3);
        assert_eq!(p.code(c), 0x010203);
        assert_eq!(p.rgb(0x010203), c);
    }

    #[test]
    fn xterm_indices_follow_the_cube_and_ramp() {
        assert_eq!(xterm_rgb(16), Rgb::new(0, 0, 0));
        assert_eq!(xterm_rgb(231), Rgb::new(255, 255, 255));
        assert_eq!(xterm_rgb(196), Rgb::new(255, 0, 0));
        assert_eq!(xterm_rgb(232), Rgb::new(8, 8, 8));
        assert_eq!(xterm_rgb(255), Rgb::new(238, 238, 238));
    }

    #[test]
    fn distance_is_zero_for_equal_and_about_255_for_black_white() {
        let w = Rgb::new(255, 255, 255);
        assert_eq!(distance(w, w), 0);
        let d = distance(Rgb::default(), w);
        assert!((250..=256).contains(&d), "{d}");
    }
}
