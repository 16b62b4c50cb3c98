//! Paints the draw lists of [`crate::render::height_cast`] (maps with `Hz` heights): floors and ceilings
//! world-anchored at their own heights, vertical faces with texture rows anchored to world
//! height (the texel row for height z is frac(1 − z)·texH, so taller faces repeat, never
//! stretch), every surface lit by its distance; then the sprites, hidden pixel by pixel by
//! whatever nearer surface was drawn there.

use crate::map::Cell;
use crate::render::billboard::{draw_sprites, Occluders, SpriteOutcome};
use crate::render::cast::{Cast, Side};
use crate::render::dither_phase;
use crate::render::fast_floor::fast_floor;
use crate::render::framebuffer::Framebuffer;
use crate::render::height_cast::{Band, FaceKind, FaceSpan, FlatSpan, Projection};
use crate::render::light::{Shade, ShadeTable};
use crate::render::point_light::{self, PointLight};
use crate::render::raster::{face_texture_x, heading_of, Y_SIDE_SHADE};
use crate::render::scene::Scene;
use crate::vec2::Vec2;
use crate::world::lightmap::{Corners, LightMap, Probe};
use crate::world::{texel_index, Paint};

/// Paints `cast` (from [`crate::render::height_cast::cast_heights`] at `fb`'s size) and the sprites.
pub fn rasterize_heights(scene: &Scene, cast: &Cast, fb: &mut Framebuffer) -> Vec<SpriteOutcome> {
    let (w, h) = (fb.width(), fb.height());
    if w == 0 || h == 0 {
        return Vec::new();
    }
    let proj = Projection::with_pixel_height(&scene.camera, &scene.view, (w, h), fb.pixel_height());
    let table = fb.shade_table(&scene.light);
    let table = &*table;
    let lamps = scene.lamp_light();
    // Faces write their dither phases (floors and ceilings carry none, as on flat maps), and
    // none may be left over from a previous frame in this buffer.
    fb.clear_phases();
    // Sprites are hidden by the distance of whatever was drawn at each pixel.
    let mut depth = if scene.world.sprites.is_empty() && scene.sprites.is_empty() {
        Vec::new()
    } else {
        vec![f32::INFINITY; w * h]
    };
    // focal / (row centre − horizon): a floor row's distance is (eye − z) times this.
    let per_row: Vec<f64> = (0..h)
        .map(|y| proj.focal / (y as f64 + 0.5 - proj.horizon))
        .collect();
    let painter = Painter {
        scene,
        proj,
        table,
        lamps,
        moving: scene.point_lights(),
        per_row,
    };
    for (x, col) in cast.heights.iter().enumerate().take(w) {
        let ray = scene.camera.ray_dir(x, w);
        for band in &col.bands {
            match band {
                Band::Flat(f) => painter.flat(f, x, ray, fb, &mut depth),
                Band::Face(f) => {
                    painter.face(f, x, ray, fb, &mut depth);
                    painter.face_phases(f, x, ray, fb);
                }
            }
        }
    }
    draw_sprites(
        scene,
        Occluders::Pixels {
            depth: &depth,
            width: w,
        },
        fb,
        table,
    )
}

/// What every band of a frame is painted with.
struct Painter<'a> {
    scene: &'a Scene<'a>,
    proj: Projection,
    table: &'a ShadeTable,
    lamps: Option<&'a LightMap>,
    /// The frame's moving lights (empty by day).
    moving: &'a [PointLight],
    per_row: Vec<f64>,
}

impl Painter<'_> {
    /// A floor or ceiling: each row's distance from the height it shows, the world point there
    /// picking the texel (world-anchored) and the lamp light.
    fn flat(&self, f: &FlatSpan, x: usize, ray: Vec2, fb: &mut Framebuffer, depth: &mut [f32]) {
        let world = self.scene.world;
        let fill = world.fill(if f.ceiling {
            world.ceiling_paint(f.zone)
        } else {
            world.floor_paint(f.zone)
        });
        let w = fb.width();
        let rise = self.proj.eye - f.z;
        let pos = self.scene.camera.pos;
        let keep_depth = !depth.is_empty();
        let mut corners = Corners::default();
        for y in f.rows.0..f.rows.1 {
            // Within the cell's stretch of the ray whatever rounding says (and at the horizon).
            let mut dist = rise * self.per_row[y];
            if dist.is_nan() {
                dist = f.dist.1;
            }
            let dist = dist.clamp(f.dist.0, f.dist.1);
            let at = pos + ray * dist;
            let mut shade = self.table.at(dist);
            if self.lamps.is_some() || !self.moving.is_empty() {
                // Lamps and moving lights add up, measured at the surface's own height.
                let lamp = self
                    .lamps
                    .map_or(0, |l| l.at_z_cached(at, f.z, &mut corners));
                let glow = if self.moving.is_empty() {
                    0
                } else {
                    point_light::level(self.moving, at, f.z)
                };
                shade = shade.lit(point_light::add(lamp, glow));
            }
            let c = fill.at_unit(
                at.x - fast_floor(at.x) as f64,
                at.y - fast_floor(at.y) as f64,
            );
            fb.set(x, y, shade.apply(c));
            if keep_depth {
                depth[y * w + x] = dist as f32;
            }
        }
    }

    /// Writes a face's dither phases: the face's own coordinates (along it, and its height in
    /// the world) on a lattice about a pixel fine, as flat maps' walls get
    /// ([`crate::render::dither_phase`]), so the 256- and 16-colour patterns lie on the faces.
    fn face_phases(&self, f: &FaceSpan, x: usize, ray: Vec2, fb: &mut Framebuffer) {
        let t = f.perp_dist;
        if !(fb.wants_phases() && t > 0.0 && t.is_finite()) {
            return;
        }
        // Pixels per unit along the face: where the next column's ray meets the face's line.
        let pos = self.scene.camera.pos;
        let next = ray + self.scene.camera.plane * (2.0 / fb.width() as f64);
        let hit = pos + ray * t;
        let du = match f.side {
            Side::X if next.x.abs() > 1e-12 => {
                (pos.y + next.y * (hit.x - pos.x) / next.x - hit.y).abs()
            }
            Side::Y if next.y.abs() > 1e-12 => {
                (pos.x + next.x * (hit.y - pos.y) / next.y - hit.x).abs()
            }
            _ => 0.0,
        };
        let px_per_unit = self.proj.focal / t;
        let along = if du > 0.0 && du.is_finite() {
            1.0 / du
        } else {
            px_per_unit
        };
        let per_row = t / self.proj.focal;
        let w = fb.width();
        // Down from the top of a unit wall (1 − z), as the texture rows are.
        dither_phase::write_upright(
            fb.phases_mut(),
            (w, x),
            f.rows,
            (f.wall_x, along),
            px_per_unit,
            |y| 1.0 - self.proj.eye + (y as f64 + 0.5 - self.proj.horizon) * per_row,
        );
    }

    /// A wall, step or lintel face: one texture column, rows by world height.
    fn face(&self, f: &FaceSpan, x: usize, ray: Vec2, fb: &mut Framebuffer, depth: &mut [f32]) {
        let world = self.scene.world;
        let t = f.perp_dist;
        let base = self.table.at(t);
        // Lamps and moving lights are read just in front of the face, on the side the ray came
        // from, at the height each row shows.
        let lit = self.lamps.is_some() || !self.moving.is_empty();
        let front = if lit {
            let back = 0.01 / ray.length().max(1e-9);
            self.scene.camera.pos + ray * (t - back)
        } else {
            Vec2::default()
        };
        let probe = self.lamps.map(|l| l.probe(front));
        let moving = if lit && point_light::near(self.moving, front) {
            self.moving
        } else {
            &[]
        };
        let side = |s: Shade| {
            if f.side == Side::Y {
                s.scaled(Y_SIDE_SHADE)
            } else {
                s
            }
        };
        let row_z =
            |y: usize| self.proj.eye - (y as f64 + 0.5 - self.proj.horizon) * t / self.proj.focal;
        // One level for the whole face when no moving light is near and every height it shows
        // reads the lamps' shared level (most faces: within the lamps' own segments).
        let lamp = match probe {
            None => Some(0),
            Some(Probe::Level(l)) => Some(l),
            Some(Probe::Heights { za, zb, level, .. }) => {
                let (z_top, z_bottom) = (row_z(f.rows.0), row_z(f.rows.1.max(f.rows.0 + 1) - 1));
                (z_bottom >= za && z_top <= zb).then_some(level)
            }
        };
        let varies = !moving.is_empty() || lamp.is_none();
        let flat_shade = side(match (probe, lamp) {
            (Some(_), Some(l)) => base.lit(l),
            _ => base,
        });
        let shade_of = |y: usize| {
            if !varies {
                return flat_shade;
            }
            let z = row_z(y);
            let lamp = probe.map_or(0, |p| p.at(z));
            let glow = if moving.is_empty() {
                0
            } else {
                point_light::level(moving, front, z)
            };
            side(base.lit(point_light::add(lamp, glow)))
        };
        let w = fb.width();
        let per_row = t / self.proj.focal;
        let keep_depth = !depth.is_empty();
        // A door's panel shows the door; the step or lintel beside a door cell is plain wall.
        let what = match (f.kind, f.what) {
            (FaceKind::Step | FaceKind::Lintel, Cell::Door(_)) => Cell::Floor { zone: 0 },
            (_, what) => what,
        };
        match world.face_paint_at(what, f.cell, heading_of(f.side, ray)) {
            Paint::Colour(c) if !varies => {
                let c = flat_shade.apply(c);
                for y in f.rows.0..f.rows.1 {
                    fb.set(x, y, c);
                    if keep_depth {
                        depth[y * w + x] = t as f32;
                    }
                }
            }
            Paint::Colour(c) => {
                for y in f.rows.0..f.rows.1 {
                    fb.set(x, y, shade_of(y).apply(c));
                    if keep_depth {
                        depth[y * w + x] = t as f32;
                    }
                }
            }
            Paint::Texture(i) => {
                let tex = &world.textures[i];
                let column = tex.column(face_texture_x(f.wall_x, f.side, ray, tex.width()));
                let th = tex.height();
                // u = 1 − z, the height measured down from the top of a unit wall; the texel
                // row is frac(u)·texH, stepped row by row.
                let y0 = f.rows.0 as f64 + 0.5 - self.proj.horizon;
                let u0 = 1.0 - self.proj.eye + y0 * per_row;
                let mut u = u0 - fast_floor(u0) as f64;
                let step = per_row - fast_floor(per_row) as f64;
                let th_f = th as f64;
                for y in f.rows.0..f.rows.1 {
                    let v = texel_index(u * th_f);
                    u += step;
                    if u >= 1.0 {
                        u -= 1.0;
                    }
                    fb.set(x, y, shade_of(y).apply(column[v.min(th - 1)]));
                    if keep_depth {
                        depth[y * w + x] = t as f32;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::camera::Camera;
    use crate::color::Rgb;
    use crate::map::parse_map;
    use crate::render::framebuffer::Framebuffer;
    use crate::render::light::{Fog, ShadeTable};
    use crate::render::scene::Scene;
    use crate::vec2::Vec2;
    use crate::world::{TextureSource, World};

    fn world(extra: &str, grid: &str) -> World {
        let text = format!("NO n\nSO s\nWE w\nEA e\nF 100,120,140\nC 4,5,6\n{extra}{grid}");
        let map = parse_map("t.cub", text.as_bytes()).unwrap();
        World::load(map, &TextureSource::Embedded, false).unwrap().0
    }

    #[test]
    fn fog_lights_steps_and_floors_by_their_own_distance() {
        // A Wz-coloured 0.3 step two cells ahead of the eye; fog thick enough to tell distances.
        let w = world(
            "Hs 0.3 1\nWs 200,100,50\n",
            "11111111\n1E0s0001\n11111111\n",
        );
        let mut scene = Scene::new(&w, Camera::from_angle(Vec2::new(1.5, 1.5), 0.0, 90.0));
        scene.light.fog = Some(Fog {
            colour: Rgb::new(10, 20, 30),
            density: 0.4,
        });
        let table = ShadeTable::new(&scene.light);
        let mut fb = Framebuffer::new(41, 41);
        let frame = scene.render_frame(&mut fb, Some(20));
        let col = &frame.cast.heights[20];
        let step = col.faces().next().unwrap();
        assert_eq!(step.cell, (3, 1));
        assert!(step.rows.0 < step.rows.1);
        let want = table.at(step.perp_dist).apply(Rgb::new(200, 100, 50));
        for y in step.rows.0..step.rows.1 {
            assert_eq!(fb.get(20, y), want, "step row {y}");
        }
        // The floor just below the step: each row at its own distance (focal 20.5, eye 0.5).
        let y = step.rows.1 + 1;
        let dist = 0.5 * 20.5 / (y as f64 + 0.5 - 20.5);
        assert_eq!(fb.get(20, y), table.at(dist).apply(Rgb::new(100, 120, 140)));
        assert_ne!(fb.get(20, y), fb.get(20, 40));
    }

    #[test]
    fn texture_rows_repeat_on_a_tall_wall_instead_of_stretching() {
        // A hall two units tall: the texel row for height z is frac(1 − z)·texH, so the wall from
        // 1 to 2 repeats the wall from 0 to 1 row for row. Focal 32 at distance 2: one unit is
        // exactly 16 rows, so rows 16 apart show the same texel.
        let w = world("Hh 0 2\n", "111111\n1Ehhh1\n111111\n");
        let view = crate::render::view::View::new(0.0, 0.92).on_ground(0.05);
        let scene =
            Scene::new(&w, Camera::from_angle(Vec2::new(3.0, 1.5), 0.0, 90.0)).with_view(view);
        let mut fb = Framebuffer::new(64, 200);
        let frame = scene.render_frame(&mut fb, Some(32));
        let wall = frame.cast.heights[32].faces().last().copied().unwrap();
        assert_eq!((wall.perp_dist, wall.z), (2.0, (0.0, 2.0)));
        // Eye at 0.97: rows 85..100 see z in (1, 2), rows 101..116 the same heights less one.
        // Columns whose rays meet the east wall (the room is one cell wide).
        for x in 29..36 {
            for y in 101..116 {
                assert_eq!(
                    fb.get(x, y),
                    fb.get(x, y - 16),
                    "column {x} rows {y}, {}",
                    y - 16
                );
            }
        }
        // And it is a texture, not one colour.
        assert!((29..36).any(|x| (101..116).any(|y| fb.get(x, y) != fb.get(x, 101))));
    }
}
