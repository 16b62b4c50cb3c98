//! Reading frame files: PNG (half-block cells) here, every text form (cells text, a ratatui
//! `Buffer`'s `Debug`, insta snapshots of either, ANSI, plain text) by [`ratatui_cells`].

use std::path::Path;

use ratatui_cells::format::FrameFormat as Format;

use crate::color::Rgb;
use crate::render::framebuffer::Framebuffer;
use crate::termframe::{FramePixels, TermFrame, MAX_FRAME, MAX_FRAME_BYTES};

/// What kind of frame file was read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameFormat {
    /// A PNG of COLS × 2·ROWS pixels.
    Png,
    /// ANSI escape sequences, read through a terminal model.
    Ansi,
    /// The cells text (glyph grid and style runs), or one of halfcast's older forms of it.
    Cells,
    /// A ratatui `Buffer`'s `Debug` form (what `insta::assert_debug_snapshot!(buffer)` pins).
    BufferDebug,
    /// Plain text, one character per cell.
    Text,
}

impl From<Format> for FrameFormat {
    fn from(f: Format) -> Self {
        match f {
            Format::Ansi => Self::Ansi,
            Format::Cells => Self::Cells,
            Format::BufferDebug => Self::BufferDebug,
            // A `TestBackend`'s `Display` holds text only.
            _ => Self::Text,
        }
    }
}

/// Reads a frame file of any supported kind, recognised by content, not by name.
///
/// # Errors
/// An unreadable or oversized file, a FIFO or device, a broken PNG or cells text, a frame over [`MAX_FRAME`],
/// with the path in the message.
pub fn load(path: &Path) -> Result<(TermFrame, FrameFormat), String> {
    let bytes = crate::input_file::read_regular_capped(path, MAX_FRAME_BYTES)
        .map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    parse_frame(&bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// Parses a frame file's bytes (what [`load`] does after reading; the fuzz targets call it).
///
/// # Errors
/// A broken PNG or cells text, a frame over [`MAX_FRAME`], bytes that are not UTF-8 text.
pub fn parse_frame(bytes: &[u8]) -> Result<(TermFrame, FrameFormat), String> {
    if bytes.starts_with(b"\x89PNG") {
        let (mc, mr) = MAX_FRAME;
        let img = crate::texture::decode::decode_within(bytes, mc as u32, 2 * mr as u32)?.to_rgb8();
        let (w, h) = (img.width() as usize, img.height() as usize);
        if h % 2 != 0 {
            return Err(format!(
                "PNG height {h} is odd; frames are COLS x 2*ROWS pixels"
            ));
        }
        let mut fb = Framebuffer::new(w, h);
        for (x, y, p) in img.enumerate_pixels() {
            fb.set(x as usize, y as usize, Rgb::new(p[0], p[1], p[2]));
        }
        return Ok((TermFrame::from_framebuffer(&fb), FrameFormat::Png));
    }
    let Ok(text) = std::str::from_utf8(bytes) else {
        return Err("not a PNG and not UTF-8 text".into());
    };
    if let Some(older) = super::legacy_cells::read_legacy(text) {
        return older.map(|frame| (frame, FrameFormat::Cells));
    }
    ratatui_cells::format::parse_frame(bytes)
        .map(|(frame, format)| (frame, format.into()))
        .map_err(|e| e.to_string())
}
