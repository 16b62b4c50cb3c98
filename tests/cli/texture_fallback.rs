//! Issue 56: a map copied without its image files still looks like itself: each missing file
//! falls back to the built-in of its name (`stone.png` → stone, `treasure.png` → the treasure
//! sprite, in any case), by its slot only when no built-in has that name, and the warning says
//! which: `…, which has its name` when the name chose it, the slot's words as before when not.

use halfcast::map::parse_map;
use halfcast::world::TextureSource;
use halfcast::{Camera, Framebuffer, Scene, World};

use crate::common::halfcast;

/// A room whose every image file is missing: walls, floor, ceiling and sprites named after
/// built-ins (paths and case as a map might write them), one wall and one sprite named after none.
const MAP: &str = "NO ./walls/stone.png\n\
SO ./walls/Wood.PNG\n\
WE ./north.png\n\
EA mossy.png\n\
FT ./floor.png\n\
CT art/ceiling.png\n\
SPRITE 2.5,2.5 ./sprites/treasure.png\n\
SPRITE 3.5,2.5 ./sprites/lamp.png scale=0.5\n\
SPRITE 4.5,2.5 plant.png\n\
SPRITE 2.5,1.5 ./gone/KEY.png\n\
SPRITE 4.5,1.5 ./gone/statue.png\n\
\n\
1111111\n\
1000001\n\
1000001\n\
1000001\n\
10N0001\n\
1111111\n";

/// (line, path, how the warning ends) for each missing file, in map order.
const WARNINGS: &[(usize, &str, &str)] = &[
    (
        1,
        "./walls/stone.png",
        "using the built-in 'stone' texture, which has its name",
    ),
    (
        2,
        "./walls/Wood.PNG",
        "using the built-in 'wood' texture, which has its name",
    ),
    (3, "./north.png", "using the built-in 'wood' texture"),
    (
        4,
        "mossy.png",
        "using the built-in 'mossy' texture, which has its name",
    ),
    (
        5,
        "./floor.png",
        "using the built-in 'floor' texture, which has its name",
    ),
    (
        6,
        "art/ceiling.png",
        "using the built-in 'ceiling' texture, which has its name",
    ),
    (
        7,
        "./sprites/treasure.png",
        "using the built-in 'treasure' sprite, which has its name",
    ),
    (
        8,
        "./sprites/lamp.png",
        "using the built-in 'lamp' sprite, which has its name",
    ),
    (
        9,
        "plant.png",
        "using the built-in 'plant' sprite, which has its name",
    ),
    (
        10,
        "./gone/KEY.png",
        "using the built-in 'key' sprite, which has its name",
    ),
    (
        11,
        "./gone/statue.png",
        "using the built-in 'barrel' sprite",
    ),
];

#[test]
fn missing_files_fall_back_by_name_and_say_which() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("copied.cub");
    std::fs::write(&path, MAP).unwrap();
    let map = path.to_str().unwrap();
    let png = dir.path().join("view.png");
    let out = halfcast(&[
        "render",
        map,
        "--angle",
        "60",
        "--size",
        "64x20",
        "--format",
        "png",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0));
    let stderr = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), WARNINGS.len(), "{stderr}");
    for (line, (n, file, tail)) in lines.iter().zip(WARNINGS) {
        assert!(line.starts_with(&format!("warning: {map}:{n}:")), "{line}");
        assert!(
            line.contains(&format!(": cannot load texture '{file}': ")),
            "{line}"
        );
        assert!(line.ends_with(&format!("; {tail}")), "{line}");
    }
    // The picture is the same map drawn from the built-ins of those names: what the embedded
    // textures give a map held in a string (stems name built-ins there), where only `north`
    // and `statue` need a slot's stand-in too.
    let parsed = parse_map("copied.cub", MAP.as_bytes()).unwrap();
    let (world, _) = World::load(parsed, &TextureSource::Embedded, false).unwrap();
    let start = world.map.start;
    let scene = Scene::new(&world, Camera::from_angle(start.pos(), 60.0, 66.0));
    let drawn = Framebuffer::from_image_bytes(&std::fs::read(&png).unwrap()).unwrap();
    assert_eq!(drawn, scene.render(64, 20));
}

#[test]
fn a_name_that_is_no_builtin_falls_back_by_slot_as_before() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("plain.cub");
    std::fs::write(
        &path,
        "NO a.png\nSO b.png\nWE c.png\nEA d.png\nF 1,2,3\nC 4,5,6\n\n111\n1N1\n111\n",
    )
    .unwrap();
    let out = halfcast(&[
        "render",
        path.to_str().unwrap(),
        "--size",
        "8x4",
        "--format",
        "txt",
    ]);
    assert_eq!(out.status.code(), Some(0));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 4, "{stderr}");
    for (line, (stem, builtin)) in stderr.lines().zip([
        ("a", "bricks"),
        ("b", "stone"),
        ("c", "wood"),
        ("d", "metal"),
    ]) {
        assert!(
            line.contains(&format!(": cannot load texture '{stem}.png': "))
                && line.ends_with(&format!("; using the built-in '{builtin}' texture")),
            "{line}"
        );
    }
}
