//! Pinning a frame of your own map in a test: the colour-aware text form (for insta) and a
//! golden PNG. Run as a program it prints the text form; `cargo test --example snapshot` runs
//! the two tests below (`INSTA_UPDATE=always` writes the golden the first time).

use halfcast::world::TextureSource;
use halfcast::{Camera, Scene, Vec2, World};

/// A small room with a pillar, in the cub3D `.cub` format (texture paths name halfcast's
/// embedded textures by file stem).
const MAP: &str = "\
F 90,80,70
C 40,50,70
NO textures/bricks.png
SO textures/bricks.png
WE textures/stone.png
EA textures/wood.png

111111
100001
10N101
100001
111111
";

/// The world of [`MAP`].
fn world() -> World {
    let map = halfcast::map::parse_map("room.cub", MAP.as_bytes()).expect("the map is valid");
    let (world, warnings) =
        World::load(map, &TextureSource::Embedded, true).expect("embedded textures load");
    assert!(warnings.is_empty(), "{warnings:?}");
    world
}

/// The frame being pinned: from the start, looking a little right of north.
fn scene(world: &World) -> Scene<'_> {
    Scene::new(world, Camera::from_angle(Vec2::new(2.5, 2.5), 80.0, 66.0))
}

fn main() {
    let world = world();
    print!("{}", scene(&world).to_cells_text(16, 6));
}

#[cfg(test)]
mod tests {
    use super::*;
    use halfcast::snapshot::{assert_png_golden, Tolerance};

    #[test]
    fn the_room_as_text() {
        let world = world();
        insta::assert_snapshot!(scene(&world).to_cells_text(16, 6));
    }

    #[test]
    fn the_room_as_a_golden_png() {
        let world = world();
        let golden = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/snapshots/room.png");
        assert_png_golden(&scene(&world).render(64, 24), golden, Tolerance::default());
    }
}
