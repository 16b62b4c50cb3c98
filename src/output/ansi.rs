//! The half-block frame as a truecolor terminal would receive it in one full redraw.

use std::fmt::Write;

use crate::framebuffer::Framebuffer;

/// Each cell as `▀` with fg = upper pixel and bg = lower pixel; colours sent only when they change.
#[must_use]
pub fn to_ansi_truecolor(fb: &Framebuffer) -> String {
    let mut out = String::new();
    for cy in 0..fb.cell_rows() {
        let mut last = None;
        for cx in 0..fb.width() {
            let (up, low) = fb.cell(cx, cy);
            if last.map(|(u, _)| u) != Some(up) {
                let _ = write!(out, "\x1b[38;2;{};{};{}m", up.r, up.g, up.b);
            }
            if last.map(|(_, l)| l) != Some(low) {
                let _ = write!(out, "\x1b[48;2;{};{};{}m", low.r, low.g, low.b);
            }
            last = Some((up, low));
            out.push('▀');
        }
        out.push_str("\x1b[0m\n");
    }
    out
}
