//! What one frame shows: a loaded world seen through a camera, with the frame's view, light,
//! door positions and time.

use crate::billboard::SpriteOutcome;
use crate::camera::Camera;
use crate::cast::{cast_with_doors, Cast};
use crate::door::DoorState;
use crate::framebuffer::Framebuffer;
use crate::light::Lighting;
use crate::lightmap::LightMap;
use crate::raster::rasterize_frame;
use crate::view::View;
use crate::world::World;

/// The whole input of one frame (pure, no terminal, no clock): the same scene gives the same pixels.
#[derive(Debug, Clone, Copy)]
pub struct Scene<'a> {
    pub world: &'a World,
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
        let cast = cast_with_doors(&self.world.map, doors, &self.camera, fb.width(), traced);
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
}
