//! The cells text format and the other text forms of a screen this crate reads.
//!
//! [`crate::cells_text`] writes the format; [`from_cells_text`] reads it back. It is plain
//! text a person reviews, first the glyph grid, then the style runs:
//!
//! ```text
//! ratatui-cells v1 12x2
//! "Tasks: 3    "
//! "> write     "
//! styles:
//! y0 x0-5 fg=cyan bold
//! y1 x0-6 fg=black bg=green reversed
//! ```
//!
//! - The first line is [`HEADER`] and the size, `COLSxROWS`.
//! - Each grid row is the row's glyphs between quotes (a wide character once, for both its
//!   columns). A row that would not read back cell for cell (a lone combining mark, a control
//!   character) is written in ASCII with `?` for each such cell, and the cell listed under
//!   `glyphs:` by its code points (`y3 x7 U+0065 U+0301`; `continuation` for a wide
//!   character's second column).
//! - A style run is `yROW xCOL` or `yROW xFIRST-LAST`, then the non-default parts
//!   ([`style_words`]): `fg=`, `bg=`, `ul=` (underline colour) as `green`, `idx2` or `#00cd00`
//!   ([`crate::colour::colour_name`]), and the attributes (`bold`, `dim`, `italic`,
//!   `underlined`, `slow_blink`, `rapid_blink`, `reversed`, `hidden`, `crossed_out`). Cells in
//!   no run have the default colours and no attributes.
//!
//! [`parse_frame`] reads any form this crate knows, recognised by content: cells text, a
//! ratatui `Buffer`'s `Debug` ([`from_buffer_debug`]), either inside an insta `.snap` file or a
//! `TestBackend`'s `Display` there ([`from_backend_display`]), ANSI bytes, plain text.

mod backend_display;
mod buffer_debug;
mod cells_text;
mod detect;
mod style;

pub use backend_display::from_backend_display;
pub use buffer_debug::from_buffer_debug;
pub use cells_text::{from_cells_text, HEADER};
pub use detect::{parse_frame, FrameFormat};
pub use style::{cell_code, style_words};

pub use cells_text::cells_text;
pub(crate) use detect::snapshot_body;
