//! What one frame shows: a loaded world seen through a camera, with the frame's view, light,
//! door positions and time — and the one call per output form a test or tool needs.
//!
//! ```
//! use halfcast::{Camera, Scene, World};
//!
//! let world = World::default_world();
//! let start = world.map.start;
//! let scene = Scene::new(&world, Camera::from_angle(start.pos(), start.angle_deg(), 66.0));
//!
//! let fb = scene.render(40, 12); // pixels: 40 × 24 (two per cell)
//! assert_eq!((fb.width(), fb.height()), (40, 24));
//! let buf = scene.to_buffer(40, 12); // ratatui cells: `▀`, fg = upper pixel, bg = lower
//! assert_eq!(buf[(0, 0)].symbol(), "▀");
//! let ansi = scene.to_ansi(40, 12); // what a truecolor terminal receives (full redraw)
//! assert!(ansi.contains("\x1b[38;2;"));
//! let png = scene.to_png(40, 12).unwrap(); // `render --format png`
//! assert!(png.starts_with(b"\x89PNG"));
//! let text = scene.to_cells_text(40, 12); // colour-aware text that snapshots pin
//! assert!(text.starts_with("halfcast-cells v1 40x12\n"));
//! // Every form shows the same frame.
//! assert_eq!(text, halfcast::snapshot::cells_text(&buf));
//! assert_eq!(text, halfcast::snapshot::cells_text(&fb));
//! ```

use crate::billboard::SpriteOutcome;
use crate::camera::Camera;
use crate::cast::{cast_with_doors, Cast};
use crate::door::DoorState;
use crate::framebuffer::Framebuffer;
use crate::height_cast::{cast_heights, Projection};
use crate::height_raster::rasterize_heights;
use crate::light::Lighting;
use crate::lightmap::LightMap;
use crate::raster::rasterize_frame;
use crate::view::View;
use crate::widget::HalfBlockView;
use crate::world::World;

/// The whole input of one frame (pure, no terminal, no clock): the same scene gives the same pixels.
#[derive(Debug, Clone, Copy)]
pub struct Scene<'a> {
    /// The world rendered.
    pub world: &'a World,
    /// The eye it is seen from.
    pub camera: Camera,
    /// Pitch and eye height; the default is level, standing.
    pub view: View,
    /// Fog, night and distance shading; [`Scene::new`] takes the map's `FOG`/`SHADE` lines.
    pub light: Lighting,
    /// How far each door is open; `None` draws every door shut.
    pub doors: Option<&'a DoorState>,
    /// Game time in seconds, which picks animation frames (passed in, never read from a clock).
    pub time: f64,
}

/// One rendered frame's by-products: the rays and what became of each sprite.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// The rays (and the traced column), as [`Scene::render_into`] returns them.
    pub cast: Cast,
    /// One outcome per world sprite, in world order.
    pub sprites: Vec<SpriteOutcome>,
}

impl<'a> Scene<'a> {
    /// Pairs a world with a camera: level standing view, the map's light, doors shut, time 0.
    #[must_use]
    pub fn new(world: &'a World, camera: Camera) -> Self {
        Self {
            world,
            camera,
            view: View::default(),
            light: world.lighting(),
            doors: None,
            time: 0.0,
        }
    }

    /// This scene seen with another pitch / eye height.
    #[must_use]
    pub fn with_view(mut self, view: View) -> Self {
        self.view = view;
        self
    }

    /// This scene under other light.
    #[must_use]
    pub fn with_light(mut self, light: Lighting) -> Self {
        self.light = light;
        self
    }

    /// This scene with doors open as `doors` says.
    #[must_use]
    pub fn with_doors(mut self, doors: &'a DoorState) -> Self {
        self.doors = Some(doors);
        self
    }

    /// This scene at game time `seconds` (animation).
    #[must_use]
    pub fn at_time(mut self, seconds: f64) -> Self {
        self.time = seconds;
        self
    }

    /// The lamp light map, when this scene is dark enough for lamps to show (night or falloff).
    #[must_use]
    pub fn lamp_light(&self) -> Option<&'a LightMap> {
        let lamps = &self.world.lightmap;
        (self.light.is_dark() && !lamps.is_empty()).then_some(lamps)
    }

    /// Casts and rasterizes into `fb` at its size; returns the rays (with `traced`'s full trace).
    pub fn render_into(&self, fb: &mut Framebuffer, traced: Option<usize>) -> Cast {
        self.render_frame(fb, traced).cast
    }

    /// [`Scene::render_into`], also reporting each sprite's projection and visibility.
    pub fn render_frame(&self, fb: &mut Framebuffer, traced: Option<usize>) -> Frame {
        let none = DoorState::none();
        let doors = self.doors.unwrap_or(&none);
        let map = &self.world.map;
        if map.has_heights() {
            // Steps, pits and lintels: each column keeps walking until its window of rows closes.
            let proj = Projection::new(&self.camera, &self.view, fb.width(), fb.height());
            let cast = cast_heights(map, doors, &self.camera, &proj, fb.width(), traced);
            let sprites = rasterize_heights(self, &cast, fb);
            return Frame { cast, sprites };
        }
        let cast = cast_with_doors(map, doors, &self.camera, fb.width(), traced);
        let sprites = rasterize_frame(self, &cast.columns, fb);
        Frame { cast, sprites }
    }

    /// Renders a fresh framebuffer for a `cols` × `rows`-cell view.
    #[must_use]
    pub fn render(&self, cols: u16, rows: u16) -> Framebuffer {
        let mut fb = Framebuffer::for_cells(cols, rows);
        self.render_into(&mut fb, None);
        fb
    }

    /// The frame as ratatui cells (`▀`, fg = upper pixel, bg = lower), as the TUI's view pane
    /// draws it: for tests of widgets and screens built around the view.
    #[must_use]
    pub fn to_buffer(&self, cols: u16, rows: u16) -> ratatui::buffer::Buffer {
        use ratatui::widgets::Widget;
        let area = ratatui::layout::Rect::new(0, 0, cols, rows);
        let mut buf = ratatui::buffer::Buffer::empty(area);
        HalfBlockView::new(&self.render(cols, rows)).render(area, &mut buf);
        buf
    }

    /// The bytes a truecolor terminal receives to show the frame in one full redraw (the same as
    /// `halfcast render --format ansi --colors truecolor`).
    #[must_use]
    pub fn to_ansi(&self, cols: u16, rows: u16) -> String {
        crate::output::ansi::to_ansi_truecolor(&self.render(cols, rows))
    }

    /// The frame as a PNG of `cols` × 2·`rows` pixels (`halfcast render --format png`).
    ///
    /// # Errors
    /// The PNG encoder's message (it does not fail for in-memory frames in practice).
    pub fn to_png(&self, cols: u16, rows: u16) -> Result<Vec<u8>, String> {
        self.render(cols, rows).to_png()
    }

    /// The frame in the colour-aware text form snapshots pin (`halfcast-cells v1`, see
    /// [`crate::snapshot::cells_text`]), so a test can `insta::assert_snapshot!` it.
    #[must_use]
    pub fn to_cells_text(&self, cols: u16, rows: u16) -> String {
        crate::snapshot::cells_text(&self.render(cols, rows))
    }
}
