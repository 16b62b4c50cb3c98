//! Paints the draw lists of [`crate::height_cast`] (maps with `Hz` heights): floors and ceilings
//! world-anchored at their own heights, vertical faces with texture rows anchored to world
//! height (the texel row for height z is frac(1 − z)·texH, so taller faces repeat, never
//! stretch), every surface lit by its distance; then the sprites, hidden pixel by pixel by
//! whatever nearer surface was drawn there.

use crate::billboard::{draw_sprites, Occluders, SpriteOutcome};
use crate::cast::{Cast, Side};
use crate::framebuffer::Framebuffer;
use crate::height_cast::{Band, FaceSpan, FlatSpan, Projection};
use crate::light::{Shade, ShadeTable};
use crate::lightmap::LightMap;
use crate::raster::{face_texture_x, fast_floor, heading_of, Y_SIDE_SHADE};
use crate::scene::Scene;
use crate::vec2::Vec2;
use crate::world::Paint;

/// Paints `cast` (from [`crate::height_cast::cast_heights`] at `fb`'s size) and the sprites.
pub fn rasterize_heights(scene: &Scene, cast: &Cast, fb: &mut Framebuffer) -> Vec<SpriteOutcome> {
    let (w, h) = (fb.width(), fb.height());
    if w == 0 || h == 0 {
        return Vec::new();
    }
    let proj = Projection::new(&scene.camera, &scene.view, w, h);
    let table = ShadeTable::new(&scene.light);
    let lamps = scene.lamp_light();
    // Sprites are hidden by the distance of whatever was drawn at each pixel.
    let mut depth = if scene.world.sprites.is_empty() {
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
        table: &table,
        lamps,
        per_row,
    };
    for (x, col) in cast.heights.iter().enumerate().take(w) {
        let ray = scene.camera.ray_dir(x, w);
        for band in &col.bands {
            match band {
                Band::Flat(f) => painter.flat(f, x, ray, fb, &mut depth),
                Band::Face(f) => painter.face(f, x, ray, fb, &mut depth),
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
        &table,
    )
}

/// What every band of a frame is painted with.
struct Painter<'a> {
    scene: &'a Scene<'a>,
    proj: Projection,
    table: &'a ShadeTable,
    lamps: Option<&'a LightMap>,
    per_row: Vec<f64>,
}

impl Painter<'_> {
    /// A floor or ceiling: each row's distance from the height it shows, the world point there
    /// picking the texel (world-anchored) and the lamp light.
    fn flat(&self, f: &FlatSpan, x: usize, ray: Vec2, fb: &mut Framebuffer, depth: &mut [f32]) {
        let world = self.scene.world;
        let paint = if f.ceiling {
            world.ceiling_paint(f.zone)
        } else {
            world.floor_paint(f.zone)
        };
        let w = fb.width();
        let rise = self.proj.eye - f.z;
        let pos = self.scene.camera.pos;
        let keep_depth = !depth.is_empty();
        for y in f.rows.0..f.rows.1 {
            // Within the cell's stretch of the ray whatever rounding says (and at the horizon).
            let mut dist = rise * self.per_row[y];
            if dist.is_nan() {
                dist = f.dist.1;
            }
            let dist = dist.clamp(f.dist.0, f.dist.1);
            let at = pos + ray * dist;
            let mut shade = self.table.at(dist);
            if let Some(lamps) = self.lamps {
                shade = shade.lit(lamps.at(at));
            }
            let c = match paint {
                Paint::Colour(c) => c,
                Paint::Texture(i) => world.textures[i].sample_unit(
                    at.x - fast_floor(at.x) as f64,
                    at.y - fast_floor(at.y) as f64,
                ),
            };
            fb.set(x, y, shade.apply(c));
            if keep_depth {
                depth[y * w + x] = dist as f32;
            }
        }
    }

    /// A wall, step or lintel face: one texture column, rows by world height.
    fn face(&self, f: &FaceSpan, x: usize, ray: Vec2, fb: &mut Framebuffer, depth: &mut [f32]) {
        let world = self.scene.world;
        let t = f.perp_dist;
        let mut shade = self.table.at(t);
        if let Some(lamps) = self.lamps {
            // Just in front of the face, on the side the ray came from.
            let back = 0.01 / ray.length().max(1e-9);
            shade = shade.lit(lamps.at(self.scene.camera.pos + ray * (t - back)));
        }
        let shade: Shade = if f.side == Side::Y {
            shade.scaled(Y_SIDE_SHADE)
        } else {
            shade
        };
        let w = fb.width();
        let per_row = t / self.proj.focal;
        let keep_depth = !depth.is_empty();
        match world.face_paint(f.what, heading_of(f.side, ray)) {
            Paint::Colour(c) => {
                let c = shade.apply(c);
                for y in f.rows.0..f.rows.1 {
                    fb.set(x, y, c);
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
                    let v = (u * th_f) as usize;
                    u += step;
                    if u >= 1.0 {
                        u -= 1.0;
                    }
                    fb.set(x, y, shade.apply(column[v.min(th - 1)]));
                    if keep_depth {
                        depth[y * w + x] = t as f32;
                    }
                }
            }
        }
    }
}
