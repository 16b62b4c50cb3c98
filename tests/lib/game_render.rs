//! The game's sprites on screen: an item is drawn through `Scene::with_sprites` until it is
//! picked up, and a locked door's panel shows its key's colour.

use crate::world_common;

use halfcast::game::{Level, Player, Score};
use halfcast::world::door::DoorState;
use halfcast::{Camera, Scene, Vec2};
use world_common::world;

const GRID: &str = "11111111\n1E000001\n11111111\n";

#[test]
fn an_item_is_drawn_until_it_is_picked_up() {
    let w = world("ITEM 4.5,1.5 barrel scale=0.6\n", GRID);
    let cam = Camera::from_angle(Vec2::new(1.5, 1.5), 0.0, 66.0);
    let mut level = Level::new(&w.map, 0);
    let bare = Scene::new(&w, cam).render(40, 12);
    let sprites = level.sprites(&w);
    assert_eq!(sprites.len(), 1);
    let with_item = Scene::new(&w, cam).with_sprites(&sprites).render(40, 12);
    // The barrel stands on the floor in the middle of the view: the centre column's lower
    // half changes where it is, the ceiling above it does not.
    let changed: Vec<usize> = (0..24)
        .filter(|&y| with_item.get(20, y) != bare.get(20, y))
        .collect();
    assert!(!changed.is_empty(), "the item was not drawn");
    assert!(
        changed.iter().all(|&y| y >= 10),
        "drawn off the floor: rows {changed:?}"
    );
    let mut score = Score::default();
    let doors = DoorState::new(&w.map);
    let mut players = [Player {
        pos: Vec2::new(4.4, 1.5),
        eye: 0.5,
        score: &mut score,
    }];
    level.tick(&w.map, &doors, &mut players, 0.1);
    let after = level.sprites(&w);
    assert!(after.is_empty());
    assert_eq!(
        Scene::new(&w, cam).with_sprites(&after).render(40, 12),
        bare
    );
}

#[test]
fn a_locked_door_and_its_key_share_the_keys_colour() {
    let grid = "1111111\n1E0D001\n1011111\n1111111\n";
    let plain = world("ITEM 1.5,2.5 lamp key=red\n", grid);
    let locked = world("ITEM 1.5,2.5 lamp key=red\nDOORLOCK 3,1 red\n", grid);
    let cam = Camera::from_angle(Vec2::new(1.5, 1.5), 0.0, 66.0);
    let a = Scene::new(&plain, cam).render(30, 10);
    let b = Scene::new(&locked, cam).render(30, 10);
    let (pa, pb) = (a.get(15, 10), b.get(15, 10));
    assert_ne!(pa, pb, "the locked door's panel is not tinted");
    assert!(pb.r > pb.g && pb.r > pb.b, "not red: {pb:?}");
    // The key's sheet is tinted too: its mean colour is red.
    let level = Level::new(&locked.map, 0);
    let key = &level.sprites(&locked)[0];
    let mean = locked.sheets[key.sheet].mean();
    assert!(mean.r > mean.g && mean.r > mean.b, "{mean:?}");
}

#[test]
fn item_and_creature_textures_load_from_disk_and_a_missing_one_is_placed() {
    use halfcast::world::World;
    let grid = "1111111\n1E00001\n1111111\n";
    let extra = "ITEM 2.5,1.5 textures/sprites/barrel.png\nCREATURE 4.5,1.5 missing.png\n";
    let (_dir, path) = world_common::map_file(extra, grid);
    let (w, warnings) = World::from_file(&path, false).unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(
        warnings[0].contains(":10:18: cannot load texture 'missing.png'"),
        "{warnings:?}"
    );
    assert!(
        warnings[0].ends_with("using the built-in 'creature' sprite"),
        "{warnings:?}"
    );
    assert_eq!((w.item_sheets.len(), w.creature_sheets.len()), (1, 1));
    let err = World::from_file(&path, true).unwrap_err().to_string();
    assert!(
        err.ends_with(
            ":10:18: cannot load texture 'missing.png': No such file or directory (os error 2)"
        ),
        "{err}"
    );
}
