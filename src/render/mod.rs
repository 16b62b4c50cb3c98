//! The pipeline's middle, in order: `cast` (rays through the grid; `height_cast` on `Hz` maps),
//! then `raster` (walls, floors, ceilings; `height_raster` on `Hz` maps) and `billboard`
//! (sprites) into the [`Framebuffer`], lit by `light`/`lightmap` and seen through a `view`.
//! A [`scene::Scene`] holds one frame's input; [`frame`] turns it into pixels.

pub(crate) mod billboard;
pub mod cast;
pub mod derivation;
pub(crate) mod dither_phase;
pub(crate) mod fast_floor;
pub(crate) mod frame;
pub(crate) mod framebuffer;
pub mod glyphs;
pub mod height_cast;
pub(crate) mod height_column;
pub(crate) mod height_raster;
pub mod light;
pub mod point_light;
pub mod raster;
pub(crate) mod scene;
pub mod sprite_projection;
pub mod view;

pub use framebuffer::Framebuffer;
pub use glyphs::Glyphs;
