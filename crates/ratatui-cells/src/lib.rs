#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod ansi;
mod assert;
mod cell;
pub mod colour;
pub mod compare;
mod error;
pub mod format;
mod frame;
mod glyph;
pub mod limits;
mod look;
mod stored;

pub use ansi::from_ansi_sized;
pub use assert::{assert_frames_eq, assert_frames_look_same};
pub use compare::diff;
pub use error::Error;
pub use format::cells_text;
pub use frame::TermFrame;

/// The parts of a [`TermFrame`]: its cells and their glyphs.
pub mod cells {
    pub use crate::cell::TermCell;
    pub use crate::glyph::{width_of, Glyph};
}

/// What [`assert_cells_snapshot!`] expands to; not part of the API.
#[doc(hidden)]
pub mod __private {
    pub use crate::stored::check_snapshot;
    pub use insta;
}
