//! The map seen from above: walls by type, the player, the view cone, a fan of this frame's
//! rays and the debugged ray's traversal. Drawn as square pixels in half-blocks.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use super::half_block::HalfBlockView;
use super::plot::{blend, dot, line, mix};
use super::revealed::RevealedTrace;
use crate::camera::Camera;
use crate::cast::ColumnHit;
use crate::color::Rgb;
use crate::framebuffer::Framebuffer;
use crate::map::Cell;
use crate::texture::Texture;
use crate::vec2::Vec2;
use crate::world::{Paint, World};

/// Fewest pixels per map cell; below this rays and cells blur, so the map scrolls instead.
pub const MIN_SCALE: usize = 3;

/// Most pixels per map cell when a small map is blown up to fill the pane.
pub const MAX_SCALE: usize = 12;

/// How many rays of the frame's fan are drawn (plus the two cone edges).
const FAN_RAYS: usize = 12;

/// Doors on the minimap: a warm wood colour, distinct from every wall type.
const DOOR: Rgb = Rgb::new(196, 140, 60);
const VOID: Rgb = Rgb::new(14, 14, 18);
const PLAYER: Rgb = Rgb::new(255, 255, 255);
const FACING: Rgb = Rgb::new(255, 120, 60);
const FAN: Rgb = Rgb::new(255, 226, 120);
const VISITED: Rgb = Rgb::new(60, 200, 255);
const CURRENT: Rgb = Rgb::new(255, 236, 64);
const HIT: Rgb = Rgb::new(255, 70, 70);
const DEBUG_RAY: Rgb = Rgb::new(150, 240, 255);

/// Which part of the map is on the canvas: pixels per cell and the map point at pixel (0, 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapView {
    pub scale: f64,
    pub origin: Vec2,
}

impl MapView {
    /// Fits the whole map when it fits at [`MIN_SCALE`] or more, else follows `player`.
    #[must_use]
    pub fn new(map_size: (usize, usize), canvas: (usize, usize), player: Vec2) -> Self {
        let fit = (canvas.0 / map_size.0.max(1)).min(canvas.1 / map_size.1.max(1));
        let scale = fit.clamp(MIN_SCALE, MAX_SCALE) as f64;
        let axis = |map_len: usize, px: usize, at: f64| {
            let visible = px as f64 / scale;
            let map_len = map_len as f64;
            if map_len <= visible {
                -(visible - map_len) / 2.0
            } else {
                (at - visible / 2.0).clamp(0.0, map_len - visible)
            }
        };
        Self {
            scale,
            origin: Vec2::new(
                axis(map_size.0, canvas.0, player.x),
                axis(map_size.1, canvas.1, player.y),
            ),
        }
    }

    /// Zooms on a segment (the debugged ray): as large as fits with a cell of margin around it.
    #[must_use]
    pub fn around(a: Vec2, b: Vec2, canvas: (usize, usize)) -> Self {
        let span = |d: f64, px: usize| px as f64 / (d.abs() + 2.0);
        let scale = span(a.x - b.x, canvas.0)
            .min(span(a.y - b.y, canvas.1))
            .floor()
            .clamp(MIN_SCALE as f64, MAX_SCALE as f64);
        let centre = Vec2::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0);
        Self {
            scale,
            origin: Vec2::new(
                centre.x - canvas.0 as f64 / scale / 2.0,
                centre.y - canvas.1 as f64 / scale / 2.0,
            ),
        }
    }

    /// A map point in canvas pixels.
    #[must_use]
    pub fn to_px(&self, p: Vec2) -> (f64, f64) {
        (
            (p.x - self.origin.x) * self.scale,
            (p.y - self.origin.y) * self.scale,
        )
    }

    /// The map cell under the centre of canvas pixel (px, py).
    #[must_use]
    pub fn cell_at(&self, px: usize, py: usize) -> (i64, i64) {
        let x = self.origin.x + (px as f64 + 0.5) / self.scale;
        let y = self.origin.y + (py as f64 + 0.5) / self.scale;
        (x.floor() as i64, y.floor() as i64)
    }
}

/// The minimap widget; build it per frame from the state it shows.
#[derive(Debug, Clone, Copy)]
pub struct Minimap<'a> {
    world: &'a World,
    camera: &'a Camera,
    rays: &'a [ColumnHit],
    debug: Option<RevealedTrace<'a>>,
    focus: bool,
}

impl<'a> Minimap<'a> {
    /// The map around `camera`, with this frame's `rays` (may be empty).
    #[must_use]
    pub fn new(world: &'a World, camera: &'a Camera, rays: &'a [ColumnHit]) -> Self {
        Self {
            world,
            camera,
            rays,
            debug: None,
            focus: false,
        }
    }

    /// Debugger focus: zoom on the debugged ray (its whole path to the hit) and drop the fan
    /// of rays, so single steps are easy to follow.
    #[must_use]
    pub fn focus_on_ray(mut self, on: bool) -> Self {
        self.focus = on;
        self
    }

    /// Also shows the debugged ray's revealed cells and its path so far.
    #[must_use]
    pub fn debug_ray(mut self, trace: RevealedTrace<'a>) -> Self {
        self.debug = Some(trace);
        self
    }

    /// Paints into a pixel canvas (two pixels per terminal row); also used for PNG screenshots.
    pub fn paint(&self, fb: &mut Framebuffer) {
        let map = &self.world.map;
        let canvas = (fb.width(), fb.height());
        let pos = self.camera.pos;
        let view = match &self.debug {
            Some(d) if self.focus => {
                let hit = pos + d.trace.ray_dir * d.trace.hit.perp_dist;
                MapView::around(pos, hit, canvas)
            }
            _ => MapView::new((map.width, map.height), canvas, pos),
        };
        let palette = Palette::new(self.world);
        for py in 0..fb.height() {
            for px in 0..fb.width() {
                let (i, j) = view.cell_at(px, py);
                fb.set(px, py, palette.cell(map.cell(i, j), i, j));
            }
        }
        if let Some(d) = &self.debug {
            self.paint_visited(fb, &view, d);
        }
        self.paint_rays(fb, &view);
        if let Some(d) = &self.debug {
            let from = view.to_px(self.camera.pos);
            let to = view.to_px(d.end_point(self.camera.pos));
            line(fb, from, to, DEBUG_RAY, 240);
        }
        let me = view.to_px(self.camera.pos);
        let tip = view.to_px(self.camera.pos + self.camera.dir * 0.9);
        line(fb, me, tip, FACING, 256);
        let size = (view.scale / 3.0).round().max(2.0) as usize;
        dot(fb, me, size, PLAYER);
    }

    fn paint_visited(&self, fb: &mut Framebuffer, view: &MapView, d: &RevealedTrace) {
        let steps = d.steps();
        let mut cells: Vec<((i64, i64), Rgb, u16)> =
            steps.iter().map(|s| (s.cell, VISITED, 110)).collect();
        let current = d.current_cell();
        let end = if d.hit_reached {
            (HIT, 200)
        } else {
            (CURRENT, 190)
        };
        cells.push((current, end.0, end.1));
        for (cell, colour, alpha) in cells {
            fill_cell(fb, view, cell, colour, alpha);
        }
    }

    fn paint_rays(&self, fb: &mut Framebuffer, view: &MapView) {
        let n = self.rays.len();
        if n == 0 {
            return;
        }
        let from = view.to_px(self.camera.pos);
        let end = |hit: &ColumnHit| view.to_px(self.camera.pos + hit.ray_dir * hit.perp_dist);
        if !self.focus {
            let every = (n / FAN_RAYS).max(1);
            for hit in self.rays.iter().step_by(every) {
                line(fb, from, end(hit), FAN, 48);
            }
        }
        for hit in [&self.rays[0], &self.rays[n - 1]] {
            line(fb, from, end(hit), FAN, 190);
        }
    }
}

/// Tints every canvas pixel of map cell `cell`.
fn fill_cell(fb: &mut Framebuffer, view: &MapView, cell: (i64, i64), c: Rgb, alpha: u16) {
    let (x0, y0) = view.to_px(Vec2::new(cell.0 as f64, cell.1 as f64));
    let (x1, y1) = view.to_px(Vec2::new(cell.0 as f64 + 1.0, cell.1 as f64 + 1.0));
    let px = |v: f64| (v - 0.5).ceil() as i64;
    for y in px(y0)..px(y1) {
        for x in px(x0)..px(x1) {
            blend(fb, x, y, c, alpha);
        }
    }
}

/// Map colours derived from the world's own textures, so the minimap matches the 3D view.
struct Palette {
    walls: [Rgb; 10],
    floors: Vec<Rgb>,
}

impl Palette {
    fn new(world: &World) -> Self {
        let mut walls = [Rgb::default(); 10];
        for (d, w) in walls.iter_mut().enumerate() {
            let avg = texture_average(world.wall_texture(Cell::Wall(d as u8), 0));
            *w = mix(avg, Rgb::new(255, 255, 255), 60);
        }
        let zones = world.map.zones.len() + 1;
        let floors = (0..zones)
            .map(|z| {
                let c = match world.floor_paint(z as u8) {
                    Paint::Colour(c) => c,
                    Paint::Texture(i) => texture_average(&world.textures[i]),
                };
                c.scaled(110)
            })
            .collect();
        Self { walls, floors }
    }

    fn cell(&self, what: Cell, i: i64, j: i64) -> Rgb {
        let checker = (i + j).rem_euclid(2) == 0;
        match what {
            Cell::Void => VOID,
            Cell::Door(_) => DOOR,
            Cell::Wall(d) => {
                let c = self.walls[usize::from(d).min(9)];
                if checker {
                    c
                } else {
                    c.scaled(236)
                }
            }
            Cell::Floor { zone } => {
                let c = self.floors[usize::from(zone).min(self.floors.len() - 1)];
                if checker {
                    c
                } else {
                    c.scaled(226)
                }
            }
        }
    }
}

/// The mean colour of a texture.
fn texture_average(t: &Texture) -> Rgb {
    let (mut r, mut g, mut b, mut n) = (0u64, 0u64, 0u64, 0u64);
    for c in (0..t.width()).flat_map(|x| t.column(x)) {
        r += u64::from(c.r);
        g += u64::from(c.g);
        b += u64::from(c.b);
        n += 1;
    }
    let n = n.max(1);
    Rgb::new((r / n) as u8, (g / n) as u8, (b / n) as u8)
}

impl Widget for Minimap<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let area = area.intersection(buf.area);
        if area.is_empty() {
            return;
        }
        let mut fb = Framebuffer::for_cells(area.width, area.height);
        self.paint(&mut fb);
        HalfBlockView::new(&fb).render(area, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_maps_are_centred_and_large_ones_follow_the_player() {
        let v = MapView::new((10, 10), (100, 60), Vec2::new(5.0, 5.0));
        assert_eq!(v.scale, 6.0);
        assert_eq!(v.origin, Vec2::new(-(100.0 / 6.0 - 10.0) / 2.0, 0.0));
        let v = MapView::new((100, 100), (60, 30), Vec2::new(50.0, 99.0));
        assert_eq!(v.scale, MIN_SCALE as f64);
        assert_eq!(v.origin, Vec2::new(40.0, 90.0));
        assert_eq!(v.cell_at(0, 0), (40, 90));
        let v = MapView::new((100, 100), (60, 30), Vec2::new(1.0, 1.0));
        assert_eq!(v.origin, Vec2::new(0.0, 0.0));
    }

    #[test]
    fn focus_zooms_on_the_ray_with_a_margin() {
        let v = MapView::around(Vec2::new(2.0, 2.0), Vec2::new(6.0, 4.0), (60, 40));
        assert_eq!(v.scale, 10.0);
        let (a, b) = (v.to_px(Vec2::new(2.0, 2.0)), v.to_px(Vec2::new(6.0, 4.0)));
        assert!(
            a.0 >= 0.0 && a.1 >= 0.0 && b.0 <= 60.0 && b.1 <= 40.0,
            "{a:?} {b:?}"
        );
    }

    #[test]
    fn cells_are_square_on_screen() {
        // A canvas pixel is one column wide and half a row tall, i.e. square on a 1:2 font.
        let v = MapView::new((28, 22), (60, 80), Vec2::new(3.0, 3.0));
        let (a, b) = (v.to_px(Vec2::new(0.0, 0.0)), v.to_px(Vec2::new(1.0, 1.0)));
        assert_eq!(b.0 - a.0, b.1 - a.1);
    }
}
