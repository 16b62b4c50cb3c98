//! The world's sprites as loaded: each map sprite line with the sheet it draws from. Where one
//! lands on screen is the renderer's (`render::sprite_projection`).

use crate::map::SpriteDef;

/// A sprite of the loaded world: its map description and the sheet it draws from.
#[derive(Debug, Clone, PartialEq)]
pub struct Sprite {
    /// Position, size and drawing options as the map gave them.
    pub def: SpriteDef,
    /// Index into [`crate::World::sheets`].
    pub sheet: usize,
}
