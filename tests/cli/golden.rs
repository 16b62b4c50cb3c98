//! Golden frames of the embedded default map, compared with a tolerance.
//! Update after an intended change: `HALFCAST_UPDATE_GOLDEN=1 cargo test --test golden`.

use crate::common;

use halfcast::camera::Camera;
use halfcast::render::cast::cast;
use halfcast::render::wall_span;
use halfcast::snapshot::{assert_png_golden, Tolerance};
use halfcast::world::World;
use halfcast::{Scene, Vec2};

fn golden(name: &str) -> std::path::PathBuf {
    common::root()
        .join("tests/images/core")
        .join(format!("{name}.png"))
}

#[test]
fn default_view_from_the_start() {
    let world = World::default_world();
    let start = world.map.start;
    let cam = Camera::from_angle(start.pos(), start.angle_deg(), 66.0);
    let fb = Scene::new(&world, cam).render(120, 40);
    assert_eq!((fb.width(), fb.height()), (120, 80));
    assert_png_golden(&fb, golden("default_start"), Tolerance::default());
}

#[test]
fn default_view_down_the_wooden_corridor() {
    let world = World::default_world();
    let cam = Camera::from_angle(Vec2::new(14.5, 9.5), 30.0, 66.0);
    let fb = Scene::new(&world, cam).render(160, 48);
    assert_png_golden(&fb, golden("default_corridor"), Tolerance::default());
}

#[test]
fn the_png_output_is_cols_by_twice_rows() {
    let out = common::halfcast(&["render", "--size", "37x11", "--format", "png"]);
    assert_eq!(out.status.code(), Some(0));
    let fb = halfcast::Framebuffer::from_image_bytes(&out.stdout).unwrap();
    assert_eq!((fb.width(), fb.height()), (37, 22));
}

/// A wall face seen head-on spans as many pixel columns as pixel rows, whatever W:H is.
#[test]
fn walls_are_square_at_any_terminal_size() {
    let text = "NO n\nSO s\nWE w\nEA e\nF 1,1,1\nC 2,2,2\n\n1111111\n1000001\n1000001\n1000001\n1000001\n100W001\n1111111\n";
    let map = halfcast::map::parse_map("sq.cub", text.as_bytes()).unwrap();
    for (cols, rows) in [(240, 68), (120, 40), (80, 60), (60, 10)] {
        for dist in [2.5, 3.5] {
            let cam = Camera::from_angle(Vec2::new(3.5, 1.0 + dist), 90.0, 66.0);
            let hits = cast(&map, &cam, cols, None).columns;
            let face = hits.iter().filter(|h| h.cell == (3, 0)).count() as f64;
            let span = wall_span(dist, cam.focal_length(cols), rows * 2);
            assert!(
                (face - span.height).abs() <= 1.0,
                "{cols}x{rows} at {dist}: {face} columns vs {} rows",
                span.height
            );
        }
    }
}

/// `maps/default.cub` read from disk (textures relative to it) looks exactly like the embedded copy.
#[test]
fn the_default_map_file_on_disk_matches_the_embedded_one() {
    let (disk, warnings) =
        World::from_file(&common::root().join("maps/default.cub"), true).unwrap();
    assert!(warnings.is_empty());
    let embedded = World::default_world();
    let start = embedded.map.start;
    let cam = Camera::from_angle(start.pos(), start.angle_deg() + 40.0, 70.0);
    assert_eq!(
        Scene::new(&disk, cam).render(64, 20),
        Scene::new(&embedded, cam).render(64, 20)
    );
}
