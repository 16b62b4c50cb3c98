//! Headless writers: a rendered frame as PNG, ANSI, plain text or ray JSON, any terminal frame
//! as a screenshot, and the [`Scene`](crate::Scene) methods that hand a frame out in each form.

pub mod ansi;
pub mod figure;
pub mod glyph_picture;
pub mod json;
pub(crate) mod scene_forms;
pub mod screenshot;
pub mod text;
