//! Other players as the world's own sprites: the 8-view walking creature, facing where its
//! player looks and animated while it walks, drawn by the world's sprite renderer; a marker in
//! their minimap colour over their heads (so they are not taken for the map's own creatures),
//! their name above them when near, and their names on the minimap.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};

use crate::color::Rgb;
use crate::game::multi::players::{PlayerId, Snapshot};
use crate::game::GameState;
use crate::map::{Blend, ColourKey, SpriteDef, TextureRef};
use crate::render::cast::Cast;
use crate::render::framebuffer::Framebuffer;
use crate::render::sprite_projection::project_on;
use crate::texture::builtin;
use crate::widget::half_block::is_view_cell;
use crate::widget::minimap::MapView;
use crate::world::sprite::Sprite;
use crate::world::World;

/// The built-in sprite sheet players wear (8 views × 4 walking frames).
pub const AVATAR_SHEET: &str = "creature";

/// A player's sprite size in cells (as wide as tall), a little shorter than a wall.
pub const AVATAR_SCALE: f64 = 0.7;

/// Walking animation speed, in frames per second (standing players show frame 0).
pub const WALK_FPS: f64 = 6.0;

/// A world as sessions draw it: `world` with the avatar sheet among its sheets (reused when the
/// map already loads it); returns the sheet's index.
#[must_use]
pub fn with_avatar_sheet(mut world: World) -> (World, usize) {
    let sheet = builtin::sheet_by_name(AVATAR_SHEET).expect("the creature sheet is built in");
    let index = match world.sheets.iter().position(|s| *s == sheet) {
        Some(i) => i,
        None => {
            world.sheets.push(sheet);
            world.sheets.len() - 1
        }
    };
    (world, index)
}

/// The sprite of a player standing in `state`'s pose.
#[must_use]
pub fn avatar(state: &GameState, walking: bool, sheet: usize) -> Sprite {
    let def = SpriteDef {
        pos: state.camera.pos,
        texture: TextureRef {
            path: AVATAR_SHEET.to_owned(),
            line: 0,
            col: 0,
        },
        scale: (AVATAR_SCALE, AVATAR_SCALE),
        // A jumping player leaves the floor.
        offset: state.jump.0.max(0.0),
        hang: false,
        // Players block each other in the world task, not through the sprite list.
        solid: None,
        blend: Blend::Normal,
        views: 8,
        facing_deg: state.camera.angle_deg(),
        frames: 4,
        fps: if walking { WALK_FPS } else { 0.0 },
        key: ColourKey::Auto,
        at: (0, 0),
    };
    Sprite { def, sheet }
}

/// How near (in cells) another player must be for its name to show above it in the 3D view.
pub const TAG_DISTANCE: f64 = 5.0;

/// The dark half of a name tag's cells (the letters are drawn over it).
const TAG_BG: Rgb = Rgb::new(14, 14, 18);

/// A name tag in the 3D view, at view cell (`col`, `row`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Tag {
    pub col: u16,
    pub row: u16,
    pub name: String,
    pub color: Rgb,
}

/// Marks every other player visible in `fb` (just rendered through `eye`'s camera; `cast` has
/// the wall depth per column): a downward triangle in the player's minimap colour over its
/// head, hidden where a wall is nearer. Returns the name tags of those within
/// [`TAG_DISTANCE`], for [`draw_tags`].
pub fn mark_players(
    fb: &mut Framebuffer,
    eye: &GameState,
    cast: &Cast,
    snap: &Snapshot,
    eye_id: PlayerId,
) -> Vec<Tag> {
    let (w, h) = (fb.width(), fb.height());
    if w == 0 || h < 2 {
        return Vec::new();
    }
    let mut seen: Vec<_> = snap
        .players
        .iter()
        .filter(|p| p.id != eye_id)
        .filter_map(|p| {
            // Where the avatar's feet are: its cell's floor (0 on flat maps) plus any jump.
            let lift = p.state.footing.floor + p.state.jump.0.max(0.0);
            let pos = p.state.camera.pos;
            project_on(
                &eye.camera,
                &eye.view,
                (pos, (AVATAR_SCALE, AVATAR_SCALE), lift),
                (w, h),
                fb.pixel_height(),
            )
            .ok()
            .map(|pr| (p, pr))
        })
        .collect();
    // Far to near, so a nearer player's marks cover a farther one's.
    seen.sort_by(|a, b| b.1.depth.total_cmp(&a.1.depth));
    let mut tags = Vec::new();
    for (p, pr) in seen {
        let in_front = |x: i64| {
            x >= 0
                && (x as usize) < w
                && cast
                    .columns
                    .get(x as usize)
                    .is_none_or(|c| c.perp_dist > pr.depth)
        };
        if !(pr.cols.0..pr.cols.1).any(|x| in_front(x as i64)) {
            continue;
        }
        let centre = ((pr.left + pr.right) / 2.0).floor() as i64;
        let k = ((pr.right - pr.left) / 10.0).clamp(1.0, 4.0) as i64;
        let base = pr.top.floor() as i64 - 1;
        for i in 0..=k {
            let y = base - k + i;
            if y < 0 || y as usize >= h {
                continue;
            }
            for x in (centre - (k - i))..=(centre + (k - i)) {
                if in_front(x) {
                    fb.set(x as usize, y as usize, p.color);
                }
            }
        }
        if pr.depth > TAG_DISTANCE {
            continue;
        }
        // The tag is in cells: a cell is `cw` × `ch` pixels at the view's glyph setting.
        let (cw, ch) = fb.glyphs().cell_size();
        let (cols, rows) = (fb.cell_cols() as i64, fb.cell_rows() as i64);
        let row = ((base - k - 1).div_euclid(ch as i64) - 1).clamp(0, rows - 1);
        // Tag: whoever is "it" says so over their head.
        let label = if snap.it == Some(p.id) {
            format!("{} (it)", p.name)
        } else {
            p.name.clone()
        };
        let name: String = label.chars().take(cols as usize).collect();
        let n = name.chars().count() as i64;
        let col = (centre.div_euclid(cw as i64) - n / 2).clamp(0, cols - n);
        tags.push(Tag {
            col: col as u16,
            row: row as u16,
            name,
            color: p.color,
        });
    }
    tags
}

/// Writes `tags` in the screen buffer over the view whose area is `view` (bold, in the player's
/// colour on a dark backing), on the view's own cells only (those still
/// [`VIEW_CELL`](crate::widget::half_block::VIEW_CELL), as the screen is drawn for the
/// presenter): an overlay drawn over the view (the help, a message) stays on top. The presenter sends such cells after the view's own bytes.
pub fn draw_tags(buf: &mut Buffer, view: Rect, tags: &[Tag]) {
    for t in tags {
        let style = Style::new()
            .fg(Color::Rgb(t.color.r, t.color.g, t.color.b))
            .bg(Color::Rgb(TAG_BG.r, TAG_BG.g, TAG_BG.b))
            .add_modifier(Modifier::BOLD);
        let y = view.y + t.row;
        for (k, ch) in t.name.chars().enumerate() {
            let x = view.x + t.col + k as u16;
            if !view.contains(ratatui::layout::Position::new(x, y)) {
                break;
            }
            let cell = &mut buf[(x, y)];
            if is_view_cell(cell) {
                cell.set_char(ch).set_style(style);
            }
        }
    }
}

/// Sets `world`'s sprites to its first `base` ones (the map's) plus every player but `eye`.
pub fn place(world: &mut World, base: usize, sheet: usize, snap: &Snapshot, eye: PlayerId) {
    world.sprites.truncate(base);
    world.sprites.extend(
        snap.players
            .iter()
            .filter(|p| p.id != eye)
            .map(|p| avatar(&p.state, p.walking, sheet)),
    );
}

/// Writes every other player's name at its place on the minimap drawn in `inner` (the pane
/// inside its border), with the same map placement the minimap widget uses.
pub fn label_minimap(
    buf: &mut Buffer,
    inner: Rect,
    eye: &GameState,
    cast: &Cast,
    snap: &Snapshot,
    eye_id: PlayerId,
) {
    let inner = inner.intersection(buf.area);
    if inner.is_empty() {
        return;
    }
    let canvas = (usize::from(inner.width), usize::from(inner.height) * 2);
    let pos = eye.camera.pos;
    let map = &eye.world.map;
    let focus = match (&cast.trace, eye.debugger.paused) {
        (Some(t), true) => Some(pos + t.ray_dir * t.hit.perp_dist),
        _ => None,
    };
    let view = MapView::for_pane((map.width, map.height), canvas, pos, focus);
    for p in snap.players.iter().filter(|p| p.id != eye_id) {
        let (px, py) = view.to_px(p.state.camera.pos);
        if !(px >= 0.0 && py >= 0.0 && px < canvas.0 as f64 && py < canvas.1 as f64) {
            continue;
        }
        let x = inner.x + px as u16;
        let y = inner.y + (py / 2.0) as u16;
        let colour = Color::Rgb(p.color.r, p.color.g, p.color.b);
        if let Some(cell) = buf.cell_mut((x, y)) {
            cell.set_symbol("●").set_fg(colour);
        }
        let room = usize::from(inner.right().saturating_sub(x + 1));
        let style = Style::new()
            .fg(colour)
            .bg(Color::Rgb(14, 14, 18))
            .add_modifier(Modifier::BOLD);
        crate::widget::text::put_str(buf, x + 1, y, &p.name, room, style);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::multi::players::Players;
    use std::sync::Arc;

    #[test]
    fn the_default_world_already_has_the_sheet_and_other_maps_get_it() {
        let world = World::default_world();
        let n = world.sheets.len();
        let (w, i) = with_avatar_sheet(world);
        assert_eq!(w.sheets.len(), n);
        let mut bare = w.clone();
        bare.sheets.clear();
        let (w2, j) = with_avatar_sheet(bare);
        assert_eq!((w2.sheets.len(), j), (1, 0));
        assert_eq!(w.sheets[i], w2.sheets[j]);
    }

    #[test]
    fn everyone_but_the_eye_becomes_a_sprite_facing_their_way() {
        let (world, sheet) = with_avatar_sheet(World::default_world());
        let base = world.sprites.len();
        let mut ps = Players::new(Arc::new(world.clone()));
        for (id, n) in [(1, "ann"), (2, "bob"), (3, "cat")] {
            ps.join(id, n);
        }
        let snap = ps.snapshot();
        let mut w = world;
        place(&mut w, base, sheet, &snap, 2);
        assert_eq!(w.sprites.len(), base + 2);
        let ann = &snap.player(1).expect("ann").state;
        let s = &w.sprites[base].def;
        assert_eq!(s.pos, ann.camera.pos);
        assert!((s.facing_deg - ann.camera.angle_deg()).abs() < 1e-9);
        assert_eq!((s.views, s.frames, s.fps), (8, 4, 0.0));
        // Placing again replaces rather than piles up.
        place(&mut w, base, sheet, &snap, 1);
        assert_eq!(w.sprites.len(), base + 2);
        assert!(avatar(ann, true, sheet).def.fps > 0.0);
    }

    #[test]
    fn the_marker_stands_over_a_player_on_a_raised_floor() {
        use crate::camera::Camera;
        use crate::vec2::Vec2;
        // A tall corridor east; cells 4-5 are a platform one wall high.
        let text = "NO textures/bricks.png\nSO textures/bricks.png\nWE textures/stone.png\n\
                    EA textures/stone.png\nF 96,88,80\nC 150,146,136\nHb 0 3\nHa 1 3\n\
                    11111111\n1Ebbaab1\n11111111\n";
        let map = crate::map::parse_map("h.cub", text.as_bytes()).unwrap();
        let source = crate::world::TextureSource::Embedded;
        let world = Arc::new(World::load(map, &source, true).unwrap().0);
        let at = |x: f64, angle: f64| {
            let cam = Camera::from_angle(Vec2::new(x, 1.5), angle, 66.0);
            GameState::new(Arc::clone(&world), cam, 0)
        };
        let eye = at(1.5, 0.0);
        let other = at(5.5, 180.0);
        assert_eq!(other.footing.floor, 1.0);
        let colour = Rgb::new(250, 40, 200);
        let snap = Snapshot {
            version: 1,
            doors: crate::world::door::DoorState::none(),
            players: vec![crate::game::multi::players::PlayerView {
                id: 7,
                name: "ada".into(),
                color: colour,
                state: other.clone(),
                walking: false,
            }],
            ..Snapshot::default()
        };
        let (w, h) = (80, 96);
        let mut fb = Framebuffer::new(w, h);
        let cast = crate::render::scene::Scene::new(&world, eye.camera)
            .with_view(eye.view)
            .render_into(&mut fb, None);
        mark_players(&mut fb, &eye, &cast, &snap, 1);
        // The marker sits just over the avatar's head, which is one wall up on the platform.
        let scale = (AVATAR_SCALE, AVATAR_SCALE);
        let pos = other.camera.pos;
        let pr = crate::render::sprite_projection::project(
            &eye.camera,
            &eye.view,
            pos,
            scale,
            1.0,
            w,
            h,
        )
        .unwrap();
        let centre = ((pr.left + pr.right) / 2.0).floor() as usize;
        let base = pr.top.floor() as usize - 1;
        assert_eq!(fb.get(centre, base), colour);
    }
}
