//! Drawing a [`Scene`]: cast the rays (through `Hz` heights where the map has them), rasterize
//! walls, floors, ceilings and sprites into a [`Framebuffer`]. The frame's other forms (ratatui
//! cells, ANSI, PNG, snapshot text) are in `output::scene_forms`.

use crate::render::billboard::SpriteOutcome;
use crate::render::cast::{cast_with_doors, Cast};
use crate::render::framebuffer::Framebuffer;
use crate::render::height_cast::{cast_heights, Projection};
use crate::render::height_raster::rasterize_heights;
use crate::render::raster::rasterize_frame;
use crate::render::scene::Scene;

/// One rendered frame's by-products: the rays and what became of each sprite.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// The rays (and the traced column), as [`Scene::render_into`] returns them.
    pub cast: Cast,
    /// One outcome per world sprite, in world order.
    pub sprites: Vec<SpriteOutcome>,
}

impl Scene<'_> {
    /// Casts and rasterizes into `fb` at its size; returns the rays (with `traced`'s full trace).
    pub fn render_into(&self, fb: &mut Framebuffer, traced: Option<usize>) -> Cast {
        self.render_frame(fb, traced).cast
    }

    /// [`Scene::render_into`], also reporting each sprite's projection and visibility.
    pub fn render_frame(&self, fb: &mut Framebuffer, traced: Option<usize>) -> Frame {
        let doors = self.doors_or_shut();
        let map = &self.world.map;
        if map.has_heights() {
            // Steps, pits and lintels: each column keeps walking until its window of rows closes.
            let size = (fb.width(), fb.height());
            let proj =
                Projection::with_pixel_height(&self.camera, &self.view, size, fb.pixel_height());
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
}

#[cfg(test)]
mod tests {
    use crate::camera::Camera;
    use crate::map::parse_map;
    use crate::render::framebuffer::Framebuffer;
    use crate::render::glyphs::Glyphs;
    use crate::render::scene::Scene;
    use crate::world::{TextureSource, World};

    /// Without phases (truecolor and mono callers) every renderer draws the same picture and
    /// writes no phase plane; with them (the default) walls and sprites write theirs.
    #[test]
    fn a_frame_without_phases_is_the_same_picture_with_none_written() {
        let heights = parse_map(
            "heights.cub",
            include_bytes!("../../maps/heights.cub").as_slice(),
        )
        .unwrap();
        let heights = World::load(heights, &TextureSource::Embedded, false)
            .unwrap()
            .0;
        for world in [World::default_world(), heights] {
            let start = world.map.start;
            for angle in [0.0, 100.0, 200.0, 300.0] {
                let cam = Camera::from_angle(start.pos(), start.angle_deg() + angle, 66.0);
                for glyphs in [Glyphs::Half, Glyphs::Octant] {
                    let mut with = Framebuffer::for_glyphs(60, 20, glyphs);
                    let mut without = Framebuffer::for_glyphs(60, 20, glyphs);
                    without.set_phases_wanted(false);
                    Scene::new(&world, cam).render_into(&mut with, None);
                    Scene::new(&world, cam).render_into(&mut without, None);
                    assert_eq!(with, without, "{} at {angle}°", world.map.name);
                    assert!(without.phases().is_none(), "{}", world.map.name);
                    if angle == 0.0 {
                        assert!(with.phases().is_some(), "{}", world.map.name);
                    }
                }
            }
        }
        // A resize keeps the choice; turning phases off drops those written.
        let mut fb = Framebuffer::for_cells(10, 4);
        fb.set_phase(0, 0, 3);
        fb.set_phases_wanted(false);
        assert!(fb.phases().is_none());
        fb.resize_cells(12, 5, Glyphs::Sextant);
        fb.resize(30, 8);
        assert!(!fb.wants_phases());
    }
}
