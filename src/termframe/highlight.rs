//! A picture of what changed between two frames, for `halfcast diff --out`.

use crate::color::Rgb;
use crate::render::framebuffer::Framebuffer;
use crate::termframe::{DiffReport, FramePixels, TermFrame};

/// A picture of the change: B's pixels where cells differ (tinted magenta), A dimmed to grey
/// elsewhere (A alone when the sizes differ).
#[must_use]
pub fn highlight(report: &DiffReport, a: &TermFrame, b: &TermFrame) -> Framebuffer {
    let base = if report.size_a == report.size_b { b } else { a };
    let mut fb = base.to_framebuffer();
    let mut changed = vec![false; base.cols * base.rows];
    for d in &report.differing {
        changed[d.y * base.cols + d.x] = true;
    }
    let (cell_w, cell_h) = fb.glyphs().cell_size();
    for y in 0..fb.height() {
        for x in 0..fb.width() {
            let p = fb.get(x, y);
            let mark = changed[(y / cell_h) * base.cols + x / cell_w];
            fb.set(
                x,
                y,
                if mark {
                    Rgb::new(p.r / 2 + 127, p.g / 3, p.b / 2 + 127)
                } else {
                    let l = p.luma() / 3;
                    Rgb::new(l, l, l)
                },
            );
        }
    }
    fb
}
