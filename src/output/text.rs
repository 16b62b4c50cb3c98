//! A plain-ASCII view: one character per cell from the cell's brightness.

use crate::encode::shade::shade_char;
use crate::render::framebuffer::Framebuffer;

/// One line per cell row, each cell shaded by the mean luminance of its two pixels.
#[must_use]
pub fn to_text(fb: &Framebuffer) -> String {
    let mut out = String::with_capacity((fb.width() + 1) * fb.cell_rows());
    for cy in 0..fb.cell_rows() {
        for cx in 0..fb.width() {
            let (a, b) = fb.cell(cx, cy);
            let luma = (u16::from(a.luma()) + u16::from(b.luma())) / 2;
            out.push(shade_char(luma as u8));
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    #[test]
    fn black_is_space_and_white_is_at() {
        assert_eq!(shade_char(0), ' ');
        assert_eq!(shade_char(255), '@');
        let mut fb = Framebuffer::for_cells(2, 1);
        fb.set(1, 0, Rgb::new(255, 255, 255));
        fb.set(1, 1, Rgb::new(255, 255, 255));
        assert_eq!(to_text(&fb), " @\n");
    }
}
