//! Other players as the world's own sprites: the 8-view walking creature, facing where its
//! player looks and animated while it walks, drawn by the world's sprite renderer; and their
//! names on the minimap.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};

use super::players::{PlayerId, Snapshot};
use crate::cast::Cast;
use crate::game::GameState;
use crate::map::{Blend, ColourKey, SpriteDef, TextureRef};
use crate::sprite::Sprite;
use crate::texture::builtin;
use crate::widget::minimap::MapView;
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
        buf.set_stringn(x + 1, y, &p.name, room, style);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::serve::players::Players;
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
}
