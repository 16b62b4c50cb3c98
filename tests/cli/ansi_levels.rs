//! Issue 56: `Scene::to_ansi_level` gives, at every colour level, the very bytes `halfcast render
//! --format ansi --colors LEVEL` writes for the same scene (the recipe docs/library.md gives: the
//! level's items and creatures, and on maps with heights the eye on its cell's floor).

use halfcast::game::Level;
use halfcast::{Camera, ColorLevel, Scene, View, World};

use crate::common::{halfcast_ok, root};

/// The scene the command line draws for `world` from `camera` (no flags but the pose).
fn check(map: Option<&str>, pose: Option<(f64, f64, f64)>, (cols, rows): (u16, u16)) {
    let world = match map {
        None => World::default_world(),
        Some(path) => World::from_file(&root().join(path), true).unwrap().0,
    };
    let start = world.map.start;
    let (x, y, angle) = pose.unwrap_or((start.pos().x, start.pos().y, start.angle_deg()));
    let camera = Camera::from_angle(halfcast::Vec2::new(x, y), angle, 66.0);
    let sprites = Level::new(&world.map, 0).sprites(&world);
    let ground = world.map.floor_height(x.floor() as i64, y.floor() as i64);
    let scene = Scene::new(&world, camera)
        .with_view(View::default().on_ground(ground))
        .with_sprites(&sprites);
    for level in ColorLevel::ALL {
        let size = format!("{cols}x{rows}");
        let (pos, angle) = (format!("{x},{y}"), angle.to_string());
        let mut args = vec!["render"];
        args.extend(map);
        args.extend([
            "--size",
            &size,
            "--format",
            "ansi",
            "--colors",
            level.name(),
        ]);
        if pose.is_some() {
            args.extend(["--pos", &pos, "--angle", &angle]);
        }
        let out = halfcast_ok(&args);
        let ours = scene.to_ansi_level(cols, rows, level);
        assert!(
            out.stdout == ours.as_bytes(),
            "{args:?}: the library's {} bytes differ from the command line's {}",
            ours.len(),
            out.stdout.len()
        );
    }
}

#[test]
fn the_library_writes_the_command_lines_bytes_at_every_level() {
    check(None, None, (80, 24));
    check(None, Some((15.3, 5.6, 62.0)), (50, 23));
    check(Some("maps/level1.cub"), None, (61, 17));
    check(Some("maps/level2.cub"), None, (40, 12));
    check(Some("maps/heights.cub"), None, (72, 20));
    check(Some("maps/heights.cub"), Some((5.6, 2.4, 200.0)), (33, 9));
}

#[test]
fn each_level_writes_only_its_own_colour_codes() {
    let world = World::default_world();
    let start = world.map.start;
    let scene = Scene::new(
        &world,
        Camera::from_angle(start.pos(), start.angle_deg(), 66.0),
    );
    let truecolor = scene.to_ansi_level(60, 20, ColorLevel::TrueColor);
    assert_eq!(truecolor, scene.to_ansi(60, 20));
    assert!(truecolor.contains("\x1b[38;2;"));
    let indexed = scene.to_ansi_level(60, 20, ColorLevel::Ansi256);
    assert!(indexed.contains("\x1b[38;5;") && !indexed.contains(";2;"));
    let sixteen = scene.to_ansi_level(60, 20, ColorLevel::Ansi16);
    assert!(!sixteen.contains("38;5;") && !sixteen.contains("38;2;") && sixteen.contains('▀'));
    let mono = scene.to_ansi_level(60, 20, ColorLevel::Mono);
    assert!(!mono.contains('\x1b') && mono.is_ascii());
    assert_eq!(mono.lines().count(), 20);
    assert!(mono.lines().all(|l| l.len() == 60));
}
