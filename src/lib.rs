//! halfcast: a grid raycaster that renders into terminal-sized framebuffers, a ratatui widget
//! that shows them, and a byte-lean terminal encoder any ratatui app can use.
//!
//! The pipeline, one module per stage: [`map`] → [`Camera`] → [`cast`](render::cast) (pure DDA) →
//! [`raster`](render::raster) into a [`Framebuffer`] → [`encode`] (bytes for a terminal), [`widget`]
//! (ratatui) or the headless forms (`Scene::to_png`, `to_ansi`, `to_cells_text`).
//!
//! # Features
//!
//! | feature | what it adds | pulls in |
//! |---|---|---|
//! | *(none)* | engine, widgets, encoder, [`LeanBackend`], [`snapshot`], [`termframe`], [`replay`] files | ratatui (no backend), ratatui-cells, image, serde |
//! | `crossterm` | ratatui's crossterm backend; [`LeanBackend`] asks the terminal its size | crossterm |
//! | `scrolling-regions` | [`LeanBackend`]'s scrolling-region methods (when ratatui's feature of that name is on) | — |
//! | `vt100` | `termframe::from_screen` (cells from a `vt100` model of your own); re-exports `halfcast::vt100` | vt100 |
//! | `tui` | the interactive terminal (`halfcast play`) | crossterm, signal-hook, toml |
//! | `serve` | the SSH server (`halfcast serve`) | russh, tokio |
//! | `cli` (default, with all above) | the `halfcast` binary | clap |
//!
//! A library user writes `halfcast = { version = "0.1", default-features = false }` (plus
//! `features = ["crossterm"]` to run a stock ratatui terminal).
//!
//! # Render a frame
//!
//! A [`Scene`] (a [`World`], a [`Camera`] and options) is one frame's whole input; it renders to
//! every form a test or tool needs:
//!
//! ```
//! use halfcast::{Camera, Scene, World};
//!
//! let world = World::default_world();
//! let start = world.map.start;
//! let scene = Scene::new(&world, Camera::from_angle(start.pos(), start.angle_deg(), 66.0));
//! let fb = scene.render(80, 24); // Framebuffer: 80 × 48 pixels (two per cell)
//! let png = scene.to_png(80, 24).unwrap(); // PNG file contents
//! let ansi = scene.to_ansi(80, 24); // the bytes a truecolor terminal receives
//! let text = scene.to_cells_text(80, 24); // colour-aware text for insta snapshots
//! assert_eq!(fb, halfcast::Framebuffer::from_image_bytes(&png).unwrap());
//! assert!(ansi.contains('▀') && text.starts_with("ratatui-cells v1 80x24"));
//! ```
//!
//! # Embed the view in a ratatui app
//!
//! [`HalfBlockView`] draws a framebuffer at one cell per two stacked pixels; [`Minimap`] and
//! [`DebugPane`] show the map and a ray's DDA. Render the framebuffer at the pane's size:
//!
//! ```
//! use halfcast::{Camera, ColorLevel, Framebuffer, HalfBlockView, Minimap, Scene, World};
//! use ratatui::{backend::TestBackend, layout::{Constraint, Layout}, Terminal};
//!
//! let world = World::default_world();
//! let start = world.map.start;
//! let camera = Camera::from_angle(start.pos(), start.angle_deg(), 66.0);
//! let mut terminal = Terminal::new(TestBackend::new(60, 20)).unwrap();
//! terminal.draw(|frame| {
//!     let [view, map] = Layout::horizontal([Constraint::Fill(2), Constraint::Fill(1)])
//!         .areas(frame.area());
//!     let mut fb = Framebuffer::for_cells(view.width, view.height);
//!     let cast = Scene::new(&world, camera).render_into(&mut fb, None);
//!     // `.level(ColorLevel::Ansi256)` for a terminal without 24-bit colour.
//!     frame.render_widget(HalfBlockView::new(&fb).level(ColorLevel::TrueColor), view);
//!     frame.render_widget(Minimap::new(&world, &camera, &cast.columns), map);
//! }).unwrap();
//! assert_eq!(terminal.backend().buffer()[(0, 0)].symbol(), "▀");
//! ```
//!
//! `cargo run --example embed --no-default-features --features crossterm` is the same with a
//! real terminal, arrow keys and q.
//!
//! # Send fewer bytes: the lean backend
//!
//! [`LeanBackend`] is a drop-in ratatui backend over any `Write`: the same cells as
//! `CrosstermBackend`, with merged colour sequences, the cheapest cursor moves, the colour
//! ladder ([`ColorLevel`]) and one synchronized update per frame. One line switches an app:
//!
//! ```no_run
//! # fn main() -> std::io::Result<()> {
//! use halfcast::{ColorLevel, LeanBackend};
//! let mut terminal =
//!     ratatui::Terminal::new(LeanBackend::new(std::io::stdout(), ColorLevel::from_env()))?;
//! # Ok(()) }
//! ```
//!
//! # Pin a frame in a test
//!
//! [`snapshot::cells_text`] turns any frame (a framebuffer, a ratatui `Buffer`, the bytes a
//! terminal received) into colour-aware text for `insta::assert_snapshot!` or a stored snapshot;
//! [`snapshot::assert_png_golden`] compares a framebuffer with a golden PNG within a tolerance
//! (with no golden yet, it says to run once with `INSTA_UPDATE=always`). The text helpers are
//! the [`ratatui_cells`] crate's, for any ratatui app. `examples/snapshot.rs` pins a custom map
//! both ways.
//!
//! ```
//! use halfcast::{snapshot, Camera, Scene, Vec2, World};
//!
//! let world = World::default_world();
//! let scene = Scene::new(&world, Camera::from_angle(Vec2::new(8.5, 5.5), 30.0, 66.0));
//! let text = snapshot::cells_text(&scene.render(6, 3));
//! assert_eq!(text, scene.to_cells_text(6, 3));
//! // insta::assert_snapshot!(text);
//! ```
//!
//! # Replay a recording
//!
//! A `.hcr` recording ([`Replay`]) is a header (map, start, size, fps) and the input of every
//! frame; stepping a [`game::GameState`] through it at 1/fps seconds per frame gives exactly
//! the game that was recorded:
//!
//! ```
//! use std::sync::Arc;
//! use halfcast::game::{step, Action, GameState, Input};
//! use halfcast::replay::{FrameInput, Header, MapSource};
//! use halfcast::{Camera, Replay, Scene, Vec2, World};
//!
//! let header = Header {
//!     map: MapSource::Embedded, pos: Vec2::new(8.5, 5.5), angle_deg: 30.0, fov_deg: 66.0,
//!     size: (80, 24), fps: 30, seed: 0, speeds: Default::default(), glyphs: Default::default(),
//! };
//! let turn = FrameInput { input: Input::holding(&[Action::TurnLeft]), ..Default::default() };
//! let text = Replay { header, frames: vec![turn; 30] }.to_jsonl(); // what a .hcr file holds
//!
//! let replay = Replay::parse("turn.hcr", &text).unwrap();
//! let h = &replay.header;
//! let camera = Camera::from_angle(h.pos, h.angle_deg, h.fov_deg);
//! let mut state = GameState::new(Arc::new(World::default_world()), camera, 0);
//! for frame in &replay.frames {
//!     step(&mut state, &frame.input, 1.0 / f64::from(h.fps));
//! }
//! assert!(state.camera.angle_deg() > 60.0); // one second of turning left
//! let last = Scene::new(&state.world, state.camera).render(80, 24);
//! # let _ = last;
//! ```
#![warn(missing_docs)]
// Some docs name private constants and modules for readers of `--document-private-items`.
#![allow(rustdoc::private_intra_doc_links)]

// The library's API: the engine and what a user pins, embeds or replays with (the root
// re-exports below name the types most users need).
pub mod encode;
pub mod game;
pub mod map;
pub mod render;
pub mod replay;
pub mod snapshot;
pub mod termframe;
pub mod widget;
pub mod world;

// Public only because the binary (`src/cli`), `fuzz/`, examples, benches and the integration
// tests are crates of their own that drive them; not part of the library API (hidden from its
// docs; their types that users meet are re-exported at the root). docs/architecture.md lists
// who needs each.
#[doc(hidden)]
#[allow(missing_docs)]
#[cfg(feature = "cli")]
pub mod bench;
#[doc(hidden)]
pub mod camera;
#[doc(hidden)]
pub mod color;
#[doc(hidden)]
#[allow(missing_docs)]
#[cfg(feature = "ui")]
pub mod fuzzing;
#[doc(hidden)]
pub mod input_file;
#[doc(hidden)]
pub mod output;
// One player's game over any transport, paced to its link (the server's edges drive it).
#[doc(hidden)]
#[allow(missing_docs)]
#[cfg(feature = "serve")]
pub mod play;
#[doc(hidden)]
pub mod present;
#[doc(hidden)]
#[allow(missing_docs)]
#[cfg(feature = "serve")]
pub mod serve;
#[doc(hidden)]
pub mod texture;
// One column's ray as `halfcast trace` and the browser's `/trace.*` ask for it.
#[doc(hidden)]
pub mod trace_query;
#[doc(hidden)]
#[allow(missing_docs)]
#[cfg(feature = "tui")]
pub mod tui;
// The game screen shared by the local terminal, SSH sessions and replays.
#[doc(hidden)]
#[allow(missing_docs)]
#[cfg(feature = "ui")]
pub mod ui;

mod lean_backend;
mod png;
mod vec2;

/// The README's Rust examples, compiled and run as doc-tests so they keep working.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeExamples;

/// docs/library.md's Rust examples, compiled and run as doc-tests for the same reason.
#[cfg(doctest)]
#[doc = include_str!("../docs/library.md")]
pub struct LibraryDocExamples;

#[cfg(doctest)]
#[doc = include_str!("../docs/snapshots.md")]
pub struct SnapshotsDocExamples;

pub use camera::Camera;
pub use color::Rgb;
pub use encode::ColorLevel;
pub use lean_backend::LeanBackend;
pub use render::scene::Scene;
pub use render::view::View;
pub use render::{Framebuffer, Glyphs};
pub use replay::{Replay, ReplayError};
pub use vec2::Vec2;
pub use widget::{DebugPane, HalfBlockView, Minimap};
pub use world::World;

/// The `vt100` terminal model at the version `termframe::from_screen` reads, so a test that
/// builds its own `vt100::Parser` needs no second dependency.
#[cfg(feature = "vt100")]
pub use vt100;
