//! Headless writers: a rendered frame as PNG, ANSI, plain text or ray JSON.

pub mod ansi;
pub mod figure;
pub mod json;
pub mod png;
pub mod text;
