//! The half-block frame as a truecolor terminal would receive it in one full redraw.
//!
//! Kept for callers of the first API; the bytes now come from the encoder's planner
//! ([`crate::encode::full_frame`]), which also serves the other colour levels.

use crate::encode::{full_frame, EncodeOptions};
use crate::render::framebuffer::Framebuffer;

/// Each cell as a half block with exact 24-bit colours, rows ending in a reset and a newline.
#[must_use]
pub fn to_ansi_truecolor(fb: &Framebuffer) -> String {
    String::from_utf8(full_frame(fb, &EncodeOptions::default()))
        .expect("the encoder writes ASCII escapes and half-block glyphs only")
}
