//! Draws the sprites over the walls: far to near, column by column, each column tested against
//! the walls' depth buffer (the per-column perpendicular distances from the cast).

use crate::color::Rgb;
use crate::map::Blend;
use crate::render::cast::ColumnHit;
use crate::render::dither_phase;
use crate::render::framebuffer::Framebuffer;
use crate::render::light::{Shade, ShadeTable};
use crate::render::point_light;
use crate::render::scene::Scene;
use crate::render::sprite_projection::{
    far_to_near, frame_index, project_on, view_index, Culled, Projection,
};
use crate::world::texel_index;

/// What became of one sprite in a frame (the JSON `sprites` array is built from these).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpriteOutcome {
    /// Index into [`crate::World::sprites`], then on into the scene's own sprites
    /// ([`Scene::all_sprites`]).
    pub index: usize,
    /// Where it projects on screen, or why it was culled.
    pub projection: Result<Projection, Culled>,
    /// Whether at least one texel reached the screen (false when walls hide it all).
    pub drawn: bool,
}

/// What hides sprites: the nearer surfaces already drawn.
#[derive(Debug, Clone, Copy)]
pub enum Occluders<'a> {
    /// Flat maps: one wall per column (the cast's perpendicular distances); floors never hide.
    Columns(&'a [ColumnHit]),
    /// `Hz` maps: the distance of the surface drawn at every pixel (row-major, `width` wide), so
    /// nearer steps, ledges and lintels hide sprites pixel by pixel.
    Pixels {
        /// Distance of the surface at each pixel.
        depth: &'a [f32],
        /// Pixels per row of `depth`.
        width: usize,
    },
}

/// The height of a sprite's bottom in the world: on `Hz` maps it stands `offset` above the floor
/// of its cell, or hangs from that cell's ceiling; on flat maps its `offset` as given.
#[must_use]
pub fn sprite_base(map: &crate::map::Map, def: &crate::map::SpriteDef) -> f64 {
    if !map.has_heights() {
        return def.offset;
    }
    let span = map
        .span(def.pos.x.floor() as i64, def.pos.y.floor() as i64)
        .unwrap_or(crate::map::Span::FLAT);
    if def.hang {
        span.ceil - def.scale.1
    } else {
        span.floor + def.offset
    }
}

/// Projects, sorts and draws every sprite of the scene behind `occluders`.
pub fn draw_sprites(
    scene: &Scene,
    occluders: Occluders,
    fb: &mut Framebuffer,
    table: &ShadeTable,
) -> Vec<SpriteOutcome> {
    let (w, h) = (fb.width(), fb.height());
    let view = scene.view.clamped();
    let mut outcomes: Vec<SpriteOutcome> = scene
        .all_sprites()
        .enumerate()
        .map(|(index, s)| SpriteOutcome {
            index,
            projection: project_on(
                &scene.camera,
                &view,
                (
                    s.def.pos,
                    s.def.scale,
                    sprite_base(&scene.world.map, &s.def),
                ),
                (w, h),
                fb.pixel_height(),
            ),
            drawn: false,
        })
        .collect();
    let depths: Vec<(usize, f64)> = outcomes
        .iter()
        .filter_map(|o| o.projection.ok().map(|p| (o.index, p.depth)))
        .collect();
    for i in far_to_near(&depths) {
        let Ok(p) = outcomes[i].projection else {
            continue;
        };
        let mut shade = table.at(p.depth);
        let lamps = scene.lamp_light();
        let moving = scene.point_lights();
        if let (true, Some(sprite)) = (lamps.is_some() || !moving.is_empty(), scene.sprite(i)) {
            // Lit at its middle: its own height on maps with heights, by moving lights.
            let def = &sprite.def;
            let z = sprite_base(&scene.world.map, def) + def.scale.1 / 2.0;
            let lamp = lamps.map_or(0, |l| l.at_z(def.pos, z));
            let glow = point_light::level(moving, def.pos, z);
            shade = shade.lit(point_light::add(lamp, glow));
        }
        outcomes[i].drawn = draw_one(scene, i, &p, occluders, fb, shade);
    }
    outcomes
}

/// Mixes `fg` over `bg` by `a`/255.
#[inline]
fn mix(bg: Rgb, fg: Rgb, a: u16) -> Rgb {
    let ch = |b: u8, f: u8| ((u16::from(f) * a + u16::from(b) * (255 - a) + 127) / 255) as u8;
    Rgb::new(ch(bg.r, fg.r), ch(bg.g, fg.g), ch(bg.b, fg.b))
}

/// Draws sprite `i` at its projection; returns whether any texel was written.
fn draw_one(
    scene: &Scene,
    i: usize,
    p: &Projection,
    occluders: Occluders,
    fb: &mut Framebuffer,
    shade: Shade,
) -> bool {
    let Some(sprite) = scene.sprite(i) else {
        return false;
    };
    let def = &sprite.def;
    let sheet = &scene.world.sheets[sprite.sheet];
    let views = usize::from(def.views).max(1);
    let views = if sheet.width() >= views { views } else { 1 };
    let frames = usize::from(def.frames).max(1);
    let frames = if sheet.height() >= frames { frames } else { 1 };
    let (cell_w, cell_h) = (sheet.width() / views, sheet.height() / frames);
    let vi = view_index(def.pos, def.facing_deg, scene.camera.pos, def.views).min(views - 1);
    let fi = frame_index(def.frames, def.fps, scene.time).min(frames - 1);
    let (x0, y0) = (vi * cell_w, fi * cell_h);
    let width = p.right - p.left;
    let v_step = cell_h as f64 / (p.bottom - p.top);
    let v_start = (p.rows.0 as f64 + 0.5 - p.top) * v_step;
    let mut drawn = false;
    let depth = p.depth as f32;
    // Dither phases on the sprite's own (u, v), a lattice about a pixel fine.
    let per_u = dither_phase::lattice(width);
    let per_v = dither_phase::lattice(p.bottom - p.top);
    let phases = fb.wants_phases();
    for x in p.cols.0..p.cols.1 {
        if let Occluders::Columns(hits) = occluders {
            if hits.get(x).is_none_or(|hit| p.depth >= hit.perp_dist) {
                continue;
            }
        }
        let u = (x as f64 - p.left) / width;
        let tx = x0 + ((u * cell_w as f64) as usize).min(cell_w - 1);
        let (colours, alphas) = sheet.column(tx);
        // The frame's rows of this column that are not clear: none, or a span to walk. Rows
        // above it are passed by stepping `v` alone, and the walk stops below it (`v` only
        // grows down the stripe).
        let seen = sheet.opaque_rows(tx);
        let (first, end) = (
            seen.start.saturating_sub(y0).min(cell_h),
            seen.end.saturating_sub(y0).min(cell_h),
        );
        if first >= end {
            continue;
        }
        let grows = v_step > 0.0;
        let mut v = v_start;
        let mut from = p.rows.0;
        while grows && from < p.rows.1 && v < first as f64 {
            v += v_step;
            from += 1;
        }
        let pu = dither_phase::index(u, per_u);
        for y in from..p.rows.1 {
            let t = texel_index(v).min(cell_h - 1);
            if grows && t >= end {
                break;
            }
            let ty = y0 + t;
            v += v_step;
            let a = alphas[ty];
            if a == 0 {
                continue;
            }
            if let Occluders::Pixels { depth: d, width } = occluders {
                if depth >= d[y * width + x] {
                    continue;
                }
            }
            drawn = true;
            let c = colours[ty];
            let bg = fb.get(x, y);
            let out = match def.blend {
                Blend::Normal if a == 255 => shade.apply(c),
                Blend::Normal => mix(bg, shade.apply(c), u16::from(a)),
                Blend::Average => mix(bg, shade.apply(c), u16::from(a) / 2 + 1),
                Blend::Additive => {
                    // Glow fades with distance but does not pick up fog colour.
                    let lit = Shade {
                        add: [0; 3],
                        ..shade
                    }
                    .apply(c);
                    let add = |b: u8, f: u8| {
                        (u16::from(b) + u16::from(f) * u16::from(a) / 255).min(255) as u8
                    };
                    Rgb::new(add(bg.r, lit.r), add(bg.g, lit.g), add(bg.b, lit.b))
                }
            };
            fb.set(x, y, out);
            if phases {
                let pv = (y as f64 + 0.5 - p.top) / (p.bottom - p.top);
                let phase = dither_phase::at(pu, dither_phase::index(pv, per_v));
                fb.set_phase(x, y, phase);
            }
        }
    }
    drawn
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sprites_stand_on_their_cells_floor_and_hang_from_its_ceiling() {
        let text = "NO n\nSO s\nWE w\nEA e\nF 1,2,3\nC 4,5,6\nHp -1 2.5\n\
                    SPRITE 2.5,1.5 t.png offset=0.25\nSPRITE 2.5,1.5 t.png scale=0.5 hang\n\
                    SPRITE 1.5,1.5 t.png scale=0.5 hang\n11111\n1Ep01\n11111\n";
        let map = crate::map::parse_map("t.cub", text.as_bytes()).unwrap();
        let base = |k: usize| sprite_base(&map, &map.sprite_defs[k]);
        assert_eq!(base(0), -0.75);
        assert_eq!(base(1), 2.0);
        // The start cell spans 0..1 as on flat maps.
        assert_eq!(base(2), 0.5);
        // A map without heights keeps offsets as given.
        let flat = text.replace("Hp -1 2.5", "Fp 9,9,9");
        let map = crate::map::parse_map("t.cub", flat.as_bytes()).unwrap();
        assert_eq!(sprite_base(&map, &map.sprite_defs[1]), 0.5);
    }

    /// A sheet's clear rows above and below its opaque ones, and its clear columns, are stepped
    /// over rather than walked: the pixels must be those of the same sheet walked whole. The
    /// whole walk is forced by a second sheet whose clear texels are opaque green instead; where
    /// it shows the red band, the first must show the same pixel, elsewhere what is behind.
    #[test]
    fn stepping_over_clear_rows_and_columns_draws_the_pixels_a_whole_walk_draws() {
        use crate::camera::Camera;
        use crate::texture::sheet::SpriteSheet;
        use crate::world::sprite::Sprite;
        use crate::world::World;
        let base = World::default_world();
        let start = base.map.start;
        // Two animation frames of 16 rows, each with its own band; the second is drawn.
        let sheet = |clear: Option<Rgb>| {
            SpriteSheet::from_fn(8, 32, move |x, y| {
                let band = if y < 16 { 10..14 } else { 21..25 };
                if x != 3 && band.contains(&y) && !(x == 6 && y == 24) {
                    (Rgb::new(255, 0, 0), 255)
                } else {
                    clear.map_or((Rgb::default(), 0), |c| (c, 255))
                }
            })
        };
        let (mut red_seen, mut green_seen) = (0, 0);
        for (turn, ahead, tall) in [(0.0, 1.3, 1.0), (10.0, 2.5, 0.6), (-20.0, 0.8, 1.4)] {
            let cam = Camera::from_angle(start.pos(), start.angle_deg() + turn, 66.0);
            let mut def = base.sprites[0].def.clone();
            def.pos = cam.pos + cam.dir * ahead;
            (def.scale, def.offset, def.views, def.frames, def.fps) = ((0.8, tall), 0.1, 1, 2, 1.0);
            def.blend = Blend::Normal;
            let draw = |sheet: Option<SpriteSheet>| {
                let mut world = base.clone();
                world.sprites.clear();
                if let Some(sheet) = sheet {
                    world.sheets.push(sheet);
                    let sheet = world.sheets.len() - 1;
                    world.sprites.push(Sprite {
                        def: def.clone(),
                        sheet,
                    });
                }
                let mut fb = Framebuffer::new(90, 60);
                Scene::new(&world, cam)
                    .at_time(1.5)
                    .render_into(&mut fb, None);
                fb
            };
            let (behind, band, whole) = (
                draw(None),
                draw(Some(sheet(None))),
                draw(Some(sheet(Some(Rgb::new(0, 255, 0))))),
            );
            let phases = |fb: &Framebuffer| fb.phases().expect("phases are wanted").to_vec();
            let (behind_phases, band_phases, whole_phases) =
                (phases(&behind), phases(&band), phases(&whole));
            for y in 0..60 {
                for x in 0..90 {
                    let w = whole.get(x, y);
                    let red = w != behind.get(x, y) && w.r > w.g;
                    red_seen += usize::from(red);
                    green_seen += usize::from(w.g > w.r);
                    let want = if red { w } else { behind.get(x, y) };
                    assert_eq!(band.get(x, y), want, "turn {turn} at ({x}, {y})");
                    let i = y * 90 + x;
                    let phase = if red {
                        whole_phases[i]
                    } else {
                        behind_phases[i]
                    };
                    assert_eq!(band_phases[i], phase, "turn {turn} phase at ({x}, {y})");
                }
            }
        }
        assert!(
            red_seen > 100 && green_seen > 100,
            "{red_seen} {green_seen}"
        );
    }

    #[test]
    fn mixing_by_alpha() {
        let (bg, fg) = (Rgb::new(0, 100, 200), Rgb::new(200, 100, 0));
        assert_eq!(mix(bg, fg, 255), fg);
        assert_eq!(mix(bg, fg, 0), bg);
        assert_eq!(mix(bg, fg, 128), Rgb::new(100, 100, 100));
    }
}
