//! Turns a framebuffer into the bytes one session's terminal receives.
//!
//! STAND-IN: the encoder branch (`src/encode/`) brings the byte-lean per-cell diff encoder and
//! the real colour ladder. This one re-sends whole rows that changed since the last frame, which
//! is correct but far from lean. When merging, replace the body of [`FrameEncoder`] (keep its
//! three methods) with the encoder; the session code only calls `new`, `invalidate` and `encode`.

use std::fmt::Write;

use super::color_level::ColorLevel;
use crate::color::Rgb;
use crate::framebuffer::Framebuffer;

/// Begin/end synchronized update (DEC 2026), so a frame never shows half-drawn.
const SYNC_BEGIN: &str = "\x1b[?2026h";
const SYNC_END: &str = "\x1b[?2026l";

/// Remembers what the terminal shows so the next frame sends only what changed.
#[derive(Debug, Clone)]
pub struct FrameEncoder {
    level: ColorLevel,
    prev: Option<Framebuffer>,
}

impl FrameEncoder {
    /// An encoder whose first frame is a full redraw at `level`.
    #[must_use]
    pub fn new(level: ColorLevel) -> Self {
        Self { level, prev: None }
    }

    /// Forget what the terminal shows (after a clear, a resize or a colour change).
    pub fn invalidate(&mut self, level: ColorLevel) {
        self.level = level;
        self.prev = None;
    }

    /// Appends the bytes that bring the terminal from the last frame to `fb`, drawn with its
    /// top-left cell at 0-based screen cell `origin` (column, row). Appends nothing if unchanged.
    pub fn encode(&mut self, fb: &Framebuffer, origin: (u16, u16), out: &mut Vec<u8>) {
        let prev = self
            .prev
            .as_ref()
            .filter(|p| p.width() == fb.width() && p.height() == fb.height());
        let mut s = String::new();
        for cy in 0..fb.cell_rows() {
            let (a, b) = (2 * cy, 2 * cy + 1);
            if prev.is_some_and(|p| p.row(a) == fb.row(a) && p.row(b) == fb.row(b)) {
                continue;
            }
            let _ = write!(
                s,
                "\x1b[{};{}H",
                usize::from(origin.1) + cy + 1,
                usize::from(origin.0) + 1
            );
            row(fb, cy, self.level, &mut s);
        }
        if !s.is_empty() {
            out.extend_from_slice(SYNC_BEGIN.as_bytes());
            out.extend_from_slice(s.as_bytes());
            out.extend_from_slice(b"\x1b[0m");
            out.extend_from_slice(SYNC_END.as_bytes());
        }
        match &mut self.prev {
            Some(p) if p.width() == fb.width() && p.height() == fb.height() => {
                p.clone_from(fb);
            }
            _ => self.prev = Some(fb.clone()),
        }
    }
}

/// One cell row: `▀` with fg = upper pixel, bg = lower; SGRs only when a colour changes.
fn row(fb: &Framebuffer, cy: usize, level: ColorLevel, s: &mut String) {
    if level == ColorLevel::Mono {
        s.push_str("\x1b[0m");
        for cx in 0..fb.width() {
            let (up, low) = fb.cell(cx, cy);
            s.push(shade((u16::from(up.luma()) + u16::from(low.luma())) / 2));
        }
        return;
    }
    let mut last: Option<(String, String)> = None;
    for cx in 0..fb.width() {
        let (up, low) = fb.cell(cx, cy);
        let (fg, bg) = (sgr(up, level, true), sgr(low, level, false));
        if last.as_ref().map(|l| &l.0) != Some(&fg) {
            s.push_str(&fg);
        }
        if last.as_ref().map(|l| &l.1) != Some(&bg) {
            s.push_str(&bg);
        }
        last = Some((fg, bg));
        s.push('▀');
    }
}

/// A luminance 0–255 as an ASCII shade, dark to light.
fn shade(luma: u16) -> char {
    const RAMP: &[u8] = b" .:-=+*#%@";
    let i = usize::from(luma) * (RAMP.len() - 1) / 255;
    char::from(RAMP[i.min(RAMP.len() - 1)])
}

fn sgr(c: Rgb, level: ColorLevel, fg: bool) -> String {
    match level {
        ColorLevel::Truecolor | ColorLevel::Mono => {
            format!(
                "\x1b[{};2;{};{};{}m",
                if fg { 38 } else { 48 },
                c.r,
                c.g,
                c.b
            )
        }
        ColorLevel::Ansi256 => {
            let q = |v: u8| (u16::from(v) * 5 + 127) / 255;
            let n = 16 + 36 * q(c.r) + 6 * q(c.g) + q(c.b);
            format!("\x1b[{};5;{n}m", if fg { 38 } else { 48 })
        }
        ColorLevel::Ansi16 => {
            let i = nearest16(c);
            let base = match (fg, i >= 8) {
                (true, false) => 30,
                (true, true) => 82,
                (false, false) => 40,
                (false, true) => 92,
            };
            format!("\x1b[{}m", base + i)
        }
    }
}

/// The nearest of the 16 ANSI colours (xterm's defaults), by squared RGB distance.
fn nearest16(c: Rgb) -> usize {
    const PALETTE: [(i32, i32, i32); 16] = [
        (0, 0, 0),
        (205, 0, 0),
        (0, 205, 0),
        (205, 205, 0),
        (0, 0, 238),
        (205, 0, 205),
        (0, 205, 205),
        (229, 229, 229),
        (127, 127, 127),
        (255, 0, 0),
        (0, 255, 0),
        (255, 255, 0),
        (92, 92, 255),
        (255, 0, 255),
        (0, 255, 255),
        (255, 255, 255),
    ];
    let (r, g, b) = (i32::from(c.r), i32::from(c.g), i32::from(c.b));
    (0..16)
        .min_by_key(|&i| {
            let (pr, pg, pb) = PALETTE[i];
            (pr - r).pow(2) + (pg - g).pow(2) + (pb - b).pow(2)
        })
        .unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn unchanged_frames_send_nothing_and_changed_rows_only() {
        let mut fb = Framebuffer::for_cells(4, 3);
        let mut enc = FrameEncoder::new(ColorLevel::Ansi256);
        let mut out = Vec::new();
        enc.encode(&fb, (0, 0), &mut out);
        out.clear();
        enc.encode(&fb, (0, 0), &mut out);
        assert!(out.is_empty());
        fb.set(0, 5, Rgb::new(255, 255, 255));
        enc.encode(&fb, (0, 0), &mut out);
        let text = String::from_utf8(out).expect("utf8");
        assert!(text.contains("\x1b[3;1H") && !text.contains("\x1b[1;1H"));
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
