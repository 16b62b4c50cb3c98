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

pub use ratatui_cells::{
    cell_code, colour_name, diff_by, diff_looks, from_ansi, from_ansi_sized, from_buffer_debug,
    from_cells_text, named_colour, style_words, to_cells_text, try_from_ansi, CellDiff, DiffReport,
    Glyph, Screen, TermCell, TermFrame, CELLS_HEADER, MAX_FRAME, MAX_FRAME_BYTES,
};

/// The strict comparison (every part of every cell), [`ratatui_cells::diff`]; this module's
/// [`diff`] compares looks, as `halfcast diff` does.
pub use ratatui_cells::diff as diff_strict;
