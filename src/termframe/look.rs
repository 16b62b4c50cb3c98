//! The loose comparison `halfcast diff` makes: what the screen shows, knowing that a quadrant,
//! sextant or octant mask and its complement with the colours swapped draw the same picture.

use crate::encode::glyph_mask::{full_mask, glyph, mask_of};
use crate::render::glyphs::Glyphs;
use crate::termframe::{DiffReport, Glyph, TermCell, TermFrame};

/// A cell's visible content in canonical form: [`TermCell::appearance`] (`▀`/`▄`/space/`█`),
/// and for a block character of the finer glyph settings the form whose first pixel is the
/// background. Cells with attributes or an underline colour are their own form.
#[must_use]
pub fn appearance(cell: &TermCell) -> TermCell {
    if !cell.is_unadorned() {
        return cell.clone();
    }
    let mut chars = cell.glyph.as_str().chars();
    let (Some(g), None) = (chars.next(), chars.next()) else {
        return cell.clone();
    };
    if matches!(g, '▀' | '▄' | ' ' | '█') {
        return cell.appearance();
    }
    for set in [Glyphs::Octant, Glyphs::Sextant] {
        if let Some(m) = mask_of(set, g) {
            if m & 1 != 0 {
                let flipped = glyph(set, !m & full_mask(set));
                return TermCell::new(Glyph::from(flipped), cell.bg, cell.fg);
            }
            return cell.clone();
        }
    }
    cell.clone()
}

/// Compares by appearance (so `▀` a/b equals `▄` b/a, and a mask equals its complement with
/// the colours swapped), every visible part of a cell counting: grapheme, colours as named,
/// underline colour, attributes. Frames of different sizes differ entirely. For the strict
/// comparison (every part of every cell, as `assert_frames_eq` makes), see
/// [`super::diff_strict`].
#[must_use]
pub fn diff(a: &TermFrame, b: &TermFrame) -> DiffReport {
    ratatui_cells::compare::diff_by(a, b, appearance)
}
