//! halfcast: a grid raycaster that renders into terminal-sized framebuffers.
//!
//! The pipeline, one module per stage: [`map`] → [`camera`] → [`cast`] (pure DDA) →
//! [`raster`] into a [`framebuffer::Framebuffer`] → [`output`] writers (PNG, ANSI, text, JSON).
//!
//! A [`Scene`] (a world, a camera and options) is one frame's whole input; it renders to every
//! form a test or tool needs, and [`snapshot`] pins what it shows:
//!
//! ```
//! use halfcast::{Camera, Scene, World};
//!
//! let world = World::default_world();
//! let start = world.map.start;
//! let scene = Scene::new(&world, Camera::from_angle(start.pos(), start.angle_deg(), 66.0));
//! let fb = scene.render(80, 24); // Framebuffer: 80 × 48 pixels
//! let buf = scene.to_buffer(80, 24); // ratatui Buffer of `▀` cells
//! let ansi = scene.to_ansi(80, 24); // the bytes a truecolor terminal receives
//! let png = scene.to_png(80, 24).unwrap(); // PNG file contents
//! let text = scene.to_cells_text(80, 24); // colour-aware text for insta snapshots
//! assert_eq!(halfcast::snapshot::cells_text(&buf), text);
//! assert_eq!(fb, halfcast::Framebuffer::from_image_bytes(&png).unwrap());
//! // The terminal shows what the framebuffer holds (compared by appearance: `▀` a/b = `▄` b/a).
//! let shown = halfcast::termframe::from_ansi(ansi.as_bytes());
//! assert!(halfcast::termframe::diff(&shown, &(&fb).into()).is_equal());
//! ```

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
pub mod dither_phase;
pub mod encode;
pub mod framebuffer;
pub mod fuzzing;
pub mod game;
pub mod input_file;
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

/// The README's Rust examples, compiled and run as doc-tests so they keep working.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeExamples;

pub use camera::Camera;
pub use color::Rgb;
pub use framebuffer::Framebuffer;
pub use scene::Scene;
pub use vec2::Vec2;
pub use view::View;
pub use world::World;
