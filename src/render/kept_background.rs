//! A frame's walls, floors and ceilings kept for the next frame. On a server every view shows
//! the other players moving, but a player who stands still, or is between two key taps, sees
//! the same walls as last frame: only the sprites moved. Casting the rays and painting the
//! background again was most of such a frame's render; copying it back is a few thousand
//! instructions.

use crate::camera::Camera;
use crate::color::Rgb;
use crate::render::cast::{cast_with_doors, Cast};
use crate::render::frame::Frame;
use crate::render::framebuffer::Framebuffer;
use crate::render::glyphs::Glyphs;
use crate::render::light::Lighting;
use crate::render::raster::{rasterize_background, rasterize_sprites};
use crate::render::scene::Scene;
use crate::render::{view::View, PointLight};
use crate::world::door::DoorState;

/// The last background painted, with everything it was painted from. Kept by whoever renders
/// one world frame after frame (an SSH session, the game, a replay). The world is known only by
/// its address: its sprites may change in place (they are not background), but a caller that
/// changes its map, textures or lights in place, or drops it while keeping this, calls
/// [`KeptBackground::forget`].
#[derive(Debug, Default)]
pub(crate) struct KeptBackground {
    /// What the kept background was painted from, and its rays (none: nothing kept).
    last: Option<(Key, Cast)>,
    pixels: Vec<Rgb>,
    phases: Vec<u8>,
    /// Frames whose background was copied back rather than painted, for tests.
    reused: usize,
}

/// Everything the background depends on (see [`rasterize_background`]).
#[derive(Debug, Clone)]
struct Key {
    world: usize,
    camera: Camera,
    view: View,
    light: Lighting,
    doors: Option<DoorState>,
    lights: Vec<PointLight>,
    traced: Option<usize>,
    size: (usize, usize),
    glyphs: Glyphs,
    phases: bool,
}

impl Key {
    fn of(scene: &Scene, fb: &Framebuffer, traced: Option<usize>) -> Self {
        Self {
            world: std::ptr::from_ref(scene.world) as usize,
            camera: scene.camera,
            view: scene.view,
            light: scene.light,
            doors: scene.doors.cloned(),
            lights: scene.point_lights().to_vec(),
            traced,
            size: (fb.width(), fb.height()),
            glyphs: fb.glyphs(),
            phases: fb.wants_phases(),
        }
    }

    /// Whether this frame's background would be the one painted from this key: compared in
    /// place, so a frame that reuses it copies nothing to find out. Moving lights count only
    /// where they show (the world is dark): in daylight a shot in flight changes no wall.
    fn is(&self, scene: &Scene, fb: &Framebuffer, traced: Option<usize>) -> bool {
        let Self {
            world,
            camera,
            view,
            light,
            doors,
            lights,
            traced: kept_traced,
            size,
            glyphs,
            phases,
        } = self;
        *world == std::ptr::from_ref(scene.world) as usize
            && *camera == scene.camera
            && *view == scene.view
            && *light == scene.light
            && doors.as_ref() == scene.doors
            && lights.as_slice() == scene.point_lights()
            && *kept_traced == traced
            && *size == (fb.width(), fb.height())
            && *glyphs == fb.glyphs()
            && *phases == fb.wants_phases()
    }
}

impl KeptBackground {
    /// Drops what is kept: the next frame paints its background afresh.
    pub(crate) fn forget(&mut self) {
        self.last = None;
    }

    /// How many frames reused the kept background.
    #[cfg(test)]
    pub(crate) fn reused(&self) -> usize {
        self.reused
    }
}

impl Scene<'_> {
    /// [`Scene::render_frame`], copying the background (walls, floors, ceilings, their phases,
    /// and the rays) from `kept` when this frame's would be the same, else painting it and
    /// keeping it; the sprites are drawn over it either way. Maps with `Hz` heights, whose
    /// sprites are drawn between the bands, are always rendered afresh.
    pub(crate) fn render_frame_kept(
        &self,
        fb: &mut Framebuffer,
        traced: Option<usize>,
        kept: &mut KeptBackground,
    ) -> Frame {
        if self.world.map.has_heights() {
            kept.forget();
            return self.render_frame(fb, traced);
        }
        let cast = match &kept.last {
            Some((key, cast)) if key.is(self, fb, traced) => {
                kept.reused += 1;
                // A view no pixel wide has no rows to copy.
                let w = fb.width().max(1);
                for (y, row) in kept.pixels.chunks_exact(w).enumerate() {
                    fb.row_mut(y).copy_from_slice(row);
                }
                // A view with no pixels has no phases to copy (and gets no plane, as when painted).
                if fb.wants_phases() && !kept.phases.is_empty() {
                    fb.phases_mut().copy_from_slice(&kept.phases);
                }
                cast.clone()
            }
            _ => {
                let map = &self.world.map;
                let doors = self.doors_or_shut();
                let cast = cast_with_doors(map, doors, &self.camera, fb.width(), traced);
                rasterize_background(self, &cast.columns, fb);
                kept.pixels.clear();
                kept.pixels.extend_from_slice(fb.pixels());
                kept.phases.clear();
                if fb.wants_phases() {
                    kept.phases
                        .extend_from_slice(fb.phases().unwrap_or_default());
                }
                kept.last = Some((Key::of(self, fb, traced), cast.clone()));
                cast
            }
        };
        let sprites = rasterize_sprites(self, &cast.columns, fb);
        Frame { cast, sprites }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vec2::Vec2;
    use crate::world::World;

    /// One frame's inputs, each changed on its own by the steps below.
    #[derive(Clone)]
    struct Inputs {
        camera: Camera,
        view: View,
        night: bool,
        falloff: f64,
        doors: DoorState,
        lights: Vec<PointLight>,
        time: f64,
        sprite_at: Vec2,
        cells: (u16, u16),
        glyphs: Glyphs,
        phases: bool,
        traced: usize,
    }

    fn render(
        world: &World,
        i: &Inputs,
        fb: &mut Framebuffer,
        kept: Option<&mut KeptBackground>,
    ) -> Frame {
        let mut sprite = world
            .sprites
            .first()
            .cloned()
            .expect("the default map has sprites");
        sprite.def.pos = i.sprite_at;
        let sprites = [sprite];
        let mut scene = Scene::new(world, i.camera)
            .with_view(i.view)
            .with_doors(&i.doors)
            .with_sprites(&sprites)
            .with_lights(&i.lights)
            .at_time(i.time);
        scene.light.night = i.night;
        scene.light.falloff = i.falloff;
        fb.resize_cells(i.cells.0, i.cells.1, i.glyphs);
        fb.set_phases_wanted(i.phases);
        match kept {
            Some(kept) => scene.render_frame_kept(fb, Some(i.traced), kept),
            None => scene.render_frame(fb, Some(i.traced)),
        }
    }

    #[test]
    fn a_kept_background_draws_what_a_fresh_render_draws_and_is_reused_only_when_nothing_it_shows_changed(
    ) {
        let world = World::default_world();
        let start = world.map.start.pos();
        let door = world.map.door_cells()[0];
        let first = Inputs {
            camera: Camera::from_angle(start, 30.0, 66.0),
            view: View::default(),
            night: false,
            falloff: 0.0,
            doors: DoorState::new(&world.map),
            lights: Vec::new(),
            time: 0.0,
            sprite_at: start + Vec2::new(1.5, 0.5),
            cells: (24, 8),
            glyphs: Glyphs::Half,
            phases: true,
            traced: 3,
        };
        // Each step changes one input of the step before; `true` where the background may be
        // reused (only the sprites or the time changed).
        type Step = (&'static str, fn(&mut Inputs, (i64, i64)), bool);
        let steps: [Step; 19] = [
            ("nothing", |_, _| {}, true),
            ("a sprite moved", |i, _| i.sprite_at.x += 0.3, true),
            ("time", |i, _| i.time += 0.5, true),
            (
                "turned",
                |i, _| i.camera = Camera::from_angle(i.camera.pos, 50.0, 66.0),
                false,
            ),
            ("walked", |i, _| i.camera.pos.x += 0.05, false),
            ("looked up", |i, _| i.view.pitch_deg = 10.0, false),
            ("darker with distance", |i, _| i.falloff = 0.3, false),
            ("evenly lit again", |i, _| i.falloff = 0.0, false),
            (
                "a shot in daylight",
                |i, _| {
                    i.lights.push(PointLight {
                        pos: i.camera.pos + Vec2::new(0.8, -0.3),
                        z: 0.5,
                        radius: 3.0,
                        strength: 1.0,
                    });
                },
                true,
            ),
            ("night", |i, _| i.night = true, false),
            ("a door opened", |i, d| i.doors.set_open(d, 0.5), false),
            (
                "a shot's light",
                |i, _| {
                    i.lights.push(PointLight {
                        pos: i.camera.pos + Vec2::new(1.0, 0.2),
                        z: 0.5,
                        radius: 3.0,
                        strength: 1.0,
                    });
                },
                false,
            ),
            ("still again", |_, _| {}, true),
            ("a wider view", |i, _| i.cells.0 = 30, false),
            ("another traced column", |i, _| i.traced = 7, false),
            (
                "quadrants of the same pixels",
                |i, _| {
                    i.cells.0 /= 2;
                    i.glyphs = Glyphs::Quadrant;
                },
                false,
            ),
            ("octants", |i, _| i.glyphs = Glyphs::Octant, false),
            ("no phases", |i, _| i.phases = false, false),
            ("phases again", |i, _| i.phases = true, false),
        ];
        let mut inputs = first;
        let (mut kept_fb, mut fresh_fb) = (Framebuffer::new(1, 1), Framebuffer::new(1, 1));
        let mut kept = KeptBackground::default();
        render(&world, &inputs, &mut kept_fb, Some(&mut kept));
        let mut reused = 0;
        for (what, change, same) in steps {
            change(&mut inputs, door);
            let got = render(&world, &inputs, &mut kept_fb, Some(&mut kept));
            let want = render(&world, &inputs, &mut fresh_fb, None);
            assert_eq!(got, want, "{what}: rays or sprites");
            assert_eq!(kept_fb.pixels(), fresh_fb.pixels(), "{what}: pixels");
            if inputs.phases {
                assert_eq!(kept_fb.phases(), fresh_fb.phases(), "{what}: phases");
            }
            reused += usize::from(same);
            assert_eq!(kept.reused(), reused, "{what}");
        }
        // A forgotten background is painted again.
        kept.forget();
        render(&world, &inputs, &mut kept_fb, Some(&mut kept));
        assert_eq!(kept.reused(), reused);
        // Views with no pixels, kept and reused.
        for cells in [(0, 4), (0, 4), (6, 0), (6, 0)] {
            inputs.cells = cells;
            let (mut a, mut b) = (Framebuffer::new(1, 1), Framebuffer::new(1, 1));
            a.set_phases_wanted(true);
            let got = render(&world, &inputs, &mut kept_fb, Some(&mut kept));
            render(
                &world,
                &inputs,
                &mut a,
                Some(&mut KeptBackground::default()),
            );
            let want = render(&world, &inputs, &mut b, None);
            assert_eq!(got, want);
            assert_eq!(
                kept_fb.phases().unwrap_or_default(),
                b.phases().unwrap_or_default()
            );
            assert_eq!(a.phases(), b.phases(), "{cells:?}");
        }
        assert_eq!(kept.reused(), reused + 2);
    }
}
