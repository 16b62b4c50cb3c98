//! What one frame shows: a loaded world seen through a camera, with the frame's view, light,
//! door positions and time. The calls that draw it, one per output form a test or tool needs,
//! live in [`crate::render::frame`], so the rasterizers read a scene without importing back.
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
//! assert!(text.starts_with("ratatui-cells v1 40x12\n"));
//! // Every form shows the same frame.
//! assert_eq!(text, halfcast::snapshot::cells_text(&buf));
//! assert_eq!(text, halfcast::snapshot::cells_text(&fb));
//! ```

use crate::camera::Camera;
use crate::render::light::Lighting;
use crate::render::point_light::PointLight;
use crate::render::view::View;
use crate::world::door::DoorState;
use crate::world::lightmap::LightMap;
use crate::world::sprite::Sprite;
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
    /// Sprites of this frame only (items, creatures, shots), drawn after and sorted with the
    /// world's own; empty unless [`Scene::with_sprites`] gives some.
    pub sprites: &'a [Sprite],
    /// Moving lights of this frame (projectiles), shown when the world is dark; none by default.
    pub lights: &'a [PointLight],
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
            sprites: &[],
            lights: &[],
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

    /// This scene with `sprites` drawn too (the game's items, creatures and shots this frame),
    /// depth-sorted with the world's sprites and hidden by walls and steps the same way.
    #[must_use]
    pub fn with_sprites(mut self, sprites: &'a [Sprite]) -> Self {
        self.sprites = sprites;
        self
    }

    /// Every sprite of the frame: the world's, then this frame's ([`SpriteOutcome`] indices
    /// count through both in this order).
    ///
    /// [`SpriteOutcome`]: crate::render::billboard::SpriteOutcome
    pub fn all_sprites(&self) -> impl Iterator<Item = &'a Sprite> {
        self.world.sprites.iter().chain(self.sprites)
    }

    /// Sprite `i` of [`Scene::all_sprites`].
    #[must_use]
    pub fn sprite(&self, i: usize) -> Option<&'a Sprite> {
        let n = self.world.sprites.len();
        if i < n {
            self.world.sprites.get(i)
        } else {
            self.sprites.get(i - n)
        }
    }

    /// This scene at game time `seconds` (animation).
    #[must_use]
    pub fn at_time(mut self, seconds: f64) -> Self {
        self.time = seconds;
        self
    }

    /// This scene with moving lights (e.g. projectiles) that brighten what is near them at night.
    #[must_use]
    pub fn with_lights(mut self, lights: &'a [PointLight]) -> Self {
        self.lights = lights;
        self
    }

    /// The doors as the rays meet them: every door shut when the scene was given none.
    #[must_use]
    pub(crate) fn doors_or_shut(&self) -> &'a DoorState {
        static SHUT: DoorState = DoorState::none();
        self.doors.unwrap_or(&SHUT)
    }

    /// The moving lights that show in this frame: all of them when the world is dark, else none.
    #[must_use]
    pub fn point_lights(&self) -> &'a [PointLight] {
        if self.light.is_dark() {
            self.lights
        } else {
            &[]
        }
    }

    /// The lamp light map, when this scene is dark enough for lamps to show (night or falloff).
    #[must_use]
    pub fn lamp_light(&self) -> Option<&'a LightMap> {
        let lamps = &self.world.lightmap;
        (self.light.is_dark() && !lamps.is_empty()).then_some(lamps)
    }
}
