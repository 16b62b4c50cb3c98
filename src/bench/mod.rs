//! The pieces of `halfcast bench` that need no clock: camera paths, the stock-ratatui byte
//! reference, the zlib meter, the colour figures (S-CIELAB) and the report's JSON shape (the timing loop lives in the binary).

pub mod glyph_grid;
pub(crate) mod path;
pub(crate) mod reference;
pub(crate) mod report;
pub mod scielab;
pub(crate) mod zlib;

pub use path::{camera_path, BenchScene};
pub use reference::RatatuiReference;
pub use report::{ColourFigures, HalfcastFigures, RatatuiFigures, Report, Run};
pub use zlib::ZlibMeter;
