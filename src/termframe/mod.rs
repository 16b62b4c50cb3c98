//! A terminal frame as cells (grapheme, colours, underline colour, attributes): the common
//! ground for comparing PNG, ANSI and text frames, and the text form that snapshots pin.
//!
//! The cells, the cells text, the strict and loose diffs and reading bytes back are the
//! [`ratatui_cells`] crate's (this repository's second crate, for any ratatui app), re-exported
//! here under the names halfcast always had. What is halfcast's own: frames to and from
//! [`Framebuffer`] pixels ([`FramePixels`], [`CellRgb`]), the loose comparison that also knows
//! quadrant, sextant and octant cells ([`diff`], [`appearance`]), PNG frame files ([`load`],
//! [`parse_frame`]), the picture of a diff ([`highlight`]) and, with the `vt100` feature,
//! reading a `vt100` screen (`from_screen`).
//!
//! [`Framebuffer`]: crate::Framebuffer

mod cell_rgb;
mod highlight;
mod legacy_cells;
mod look;
mod parse;
mod pixels;
#[cfg(any(test, feature = "vt100"))]
mod screen;

pub use cell_rgb::{ratatui_rgb, rgb_colour, CellRgb};
pub use highlight::highlight;
pub use look::{appearance, diff};
pub use parse::{load, parse_frame, FrameFormat};
pub use pixels::FramePixels;
#[cfg(any(test, feature = "vt100"))]
pub use screen::{from_parser, from_screen};

pub use ratatui_cells::ansi::{from_ansi, from_ansi_sized, try_from_ansi, Screen};
pub use ratatui_cells::cells::{Glyph, TermCell};
pub use ratatui_cells::colour::{colour_name, named_colour};
pub use ratatui_cells::compare::{diff_by, diff_looks, CellDiff, DiffReport};
pub use ratatui_cells::format::{cell_code, from_buffer_debug, from_cells_text, style_words};
pub use ratatui_cells::limits::MAX_FRAME;

/// Most bytes a frame file may hold when read from disk: anything a person reviews fits, and a
/// runaway file is refused instead of read.
pub const MAX_FRAME_BYTES: u64 = 64 << 20;
/// The cells text of a frame ([`ratatui_cells::cells_text`]), under the name halfcast's callers
/// always used.
#[must_use]
pub fn to_cells_text(frame: &TermFrame) -> String {
    ratatui_cells::cells_text(frame)
}
/// The first line of the cells text: [`ratatui_cells::format::HEADER`].
pub use ratatui_cells::format::HEADER as CELLS_HEADER;
pub use ratatui_cells::TermFrame;

/// The strict comparison (every part of every cell), [`ratatui_cells::diff`]; this module's
/// [`diff`] compares looks, as `halfcast diff` does.
pub use ratatui_cells::diff as diff_strict;
