//! The pipeline's middle, in order: `cast` (rays through the grid; `height_cast` on `Hz` maps),
//! then `raster` (walls, floors, ceilings; `height_raster` on `Hz` maps) and `billboard`
//! (sprites) into the [`Framebuffer`], lit by `light`/`lightmap` and seen through a `view`.
//! A [`scene::Scene`] holds one frame's input; `frame` turns it into pixels.

pub(crate) mod billboard;
pub mod cast;
pub(crate) mod derivation;
pub(crate) mod dither_phase;
pub(crate) mod fast_floor;
pub(crate) mod frame;
pub(crate) mod framebuffer;
pub(crate) mod glyphs;
pub(crate) mod height_cast;
pub(crate) mod height_column;
pub(crate) mod height_raster;
// Only the game screen (`ui`) renders one world frame after frame.
#[cfg(feature = "ui")]
pub(crate) mod kept_background;
pub mod light;
pub(crate) mod plain_floor;
pub(crate) mod point_light;
pub(crate) mod raster;
pub(crate) mod scene;
pub mod sprite_projection;
pub mod view;

pub use framebuffer::Framebuffer;
// The heights projection and its per-column bands, as `Scene::render_frame` hands them out.
pub use height_cast::{Band, FaceSpan, Projection};
// Moving lights a caller hands to `Scene::with_lights`.
pub use point_light::PointLight;
// Where a wall at a distance lands on screen: what tests pin a frame's geometry against.
pub use glyphs::Glyphs;
pub use raster::{wall_span, WallSpan};
