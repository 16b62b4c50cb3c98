//! The textures compiled into the binary, so it runs with no files beside it.

use super::sheet::SpriteSheet;
use super::Texture;
use crate::map::ColourKey;

/// The generated PNGs from `textures/`, by file stem.
pub const EMBEDDED: [(&str, &[u8]); 8] = [
    ("bricks", include_bytes!("../../textures/bricks.png")),
    ("stone", include_bytes!("../../textures/stone.png")),
    ("wood", include_bytes!("../../textures/wood.png")),
    ("metal", include_bytes!("../../textures/metal.png")),
    ("mossy", include_bytes!("../../textures/mossy.png")),
    ("floor", include_bytes!("../../textures/floor.png")),
    ("ceiling", include_bytes!("../../textures/ceiling.png")),
    ("door", include_bytes!("../../textures/door.png")),
];

/// The generated sprite sheets (RGBA) from `textures/sprites/`, by file stem.
pub const EMBEDDED_SPRITES: [(&str, &[u8]); 9] = [
    (
        "barrel",
        include_bytes!("../../textures/sprites/barrel.png"),
    ),
    (
        "pillar",
        include_bytes!("../../textures/sprites/pillar.png"),
    ),
    ("lamp", include_bytes!("../../textures/sprites/lamp.png")),
    ("plant", include_bytes!("../../textures/sprites/plant.png")),
    (
        "creature",
        include_bytes!("../../textures/sprites/creature.png"),
    ),
    (
        "treasure",
        include_bytes!("../../textures/sprites/treasure.png"),
    ),
    ("key", include_bytes!("../../textures/sprites/key.png")),
    ("exit", include_bytes!("../../textures/sprites/exit.png")),
    ("orb", include_bytes!("../../textures/sprites/orb.png")),
];

/// Decodes the embedded sprite sheet named `stem` (e.g. "barrel"), if there is one.
#[must_use]
pub fn sheet_by_name(stem: &str) -> Option<SpriteSheet> {
    EMBEDDED_SPRITES
        .iter()
        .find(|(name, _)| *name == stem)
        .map(|(_, bytes)| {
            SpriteSheet::decode(bytes, ColourKey::Auto).expect("embedded sprites are valid PNGs")
        })
}

/// Decodes the embedded texture named `stem` (e.g. "bricks"), if there is one.
#[must_use]
pub fn by_name(stem: &str) -> Option<Texture> {
    EMBEDDED
        .iter()
        .find(|(name, _)| *name == stem)
        .map(|(_, bytes)| Texture::decode(bytes).expect("embedded textures are valid PNGs"))
}

/// The stand-in used for a wall whose texture is missing, chosen so faces stay distinct.
#[must_use]
pub fn fallback_stem(slot: usize) -> &'static str {
    const ORDER: [&str; 5] = ["bricks", "stone", "wood", "metal", "mossy"];
    ORDER[slot % ORDER.len()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::generate;

    #[test]
    fn embedded_pngs_match_the_generator() {
        for (name, f) in generate::ALL {
            assert_eq!(
                by_name(name).as_ref(),
                Some(&f()),
                "textures/{name}.png is stale: run `cargo run --example gen-textures`"
            );
        }
    }

    #[test]
    fn embedded_sprite_pngs_match_the_generator() {
        for (name, f) in crate::texture::sprite_art::ALL {
            assert_eq!(
                sheet_by_name(name).as_ref(),
                Some(&f()),
                "textures/sprites/{name}.png is stale: run `cargo run --example gen-textures`"
            );
        }
    }
}
