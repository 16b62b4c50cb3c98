//! halfcast: a grid raycaster that renders into terminal-sized framebuffers.
//!
//! The pipeline, one module per stage: [`map`] → [`camera`] → [`cast`] (pure DDA) →
//! [`raster`] into a [`framebuffer::Framebuffer`] → [`output`] writers (PNG, ANSI, text, JSON).

pub mod camera;
pub mod cast;
pub mod color;
pub mod framebuffer;
pub mod map;
pub mod output;
pub mod raster;
pub mod scene;
pub mod serve;
pub mod snapshot;
pub mod texture;
pub mod vec2;
pub mod world;

pub use camera::Camera;
pub use color::Rgb;
pub use framebuffer::Framebuffer;
pub use scene::Scene;
pub use vec2::Vec2;
pub use world::World;
