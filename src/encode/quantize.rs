//! Framebuffer → one (top, bottom) code pair per cell at a colour level (mono: the shade character).

use super::level::ColorLevel;
use super::palette::{Code, Palette};
use crate::framebuffer::Framebuffer;
use crate::output::text::shade_char;

/// The mono glyph of a cell: the shade-ramp character of its two pixels' mean luminance.
#[must_use]
#[inline]
pub fn mono_char(top: crate::Rgb, bottom: crate::Rgb) -> char {
    shade_char(((u16::from(top.luma()) + u16::from(bottom.luma())) / 2) as u8)
}

/// Fills `cells` (row-major, `width × cell_rows`) with what each cell should show.
///
/// Colour levels give `[top code, bottom code]`; mono gives `[char, 0]`.
pub fn quantize(palette: &Palette, fb: &Framebuffer, cells: &mut Vec<[Code; 2]>) {
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
            _ => cells.extend(
                top.iter()
                    .zip(bottom)
                    .enumerate()
                    .map(|(x, (&t, &b))| palette.cell(t, b, x, 2 * cy)),
            ),
        }
    }
}
