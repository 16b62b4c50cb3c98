//! Byte-lean terminal output (pure: framebuffers in, bytes out; no terminal I/O here).
//!
//! - `level`: the colour ladder (truecolor → 256 → 16 → mono) and its detection.
//! - [`palette`]: pixel → colour code, from shared tables: the nearest entry, or `mixing`'s
//!   per-pixel mixes thresholded by the surfaces' dither phases.
//! - `encoder`: the live frame encoder (diff against what the terminal shows, minimal SGR and moves,
//!   synchronized output); `inline`: a whole frame as printable lines for `render --format ansi`.
//! - `pacer`: fitting the frame rate to a bandwidth cap.

pub(crate) mod cell_diff;
pub(crate) mod cells;
mod cursor;
pub(crate) mod encoder;
pub mod glyph_cell;
pub mod glyph_frame;
pub mod glyph_mask;
pub(crate) mod inline;
mod lane_split;
pub(crate) mod level;
#[cfg(test)]
mod mix_solver;
pub(crate) mod mix_table;
pub(crate) mod mixing;
mod number;
pub(crate) mod pacer;
pub mod palette;
mod plan;
pub(crate) mod quantize;
mod sgr;
pub(crate) mod shade;

pub use encoder::{EncodeOptions, Encoder, SYNC_BEGIN, SYNC_END};
// The cells a terminal should show for a framebuffer: the oracle that tests read a terminal
// model's screen against.
pub use inline::full_frame;
pub use level::{ColorLevel, ColourChoice, ColourReason};
pub use pacer::{parse_rate, Pacer};
pub use palette::Palette;
pub use quantize::quantize;
