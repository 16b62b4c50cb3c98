//! Turns a framebuffer into the bytes one session's terminal receives: the project's byte-lean
//! encoder (`crate::encode`), at the session's colour level.

use super::color_level::ColorLevel;
use crate::encode::{self, EncodeOptions, Encoder};
use crate::framebuffer::Framebuffer;

/// The encoder's colour level for a session's level.
fn ladder(level: ColorLevel) -> encode::ColorLevel {
    match level {
        ColorLevel::Truecolor => encode::ColorLevel::TrueColor,
        ColorLevel::Ansi256 => encode::ColorLevel::Ansi256,
        ColorLevel::Ansi16 => encode::ColorLevel::Ansi16,
        ColorLevel::Mono => encode::ColorLevel::Mono,
    }
}

/// Remembers what the terminal shows so the next frame sends only what changed.
#[derive(Debug)]
pub struct FrameEncoder {
    level: ColorLevel,
    inner: Encoder,
}

impl FrameEncoder {
    /// An encoder whose first frame is a full redraw at `level`.
    #[must_use]
    pub fn new(level: ColorLevel) -> Self {
        Self {
            level,
            inner: Encoder::new(EncodeOptions::new(ladder(level))),
        }
    }

    /// Forget what the terminal shows (after a clear, a resize or a colour change).
    pub fn invalidate(&mut self, level: ColorLevel) {
        if level == self.level {
            self.inner.invalidate();
        } else {
            *self = Self::new(level);
        }
    }

    /// Appends the bytes that bring the terminal from the last frame to `fb`, drawn with its
    /// top-left cell at 0-based screen cell `origin` (column, row). Appends nothing if unchanged.
    pub fn encode(&mut self, fb: &Framebuffer, origin: (u16, u16), out: &mut Vec<u8>) {
        out.extend_from_slice(self.inner.encode(fb, origin.0, origin.1));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Rgb;

    fn screen(bytes: &[u8], cols: u16, rows: u16) -> vt100::Parser {
        let mut p = vt100::Parser::new(rows, cols, 0);
        p.process(bytes);
        p
    }

    #[test]
    fn truecolor_frame_round_trips_through_a_terminal_model() {
        let mut fb = Framebuffer::for_cells(4, 2);
        fb.set(1, 0, Rgb::new(10, 20, 30));
        fb.set(1, 1, Rgb::new(200, 100, 0));
        let mut enc = FrameEncoder::new(ColorLevel::Truecolor);
        let mut out = Vec::new();
        enc.encode(&fb, (2, 1), &mut out);
        let p = screen(&out, 10, 5);
        let cell = p.screen().cell(1, 3).expect("cell");
        assert_eq!(cell.contents(), "▀");
        assert_eq!(cell.fgcolor(), vt100::Color::Rgb(10, 20, 30));
        assert_eq!(cell.bgcolor(), vt100::Color::Rgb(200, 100, 0));
    }

    #[test]
    fn unchanged_frames_send_nothing_and_changes_arrive() {
        let mut fb = Framebuffer::for_cells(4, 3);
        let mut enc = FrameEncoder::new(ColorLevel::Ansi256);
        let mut out = Vec::new();
        enc.encode(&fb, (0, 0), &mut out);
        out.clear();
        enc.encode(&fb, (0, 0), &mut out);
        assert!(out.is_empty());
        fb.set(0, 5, Rgb::new(255, 255, 255));
        enc.encode(&fb, (0, 0), &mut out);
        assert!(!out.is_empty(), "a changed cell is sent");
        let p = screen(&out, 4, 3);
        let c = p.screen().cell(2, 0).expect("cell");
        let white = vt100::Color::Idx(231);
        let lower = if c.contents() == "▄" {
            c.fgcolor()
        } else {
            c.bgcolor()
        };
        assert_eq!(lower, white, "{:?}", c.contents());
        let text = String::from_utf8(out).expect("utf8");
        assert!(!text.contains(";2;"), "no 24-bit colour at 256 colours");
    }

    #[test]
    fn mono_sends_no_colour() {
        let fb = Framebuffer::for_cells(3, 1);
        let mut out = Vec::new();
        FrameEncoder::new(ColorLevel::Mono).encode(&fb, (0, 0), &mut out);
        let text = String::from_utf8(out).expect("utf8");
        assert!(!text.contains("38;") && !text.contains("48;"));
    }
}
