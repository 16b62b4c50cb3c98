//! halfcast: a grid raycaster that renders into terminal-sized framebuffers.
//!
//! The pipeline, one module per stage: [`map`] → [`camera`] → [`cast`] (pure DDA) →
//! [`raster`] into a [`framebuffer::Framebuffer`] → [`output`] writers (PNG, ANSI, text, JSON).

pub mod bench;
// World features: sprites, doors, light, vertical view.
pub mod billboard;
pub mod door;
pub mod light;
pub mod lightmap;
pub mod sprite;
pub mod view;

pub mod camera;
pub mod cast;
pub mod color;
pub mod encode;
pub mod framebuffer;
pub mod game;
pub mod map;
pub mod output;
pub mod present;
pub mod raster;
pub mod replay;
pub mod scene;
pub mod serve;
pub mod snapshot;
pub mod termframe;
pub mod texture;
pub mod tui;
pub mod vec2;
pub mod widget;
pub mod world;

pub use camera::Camera;
pub use color::Rgb;
pub use framebuffer::Framebuffer;
pub use scene::Scene;
pub use vec2::Vec2;
pub use view::View;
pub use world::World;
