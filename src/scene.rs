//! What one frame shows: a loaded world seen through a camera.

use crate::camera::Camera;
use crate::cast::{cast, Cast};
use crate::framebuffer::Framebuffer;
use crate::raster::rasterize;
use crate::world::World;

/// A world and a camera: the whole input of one frame (pure, no terminal, no clock).
#[derive(Debug, Clone, Copy)]
pub struct Scene<'a> {
    pub world: &'a World,
    pub camera: Camera,
}

impl<'a> Scene<'a> {
    /// Pairs a world with a camera.
    #[must_use]
    pub fn new(world: &'a World, camera: Camera) -> Self {
        Self { world, camera }
    }

    /// Casts and rasterizes into `fb` at its size; returns the rays (with `traced`'s full trace).
    pub fn render_into(&self, fb: &mut Framebuffer, traced: Option<usize>) -> Cast {
        let cast = cast(&self.world.map, &self.camera, fb.width(), traced);
        rasterize(self, &cast.columns, fb);
        cast
    }

    /// Renders a fresh framebuffer for a `cols` × `rows`-cell view.
    #[must_use]
    pub fn render(&self, cols: u16, rows: u16) -> Framebuffer {
        let mut fb = Framebuffer::for_cells(cols, rows);
        self.render_into(&mut fb, None);
        fb
    }
}
