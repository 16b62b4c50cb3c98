//! The pipeline's middle, in order: `cast` (rays through the grid; `height_cast` on `Hz` maps),
//! then `raster` (walls, floors, ceilings; `height_raster` on `Hz` maps) and `billboard`
//! (sprites) into the [`Framebuffer`], lit by `light`/`lightmap` and seen through a `view`.
//! A [`scene::Scene`] holds one frame's input; [`frame`] turns it into pixels.

pub mod billboard;
pub mod cast;
pub mod derivation;
pub mod dither_phase;
pub mod frame;
pub(crate) mod framebuffer;
pub mod height_cast;
pub mod height_raster;
pub mod lamp_reach;
pub mod light;
pub mod lightmap;
pub mod point_light;
pub mod raster;
pub mod scene;
pub mod view;

pub use framebuffer::Framebuffer;
