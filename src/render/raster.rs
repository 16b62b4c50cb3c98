//! Turns the cast rays into pixels: textured floor and ceiling rows, then wall stripes, then
//! sprites; everything lit through one distance table and placed by the view's horizon and eye.

use crate::render::billboard::{draw_sprites, Occluders, SpriteOutcome};
use crate::render::cast::{ColumnHit, Side};
use crate::render::dither_phase;
use crate::render::fast_floor::fast_floor;
use crate::render::framebuffer::{Framebuffer, NEUTRAL_PHASE};
use crate::render::light::{Shade, ShadeTable};
use crate::render::plain_floor::PlainRow;
use crate::render::point_light;
use crate::render::scene::Scene;
use crate::vec2::Vec2;
use crate::world::{texel_index, Fill, World};

/// Brightness (of 256) of faces hit on a y side, so corners read as corners.
pub const Y_SIDE_SHADE: u16 = 184;

/// The eye's height above the floor, in wall heights (walls span 0..1), when standing.
const EYE_HEIGHT: f64 = crate::render::view::STANDING_EYE;

/// Which compass direction a ray travels when it hits (index into a wall's face textures).
#[must_use]
pub fn heading(hit: &ColumnHit) -> usize {
    heading_of(hit.side, hit.ray_dir)
}

/// [`heading`] of a ray `ray` crossing a `side` grid line (N, S, W, E = 0..4).
#[must_use]
#[inline]
pub fn heading_of(side: Side, ray: Vec2) -> usize {
    match side {
        Side::Y if ray.y < 0.0 => 0,
        Side::Y => 1,
        Side::X if ray.x < 0.0 => 2,
        Side::X => 3,
    }
}

/// Texture column for a hit, mirrored where needed so every face reads left-to-right.
#[must_use]
pub fn texture_x(hit: &ColumnHit, tex_width: usize) -> usize {
    face_texture_x(hit.wall_x, hit.side, hit.ray_dir, tex_width)
}

/// [`texture_x`] of a face met at `wall_x` along it by `ray` crossing a `side` grid line.
#[must_use]
#[inline]
pub fn face_texture_x(wall_x: f64, side: Side, ray: Vec2, tex_width: usize) -> usize {
    let x = ((wall_x * tex_width as f64) as usize).min(tex_width - 1);
    let mirrored = match side {
        Side::X => ray.x < 0.0,
        Side::Y => ray.y > 0.0,
    };
    if mirrored {
        tex_width - 1 - x
    } else {
        x
    }
}

/// Vertical extent of one column's wall on screen, in pixel rows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallSpan {
    /// Top edge (may be above the screen), in pixels.
    pub top: f64,
    /// Projected height in pixels: focal length / perpendicular distance.
    pub height: f64,
    /// First and one-past-last pixel rows drawn.
    pub rows: (usize, usize),
}

/// Projects a hit: one focal length for both axes, so a 1×1 wall face is square on screen.
#[must_use]
pub fn wall_span(perp_dist: f64, focal: f64, screen_h: usize) -> WallSpan {
    wall_span_at(
        perp_dist,
        focal,
        screen_h,
        screen_h as f64 / 2.0,
        EYE_HEIGHT,
    )
}

/// [`wall_span`] for a horizon row and an eye height (look up/down, crouch/jump).
#[must_use]
pub fn wall_span_at(
    perp_dist: f64,
    focal: f64,
    screen_h: usize,
    horizon: f64,
    eye: f64,
) -> WallSpan {
    let height = focal / perp_dist.max(1e-9);
    let top = horizon - height * (1.0 - eye);
    let bottom = horizon + height * eye;
    let row = |edge: f64| (edge - 0.5).ceil().clamp(0.0, screen_h as f64) as usize;
    WallSpan {
        top,
        height,
        rows: (row(top), row(bottom)),
    }
}

/// Paints the frame: floor and ceiling where no wall covers, then the walls, then the sprites;
/// returns what became of each sprite (for the JSON report).
pub fn rasterize_frame(
    scene: &Scene,
    hits: &[ColumnHit],
    fb: &mut Framebuffer,
) -> Vec<SpriteOutcome> {
    rasterize_background(scene, hits, fb);
    rasterize_sprites(scene, hits, fb)
}

/// The sprites of [`rasterize_frame`], over a background already painted: each hidden behind
/// the walls of `hits`.
pub fn rasterize_sprites(
    scene: &Scene,
    hits: &[ColumnHit],
    fb: &mut Framebuffer,
) -> Vec<SpriteOutcome> {
    if fb.width() == 0 || fb.height() == 0 {
        return Vec::new();
    }
    let table = fb.shade_table(&scene.light);
    draw_sprites(scene, Occluders::Columns(hits), fb, &table)
}

/// The background of [`rasterize_frame`]: floor, ceiling and walls (and their dither phases).
/// They depend on the world (map, textures, lamps), the camera, the view, the light, the
/// doors, the moving lights when the world is dark, and the framebuffer's size and glyph
/// setting, but not on the sprites or the time; every pixel (and phase, when wanted) is written.
pub fn rasterize_background(scene: &Scene, hits: &[ColumnHit], fb: &mut Framebuffer) {
    let (w, h) = (fb.width(), fb.height());
    if w == 0 || h == 0 {
        return;
    }
    // Vertical pixels per unit at distance 1: the camera's focal length, over the pixel's
    // height where the sub-grid's pixels are not square.
    let focal = scene.camera.focal_length(w) / fb.pixel_height();
    let view = scene.view.clamped();
    let horizon = view.horizon(focal, h);
    let table = fb.shade_table(&scene.light);
    let table = &*table;
    let spans: Vec<WallSpan> = hits
        .iter()
        .map(|hit| wall_span_at(hit.perp_dist, focal, h, horizon, view.eye()))
        .collect();
    floor_and_ceiling(scene, &spans, fb, focal, horizon, view.eye(), table);
    let lamps = scene.lamp_light();
    let moving = scene.point_lights();
    for (x, (hit, span)) in hits.iter().zip(&spans).enumerate() {
        let mut shade = table.at(hit.perp_dist);
        // Just in front of the wall, on the side the ray came from.
        let front = || {
            let back = 0.01 / hit.ray_dir.length().max(1e-9);
            scene.camera.pos + hit.ray_dir * (hit.perp_dist - back)
        };
        if let Some(lamps) = lamps {
            shade = shade.lit(lamps.at(front()));
        }
        let side = |s: Shade| {
            if hit.side == Side::Y {
                s.scaled(Y_SIDE_SHADE)
            } else {
                s
            }
        };
        if !moving.is_empty() && point_light::near(moving, front()) {
            // Moving lights are measured in 3-D: each row at the height it shows.
            let at = front();
            let lamp = lamps.map_or(0, |l| l.at(at));
            let base = table.at(hit.perp_dist);
            let per_row = hit.perp_dist / focal;
            let eye = view.eye();
            wall_stripe(scene.world, hit, span, x, fb, |y| {
                let z = eye - (y as f64 + 0.5 - horizon) * per_row;
                side(base.lit(point_light::add(lamp, point_light::level(moving, at, z))))
            });
        } else {
            let shade = side(shade);
            wall_stripe(scene.world, hit, span, x, fb, |_| shade);
        }
        if fb.wants_phases() {
            wall_phases(hits, span, x, fb);
        }
    }
}

/// Draws one wall column from its texture column, top to bottom, row `y` lit by `shade(y)`
/// (side shading included).
fn wall_stripe(
    world: &World,
    hit: &ColumnHit,
    span: &WallSpan,
    x: usize,
    fb: &mut Framebuffer,
    shade: impl Fn(usize) -> Shade,
) {
    let tex = world.wall_texture_at(hit.what, hit.cell, heading(hit));
    let column = tex.column(texture_x(hit, tex.width()));
    let th = tex.height();
    let scale = th as f64 / span.height;
    let (first, end) = span.rows;
    // Row numbers as f64 by counting (exact), not by converting each one.
    let mut row = first as f64;
    for (y, px) in (first..end).zip(fb.column_mut(x, first..end)) {
        let v = texel_index((row + 0.5 - span.top) * scale);
        row += 1.0;
        *px = shade(y).apply(column[v.min(th - 1)]);
    }
}

/// Writes one wall column's dither phases: the wall's own coordinates (fraction along, fraction
/// up) on a lattice about a pixel fine (see [`crate::render::dither_phase`]).
fn wall_phases(hits: &[ColumnHit], span: &WallSpan, x: usize, fb: &mut Framebuffer) {
    let hit = &hits[x];
    // Pixels per unit along the wall: from the next (or previous) column on the same face.
    let same = |o: &ColumnHit| o.cell == hit.cell && o.side == hit.side;
    let du = match (x.checked_sub(1).map(|i| &hits[i]), hits.get(x + 1)) {
        (_, Some(n)) if same(n) => (n.wall_x - hit.wall_x).abs(),
        (Some(p), _) if same(p) => (p.wall_x - hit.wall_x).abs(),
        _ => 0.0,
    };
    let along = if du > 0.0 { 1.0 / du } else { span.height };
    let w = fb.width();
    dither_phase::write_upright(
        fb.phases_mut(),
        (w, x),
        span.rows,
        (hit.wall_x, along),
        span.height,
        |y| (y as f64 + 0.5 - span.top) / span.height,
    );
}

/// Horizontal scanline floor/ceiling casting (Lode's method with the shared focal length),
/// with the horizon moved by pitch and the floor/ceiling distances set by the eye height.
fn floor_and_ceiling(
    scene: &Scene,
    spans: &[WallSpan],
    fb: &mut Framebuffer,
    focal: f64,
    horizon: f64,
    eye: f64,
    table: &ShadeTable,
) {
    let (w, h) = (fb.width(), fb.height());
    let cam = &scene.camera;
    let world = scene.world;
    let left = cam.dir - cam.plane;
    let across = cam.plane * (2.0 / w as f64);
    let lamps = scene.lamp_light();
    let moving = scene.point_lights();
    for y in 0..h {
        let p = y as f64 + 0.5 - horizon;
        let is_floor = p > 0.0;
        let height = if is_floor { eye } else { 1.0 - eye };
        let dist = height * focal / p.abs().max(1e-9);
        let shade = table.at(dist);
        let start = cam.pos + left * dist;
        let step = across * dist;
        // Floors and ceilings carry no pattern (measured: patterns there cost more bytes than
        // they gain), and no phase left from the last frame either.
        if fb.wants_phases() {
            fb.phase_row_mut(y).fill(NEUTRAL_PHASE);
        }
        let row = fb.row_mut(y);
        if lamps.is_none() && moving.is_empty() {
            let plain = PlainRow {
                world,
                is_floor,
                start,
                step,
                shade,
            };
            plain.paint(row, |x| {
                let span = &spans[x].rows;
                y < span.0 || y >= span.1
            });
            continue;
        }
        // Neighbouring pixels mostly share a map cell: its paint is looked up once per run.
        let mut here: Option<((i64, i64), Fill)> = None;
        for (x, px) in row.iter_mut().enumerate() {
            let span = &spans[x].rows;
            if y >= span.0 && y < span.1 {
                continue;
            }
            let fx = start.x + step.x * x as f64;
            let fy = start.y + step.y * x as f64;
            let (ci, cj) = (fast_floor(fx), fast_floor(fy));
            let fill = match here {
                Some((cell, fill)) if cell == (ci, cj) => fill,
                _ => {
                    let fill = world.surface_fill(ci, cj, is_floor);
                    here = Some(((ci, cj), fill));
                    fill
                }
            };
            let shade = match lamps {
                Some(lamps) if moving.is_empty() => shade.lit(lamps.at(Vec2::new(fx, fy))),
                None if moving.is_empty() => shade,
                _ => {
                    let at = Vec2::new(fx, fy);
                    let lamp = lamps.map_or(0, |l| l.at(at));
                    let z = if is_floor { 0.0 } else { 1.0 };
                    shade.lit(point_light::add(lamp, point_light::level(moving, at, z)))
                }
            };
            *px = shade.apply(fill.at_unit(fx - ci as f64, fy - cj as f64));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::Cell;
    use crate::vec2::Vec2;

    fn hit(side: Side, ray: Vec2, wall_x: f64) -> ColumnHit {
        ColumnHit {
            cell: (0, 0),
            what: Cell::Wall(1),
            side,
            perp_dist: 1.0,
            wall_x,
            ray_dir: ray,
        }
    }

    #[test]
    fn face_headings_follow_the_ray() {
        assert_eq!(heading(&hit(Side::Y, Vec2::new(0.1, -1.0), 0.0)), 0);
        assert_eq!(heading(&hit(Side::Y, Vec2::new(0.1, 1.0), 0.0)), 1);
        assert_eq!(heading(&hit(Side::X, Vec2::new(-1.0, 0.1), 0.0)), 2);
        assert_eq!(heading(&hit(Side::X, Vec2::new(1.0, 0.1), 0.0)), 3);
    }

    #[test]
    fn texture_left_edge_is_on_the_viewers_left_on_every_face() {
        // The viewer's left at a face is where wall_x → the texture's u = 0 must appear.
        // Looking east the left is north (small y); looking west it is south (large y);
        // looking north it is west (small x); looking south it is east (large x).
        let cases = [
            (Side::X, Vec2::new(1.0, 0.0), 0.01),
            (Side::X, Vec2::new(-1.0, 0.0), 0.99),
            (Side::Y, Vec2::new(0.0, -1.0), 0.01),
            (Side::Y, Vec2::new(0.0, 1.0), 0.99),
        ];
        for (side, ray, wall_x) in cases {
            assert_eq!(
                texture_x(&hit(side, ray, wall_x), 64),
                0,
                "{side:?} {ray:?}"
            );
        }
    }

    #[test]
    fn a_wall_one_unit_away_is_as_tall_as_the_focal_length() {
        let s = wall_span(1.0, 40.0, 60);
        assert_eq!(s.height, 40.0);
        assert_eq!(s.top, 10.0);
        assert_eq!(s.rows, (10, 50));
    }

    #[test]
    fn spans_clamp_to_the_screen_when_very_close() {
        let s = wall_span(0.0, 40.0, 60);
        assert_eq!(s.rows, (0, 60));
    }

    /// Two floor zones side by side, seen from the line between them: every floor row shows
    /// the left zone's colour on the left and the right one's on the right, however the row
    /// crosses cells (the caster keeps a cell's paint only while it stays in that cell).
    #[test]
    fn a_floor_row_shows_each_zone_it_crosses() {
        use crate::camera::Camera;
        use crate::color::Rgb;
        use crate::map::parse_map;
        use crate::world::TextureSource;
        let text = "NO textures/bricks.png\nSO textures/bricks.png\nWE textures/stone.png\n\
                    EA textures/stone.png\nF 0,0,255\nFa 255,0,0\nFb 0,255,0\nC 40,40,40\n\n\
                    1111111111\n1aaaabbbb1\n1aaaabbbb1\n1aaaabbbb1\n1aaaabbbb1\n1aaaabbbb1\n\
                    1Naaabbbb1\n1111111111\n";
        let map = parse_map("zones.cub", text.as_bytes()).unwrap();
        let world = World::load(map, &TextureSource::Embedded, true).unwrap().0;
        // On the boundary x = 5 between the zones, looking north (up the map).
        let cam = Camera::from_angle(Vec2::new(5.0, 6.9), 90.0, 66.0);
        let mut fb = Framebuffer::new(120, 80);
        Scene::new(&world, cam).render_into(&mut fb, None);
        let red = |c: Rgb| c.r > 0 && c.g == 0 && c.b == 0;
        let green = |c: Rgb| c.g > 0 && c.r == 0 && c.b == 0;
        let mut rows_with_both = 0;
        for y in 40..80 {
            let row = fb.row(y);
            let (left, right) = (&row[..54], &row[66..]);
            assert!(
                !left.iter().any(|&c| green(c)),
                "row {y}: zone b on the left"
            );
            assert!(
                !right.iter().any(|&c| red(c)),
                "row {y}: zone a on the right"
            );
            if left.iter().any(|&c| red(c)) && right.iter().any(|&c| green(c)) {
                rows_with_both += 1;
            }
        }
        assert!(
            rows_with_both >= 30,
            "{rows_with_both} rows show both zones"
        );
    }
}
