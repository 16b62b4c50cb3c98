#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod ansi;
mod assert;
mod cell;
mod colour;
mod diff;
mod frame;
mod glyph;
mod limits;
mod look;
mod parse;
mod ratatui_debug;
mod stored;
mod text;
mod text_v1;
mod update;

pub use ansi::{from_ansi, from_ansi_sized, try_from_ansi, Screen};
pub use assert::{assert_frames_eq, assert_frames_look_same};
pub use cell::TermCell;
pub use colour::{colour_name, named_colour, parse_colour_name, xterm_rgb};
pub use diff::{diff, diff_by, diff_looks, CellDiff, DiffReport, LISTED_CELLS};
pub use frame::TermFrame;
pub use glyph::{width_of, Glyph};
pub use limits::{MAX_FRAME, MAX_FRAME_BYTES};
pub use parse::{parse_frame, FrameFormat};
pub use ratatui_debug::from_buffer_debug;
pub use stored::check_stored_snapshot;
pub use text::{cell_code, cells_text, from_cells_text, style_words, to_cells_text, CELLS_HEADER};
pub use update::{update_requested, UPDATE_ENV};
