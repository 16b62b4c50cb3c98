//! The map seen from above: walls by type, doors as far as they are open, sprites, other
//! players, the player, the view cone, a fan of this frame's rays and the debugged ray's
//! traversal. Drawn as square pixels in half-blocks. On maps with heights, floors are lighter
//! the higher they are and a ledge too high to step onto is outlined on its upper side.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use super::half_block::HalfBlockView;
use super::plot::{blend, disc, dot, line, mix};
use super::revealed::RevealedTrace;
use crate::camera::Camera;
use crate::color::Rgb;
use crate::map::STEP_UP;
use crate::map::{Cell, DoorPlane, Map};
use crate::render::cast::ColumnHit;
use crate::render::framebuffer::Framebuffer;
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::sprite::Sprite;
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
/// Outline of a sprite that blocks movement, so obstacles read as obstacles.
const SOLID_RIM: Rgb = Rgb::new(20, 20, 24);
/// The lip of a ledge too high to step onto (a contour line, as on a map of hills).
const LEDGE: Rgb = Rgb::new(6, 6, 8);

/// Brightness (of 256) of a floor at height 0; each wall height up adds [`SHADE_PER_HEIGHT`].
const SHADE_AT_0: f64 = 110.0;
const SHADE_PER_HEIGHT: f64 = 64.0;
/// Darkest and brightest floor shades, so deep pits and high balconies keep their colour.
const SHADE_RANGE: (f64, f64) = (40.0, 250.0);

/// How bright a floor at `height` is drawn: higher is lighter, so levels read at a glance.
fn height_shade(height: f64) -> u16 {
    (SHADE_AT_0 + SHADE_PER_HEIGHT * height)
        .round()
        .clamp(SHADE_RANGE.0, SHADE_RANGE.1) as u16
}

/// Whether two neighbouring open cells differ by more than a walkable step.
fn is_ledge(map: &Map, a: (i64, i64), b: (i64, i64)) -> bool {
    match (map.span(a.0, a.1), map.span(b.0, b.1)) {
        (Some(x), Some(y)) => (x.floor - y.floor).abs() > STEP_UP + 1e-9,
        _ => false,
    }
}

/// The ASCII minimap's glyph for a floor at `height`: `.` at 0, `1`–`9` quarter walls (one
/// walkable step each) above it (9 = 2.25 or more), `-` up to half a wall below 0, `_` deeper.
#[must_use]
pub fn level_glyph(height: f64) -> &'static str {
    const UP: [&str; 10] = [".", "1", "2", "3", "4", "5", "6", "7", "8", "9"];
    let quarters = (height / STEP_UP).round();
    if quarters >= 0.0 {
        UP[(quarters as usize).min(9)]
    } else if quarters >= -2.0 {
        "-"
    } else {
        "_"
    }
}

/// Radius on the map of a sprite that does not block (it has no collision radius to show).
const DECOR_RADIUS: f64 = 0.18;

/// Something else moving in the world (another player), drawn as a disc with a facing tick and a
/// name beside it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Marker<'a> {
    /// Map position.
    pub pos: Vec2,
    /// Facing, any length (zero: no tick).
    pub dir: Vec2,
    /// Disc radius in cells.
    pub radius: f64,
    /// Disc colour.
    pub colour: Rgb,
    /// Written in the cell right of the marker when it fits in the pane.
    pub label: Option<&'a str>,
}

/// A game object on the map (a treasure, a key, a creature): a dot in its colour, or its
/// character on the ASCII map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thing {
    /// Map position.
    pub pos: Vec2,
    /// Dot colour.
    pub colour: Rgb,
    /// What the ASCII map shows (one character).
    pub glyph: &'static str,
}

/// The exit's cells on the minimap.
const EXIT: Rgb = Rgb::new(90, 230, 120);

/// Radius of a thing's dot, in cells.
const THING_RADIUS: f64 = 0.18;

/// Which part of the map is on the canvas: pixels per cell and the map point at pixel (0, 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapView {
    /// Canvas pixels per map cell.
    pub scale: f64,
    /// The map point at canvas pixel (0, 0).
    pub origin: Vec2,
}

/// Where a pane showing `visible` map cells along an axis starts: the map centred when it fits,
/// else following `at` without showing past the map's edges.
fn follow(map_len: usize, visible: f64, at: f64) -> f64 {
    let map_len = map_len as f64;
    if map_len <= visible {
        -(visible - map_len) / 2.0
    } else {
        (at - visible / 2.0).clamp(0.0, map_len - visible)
    }
}

impl MapView {
    /// Fits the whole map when it fits at [`MIN_SCALE`] or more, else follows `player`.
    #[must_use]
    pub fn new(map_size: (usize, usize), canvas: (usize, usize), player: Vec2) -> Self {
        let fit = (canvas.0 / map_size.0.max(1)).min(canvas.1 / map_size.1.max(1));
        let scale = fit.clamp(MIN_SCALE, MAX_SCALE) as f64;
        Self {
            scale,
            origin: Vec2::new(
                follow(map_size.0, canvas.0 as f64 / scale, player.x),
                follow(map_size.1, canvas.1 as f64 / scale, player.y),
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

    /// What the minimap pane shows: zoomed on the ray from `pos` to `focus` (the debugged ray's
    /// hit, while the debugger is paused), else the map around `pos`. Overlays use it to line up.
    #[must_use]
    pub fn for_pane(
        map_size: (usize, usize),
        canvas: (usize, usize),
        pos: Vec2,
        focus: Option<Vec2>,
    ) -> Self {
        match focus {
            Some(hit) => Self::around(pos, hit, canvas),
            None => Self::new(map_size, canvas, pos),
        }
    }

    /// A map point in canvas pixels.
    #[must_use]
    pub fn to_px(self, p: Vec2) -> (f64, f64) {
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
    doors: Option<&'a DoorState>,
    markers: &'a [Marker<'a>],
    things: &'a [Thing],
    ascii: bool,
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
            doors: None,
            markers: &[],
            things: &[],
            ascii: false,
        }
    }

    /// Draws each door as the part of its panel still shut (without this every door is shut).
    #[must_use]
    pub fn doors(mut self, doors: &'a DoorState) -> Self {
        self.doors = Some(doors);
        self
    }

    /// Also shows these (other players).
    #[must_use]
    pub fn markers(mut self, markers: &'a [Marker<'a>]) -> Self {
        self.markers = markers;
        self
    }

    /// Also shows the game's objects (items left, creatures); the map's exits always show.
    #[must_use]
    pub fn things(mut self, things: &'a [Thing]) -> Self {
        self.things = things;
        self
    }

    /// Debugger focus: zoom on the debugged ray (its whole path to the hit) and drop the fan
    /// of rays, so single steps are easy to follow.
    #[must_use]
    pub fn focus_on_ray(mut self, on: bool) -> Self {
        self.focus = on;
        self
    }

    /// Draws plain ASCII characters instead of coloured half-blocks (for `--colors mono`):
    /// `#` wall, `.` floor, `+` shut door, `/` open door, `o` sprite, `E` exit, things by their
    /// glyph, `@` player, `*` the ray, `X` the cell it reached; raised and sunk floors by `level_glyph`.
    #[must_use]
    pub fn ascii(mut self, on: bool) -> Self {
        self.ascii = on;
        self
    }

    /// Also shows the debugged ray's revealed cells and its path so far.
    #[must_use]
    pub fn debug_ray(mut self, trace: RevealedTrace<'a>) -> Self {
        self.debug = Some(trace);
        self
    }

    /// Which part of the map a canvas of `canvas` pixels shows (the debugged ray when focused).
    #[must_use]
    pub fn map_view(&self, canvas: (usize, usize)) -> MapView {
        let map = &self.world.map;
        let pos = self.camera.pos;
        let focus = match &self.debug {
            Some(d) if self.focus => Some(pos + d.trace.ray_dir * d.trace.hit.perp_dist),
            _ => None,
        };
        MapView::for_pane((map.width, map.height), canvas, pos, focus)
    }

    /// Paints into a pixel canvas (two pixels per terminal row); also used for PNG screenshots.
    pub fn paint(&self, fb: &mut Framebuffer) {
        let map = &self.world.map;
        let view = self.map_view((fb.width(), fb.height()));
        let palette = Palette::new(self.world);
        let heights = map.has_heights();
        for py in 0..fb.height() {
            for px in 0..fb.width() {
                let (i, j) = view.cell_at(px, py);
                let what = match map.cell(i, j) {
                    // The panel is drawn on top, as far as it is shut.
                    Cell::Door(_) if self.doors.is_some() => Cell::Floor { zone: 0 },
                    c => c,
                };
                let height = map.floor_height(i, j);
                let lip = heights && on_ledge_lip(map, &view, (px, py), (i, j), height);
                let colour = if lip {
                    LEDGE
                } else {
                    palette.cell(what, i, j, height)
                };
                fb.set(px, py, colour);
            }
        }
        if let Some(doors) = self.doors {
            paint_door_panels(fb, &view, map, doors);
        }
        for e in &map.exits {
            fill_cell(fb, &view, e.cell, EXIT, 200);
        }
        for s in &self.world.sprites {
            paint_sprite(fb, &view, s, palette.sprites[s.sheet]);
        }
        for t in self.things {
            let at = view.to_px(t.pos);
            let r = (THING_RADIUS * view.scale).max(1.0);
            disc(fb, at, r + 0.75, SOLID_RIM, 256);
            disc(fb, at, r, t.colour, 256);
        }
        for m in self.markers {
            paint_marker(fb, &view, m);
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

/// Whether canvas pixel `px` of cell `cell` (floor at `height`) lies on the cell's edge toward
/// a lower neighbour that cannot be stepped up from: the ledge is outlined on its upper side.
fn on_ledge_lip(
    map: &Map,
    view: &MapView,
    px: (usize, usize),
    cell: (i64, i64),
    height: f64,
) -> bool {
    let (x, y) = px;
    let around = [
        (x.wrapping_sub(1), y),
        (x + 1, y),
        (x, y.wrapping_sub(1)),
        (x, y + 1),
    ];
    around.iter().any(|&(ax, ay)| {
        if ax == usize::MAX || ay == usize::MAX {
            return false;
        }
        let other = view.cell_at(ax, ay);
        other != cell
            && map.span(other.0, other.1).is_some_and(|s| s.floor < height)
            && is_ledge(map, cell, other)
    })
}

/// Each door's shut part: a bar along its panel line from `open` to the far end of the cell.
fn paint_door_panels(fb: &mut Framebuffer, view: &MapView, map: &Map, doors: &DoorState) {
    let half_width = (view.scale * 0.12).max(0.5);
    for &(i, j) in doors.cells() {
        let open = doors.open_amount((i, j));
        if open >= 1.0 {
            continue;
        }
        let (x, y) = (i as f64, j as f64);
        let Cell::Door(plane) = map.cell(i, j) else {
            continue;
        };
        let (a, b) = match plane {
            DoorPlane::X => (Vec2::new(x + 0.5, y + open), Vec2::new(x + 0.5, y + 1.0)),
            DoorPlane::Y => (Vec2::new(x + open, y + 0.5), Vec2::new(x + 1.0, y + 0.5)),
        };
        let (pa, pb) = (view.to_px(a), view.to_px(b));
        let (lo, hi) = (
            (pa.0.min(pb.0) - half_width, pa.1.min(pb.1) - half_width),
            (pa.0.max(pb.0) + half_width, pa.1.max(pb.1) + half_width),
        );
        for py in lo.1.round() as i64..hi.1.round() as i64 {
            for px in lo.0.round() as i64..hi.0.round() as i64 {
                blend(fb, px, py, DOOR, 256);
            }
        }
    }
}

/// A sprite as a disc of its collision radius in its own colour; solid ones get a dark rim and
/// directional ones a tick toward their facing.
fn paint_sprite(fb: &mut Framebuffer, view: &MapView, s: &Sprite, colour: Rgb) {
    let def = &s.def;
    let radius = def.solid.unwrap_or(DECOR_RADIUS);
    let at = view.to_px(def.pos);
    let r = (radius * view.scale).max(1.0);
    if def.solid.is_some() {
        disc(fb, at, r + 0.75, SOLID_RIM, 256);
    }
    disc(fb, at, r, colour, 256);
    if def.views > 1 {
        let a = def.facing_deg.to_radians();
        let dir = Vec2::new(a.cos(), -a.sin());
        line(
            fb,
            at,
            view.to_px(def.pos + dir * (radius * 2.0)),
            colour,
            256,
        );
    }
}

fn paint_marker(fb: &mut Framebuffer, view: &MapView, m: &Marker) {
    let at = view.to_px(m.pos);
    let r = (m.radius * view.scale).max(1.0);
    disc(fb, at, r + 0.75, SOLID_RIM, 256);
    disc(fb, at, r, m.colour, 256);
    let len = m.dir.length();
    if len > 0.0 {
        let tip = m.pos + m.dir * (m.radius * 2.5 / len);
        line(fb, at, view.to_px(tip), m.colour, 256);
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
    /// Per zone, the floor's mean colour (shaded by height when drawn).
    floors: Vec<Rgb>,
    /// Per sprite sheet: the mean opaque colour of its first picture.
    sprites: Vec<Rgb>,
}

impl Palette {
    fn new(world: &World) -> Self {
        let mut walls = [Rgb::default(); 10];
        for (d, w) in walls.iter_mut().enumerate() {
            let avg = world.wall_texture(Cell::Wall(d as u8), 0).mean();
            *w = mix(avg, Rgb::new(255, 255, 255), 60);
        }
        let zones = world.map.zones.len() + 1;
        let floors = (0..zones)
            .map(|z| match world.floor_paint(z as u8) {
                Paint::Colour(c) => c,
                Paint::Texture(i) => world.textures[i].mean(),
            })
            .collect();
        let brighten = |c: Rgb| mix(c, Rgb::new(255, 255, 255), 40);
        let sprites = world.sheets.iter().map(|s| brighten(s.mean())).collect();
        Self {
            walls,
            floors,
            sprites,
        }
    }

    /// The colour of a cell; floors by their `height` (0 gives the flat map's colours).
    fn cell(&self, what: Cell, i: i64, j: i64, height: f64) -> Rgb {
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
                let c = self.floors[usize::from(zone).min(self.floors.len() - 1)]
                    .scaled(height_shade(height));
                if checker {
                    c
                } else {
                    c.scaled(226)
                }
            }
        }
    }
}

impl Minimap<'_> {
    /// The ASCII map: one map cell is two characters wide and one row tall (about square).
    fn render_ascii(&self, area: Rect, buf: &mut Buffer) {
        let map = &self.world.map;
        let pos = self.camera.pos;
        let (cols, rows) = (f64::from(area.width) / 2.0, f64::from(area.height));
        let end = self.debug.as_ref().map(|d| d.end_point(pos));
        let centre = match end {
            Some(e) if self.focus => Vec2::new((pos.x + e.x) / 2.0, (pos.y + e.y) / 2.0),
            _ => pos,
        };
        let origin = Vec2::new(
            follow(map.width, cols, centre.x).floor(),
            follow(map.height, rows, centre.y).floor(),
        );
        // Terminal cell of a map point, if on the pane.
        let at = |p: Vec2| -> Option<(u16, u16)> {
            let (x, y) = ((p.x - origin.x) * 2.0, p.y - origin.y);
            (x >= 0.0 && y >= 0.0 && x < f64::from(area.width) && y < rows)
                .then(|| (area.x + x as u16, area.y + y as u16))
        };
        let put = |p: Vec2, c: &str, buf: &mut Buffer| {
            if let Some(xy) = at(p) {
                buf[xy].set_symbol(c);
            }
        };
        for cy in 0..area.height {
            for cx in 0..area.width {
                let i = (origin.x + f64::from(cx) / 2.0).floor() as i64;
                let j = (origin.y + f64::from(cy)).floor() as i64;
                let c = match map.cell(i, j) {
                    Cell::Void => " ",
                    Cell::Wall(_) => "#",
                    Cell::Floor { .. } => level_glyph(map.floor_height(i, j)),
                    Cell::Door(_) => match self.doors {
                        Some(d) if d.open_amount((i, j)) >= 0.5 => "/",
                        _ => "+",
                    },
                };
                buf[(area.x + cx, area.y + cy)].set_symbol(c);
            }
        }
        for s in &self.world.sprites {
            put(s.def.pos, "o", buf);
        }
        if let (Some(d), Some(e)) = (&self.debug, end) {
            let len = (e - pos).length();
            let n = (len * 8.0).ceil().max(1.0) as usize;
            for k in 1..=n {
                put(pos + (e - pos) * (k as f64 / n as f64), "*", buf);
            }
            let (i, j) = d.current_cell();
            let hit = Vec2::new(i as f64 + 0.25, j as f64 + 0.5);
            put(hit, "X", buf);
            put(hit + Vec2::new(0.5, 0.0), "X", buf);
        }
        // The game's marks and other players over the ray, so its path never hides them.
        for e in &map.exits {
            let row = e.cell.1 as f64 + 0.5;
            put(Vec2::new(e.cell.0 as f64, row), "E", buf);
            put(Vec2::new(e.cell.0 as f64 + 0.5, row), "E", buf);
        }
        for t in self.things {
            put(t.pos, t.glyph, buf);
        }
        for m in self.markers {
            put(m.pos, "&", buf);
        }
        put(pos, "@", buf);
    }
}

impl Widget for Minimap<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let area = area.intersection(buf.area);
        if area.is_empty() {
            return;
        }
        if self.ascii {
            self.render_ascii(area, buf);
            return;
        }
        let mut fb = Framebuffer::for_cells(area.width, area.height);
        self.paint(&mut fb);
        HalfBlockView::new(&fb).render(area, buf);
        let view = self.map_view((fb.width(), fb.height()));
        for m in self.markers {
            if let Some(label) = m.label {
                write_label(&view, m, label, area, buf);
            }
        }
    }
}

/// A marker's name in the cells right of it, clipped to the pane (skipped if its start is off it).
fn write_label(view: &MapView, m: &Marker, label: &str, area: Rect, buf: &mut Buffer) {
    let (px, py) = view.to_px(m.pos);
    let col = (px + m.radius * view.scale + 1.0).floor();
    let row = (py / 2.0).floor();
    if col < 0.0 || row < 0.0 || col >= f64::from(area.width) || row >= f64::from(area.height) {
        return;
    }
    let (x, y) = (area.x + col as u16, area.y + row as u16);
    let room = usize::from(area.right() - x);
    let style = ratatui::style::Style::new()
        .fg(ratatui::style::Color::Rgb(
            m.colour.r, m.colour.g, m.colour.b,
        ))
        .bg(ratatui::style::Color::Rgb(VOID.r, VOID.g, VOID.b));
    super::text::put_str(buf, x, y, label, room, style);
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

    fn painted(map: &Minimap, canvas: (usize, usize)) -> (Framebuffer, MapView) {
        let mut fb = Framebuffer::new(canvas.0, canvas.1);
        map.paint(&mut fb);
        (fb, map.map_view(canvas))
    }

    fn pixel(fb: &Framebuffer, view: &MapView, p: Vec2) -> Rgb {
        let (x, y) = view.to_px(p);
        fb.get(x as usize, y as usize)
    }

    #[test]
    fn sprites_show_in_their_sheet_colour_where_they_stand() {
        let world = World::default_world();
        let cam = Camera::from_angle(Vec2::new(5.5, 5.5), 0.0, 66.0);
        let map = Minimap::new(&world, &cam, &[]);
        let (fb, view) = painted(&map, (224, 176));
        let palette = Palette::new(&world);
        for s in &world.sprites {
            assert_eq!(
                pixel(&fb, &view, s.def.pos),
                palette.sprites[s.sheet],
                "sprite at {:?}",
                s.def.pos
            );
        }
        // Solid sprites wear a dark rim just outside their radius.
        let barrel = world
            .sprites
            .iter()
            .find(|s| s.def.solid.is_some())
            .unwrap();
        let r = barrel.def.solid.unwrap();
        let rim = barrel.def.pos + Vec2::new(r + 0.5 / view.scale, 0.0);
        assert_eq!(pixel(&fb, &view, rim), SOLID_RIM);
    }

    #[test]
    fn door_panels_shrink_as_doors_open() {
        let world = World::default_world();
        let cam = Camera::from_angle(Vec2::new(5.5, 5.5), 0.0, 66.0);
        let mut doors = DoorState::new(&world.map);
        let &cell = doors.cells().first().unwrap();
        let Cell::Door(plane) = world.map.cell(cell.0, cell.1) else {
            panic!("not a door");
        };
        let on_panel = |along: f64| {
            let (x, y) = (cell.0 as f64, cell.1 as f64);
            match plane {
                DoorPlane::X => Vec2::new(x + 0.5, y + along),
                DoorPlane::Y => Vec2::new(x + along, y + 0.5),
            }
        };
        let at = |doors: &DoorState, along: f64| {
            let map = Minimap::new(&world, &cam, &[]).doors(doors);
            let (fb, view) = painted(&map, (224, 176));
            pixel(&fb, &view, on_panel(along))
        };
        assert_eq!(at(&doors, 0.2), DOOR);
        assert_eq!(at(&doors, 0.8), DOOR);
        doors.set_open(cell, 0.5);
        assert_ne!(at(&doors, 0.2), DOOR, "the open half is passage");
        assert_eq!(at(&doors, 0.8), DOOR, "the shut half is still panel");
        doors.set_open(cell, 1.0);
        assert_ne!(at(&doors, 0.8), DOOR);
        // Without a door state every door is a whole shut cell, as before.
        let map = Minimap::new(&world, &cam, &[]);
        let (fb, view) = painted(&map, (224, 176));
        assert_eq!(pixel(&fb, &view, on_panel(0.1)), DOOR);
    }

    #[test]
    fn on_the_ascii_map_game_things_and_the_exit_show_over_the_debugged_ray() {
        let world = World::default_world();
        // From the west room's middle, looking east along row 5 towards the start room.
        let cam = Camera::from_angle(Vec2::new(5.5, 5.5), 0.0, 66.0);
        let trace = crate::render::cast::trace_column(&world.map, &cam, 20, 40);
        let things = [Thing {
            pos: Vec2::new(7.5, 5.5),
            colour: Rgb::new(255, 200, 60),
            glyph: "$",
        }];
        let map = Minimap::new(&world, &cam, &[])
            .ascii(true)
            .things(&things)
            .debug_ray(RevealedTrace::full(&trace));
        let area = Rect::new(0, 0, 40, 20);
        let mut buf = Buffer::empty(area);
        map.render(area, &mut buf);
        let text: String = (0..area.height)
            .map(|y| {
                (0..area.width)
                    .map(|x| buf[(x, y)].symbol().to_owned())
                    .collect::<String>()
            })
            .collect::<Vec<_>>()
            .join("\n");
        let row = text.lines().find(|l| l.contains('@')).expect("player row");
        assert!(row.contains('$') && row.contains('*'), "{text}");
        assert!(
            row.find('$') > row.find('@'),
            "the $ on the ray east of @: {text}"
        );
    }

    #[test]
    fn markers_are_drawn_with_their_label_beside_them() {
        let world = World::default_world();
        let cam = Camera::from_angle(Vec2::new(5.5, 5.5), 0.0, 66.0);
        let other = Marker {
            pos: Vec2::new(3.5, 3.5),
            dir: Vec2::new(1.0, 0.0),
            radius: 0.25,
            colour: Rgb::new(250, 40, 200),
            label: Some("ada"),
        };
        let markers = [other];
        let map = Minimap::new(&world, &cam, &[]).markers(&markers);
        let (fb, view) = painted(&map, (112, 88));
        assert_eq!(pixel(&fb, &view, other.pos), other.colour);
        // The facing tick runs east of the disc.
        assert_eq!(
            pixel(&fb, &view, other.pos + Vec2::new(0.5, 0.0)),
            other.colour
        );
        let area = Rect::new(0, 0, 112, 44);
        let mut buf = Buffer::empty(area);
        map.render(area, &mut buf);
        let (px, py) = view.to_px(other.pos);
        let row = (py / 2.0) as u16;
        let text: String = (0..area.width)
            .map(|x| buf[(x, row)].symbol().to_owned())
            .collect();
        let col = text.find("ada").expect("label on the marker's row");
        assert!(col as f64 > px, "label {col} right of the marker at {px}");
    }

    #[test]
    fn cells_are_square_on_screen() {
        // A canvas pixel is one column wide and half a row tall, i.e. square on a 1:2 font.
        let v = MapView::new((28, 22), (60, 80), Vec2::new(3.0, 3.0));
        let (a, b) = (v.to_px(Vec2::new(0.0, 0.0)), v.to_px(Vec2::new(1.0, 1.0)));
        assert_eq!(b.0 - a.0, b.1 - a.1);
    }
}
