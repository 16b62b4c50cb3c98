//! Golden frames of `maps/heights.cub` (issue 14): stairs from below and above, the pit, the
//! balcony seen from under it, the window, a sprite behind a low step, night with a lamp on the
//! balcony; and sprites hidden by nearer floors. Update after an intended change:
//! `HALFCAST_UPDATE_GOLDEN=1 cargo test --test heights_golden` (and look at every image).

use std::path::{Path, PathBuf};

use halfcast::camera::Camera;
use halfcast::snapshot::{assert_png_golden, Tolerance};
use halfcast::world::door::DoorState;
use halfcast::world::{TextureSource, World};
use halfcast::{Framebuffer, Scene, Vec2, View};

const COLS: u16 = 96;
const ROWS: u16 = 32;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn heights_world() -> World {
    let (w, warnings) = World::from_file(&root().join("maps/heights.cub"), true).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    w
}

/// The frame `render maps/heights.cub --pos X,Y --angle A --pitch P [--night]` shows: standing
/// (eye 0.5) on the floor of the camera's cell.
fn frame(world: &World, pos: (f64, f64), angle: f64, pitch: f64, night: bool) -> Framebuffer {
    let p = Vec2::new(pos.0, pos.1);
    let ground = world
        .map
        .span(p.x.floor() as i64, p.y.floor() as i64)
        .unwrap()
        .floor;
    let mut scene = Scene::new(world, Camera::from_angle(p, angle, 66.0))
        .with_view(View::new(pitch, 0.5).on_ground(ground));
    scene.light.night = night;
    scene.render(COLS, ROWS)
}

fn golden(fb: &Framebuffer, name: &str) {
    let path: PathBuf = root()
        .join("tests/images/heights")
        .join(format!("{name}.png"));
    assert_png_golden(fb, path, Tolerance::default());
}

#[test]
fn stairs_from_below() {
    golden(
        &frame(&heights_world(), (2.0, 8.6), 90.0, 8.0, false),
        "stairs_from_below",
    );
}

#[test]
fn stairs_from_the_balcony_above() {
    golden(
        &frame(&heights_world(), (2.0, 1.6), 270.0, -25.0, false),
        "stairs_from_above",
    );
}

#[test]
fn pit_with_its_ledge_and_a_barrel_on_the_bottom() {
    golden(
        &frame(&heights_world(), (15.5, 5.0), 0.0, -35.0, false),
        "pit",
    );
}

#[test]
fn balcony_seen_from_under_it() {
    golden(
        &frame(&heights_world(), (3.5, 4.6), 90.0, 25.0, false),
        "balcony_from_below",
    );
}

#[test]
fn window_between_two_rooms() {
    let w = heights_world();
    let start = w.map.start;
    golden(
        &frame(&w, (13.5, 5.5), start.angle_deg(), 0.0, false),
        "window",
    );
}

#[test]
fn sprite_behind_a_low_step() {
    golden(
        &frame(&heights_world(), (14.0, 5.5), 270.0, 0.0, false),
        "sprite_behind_low_step",
    );
}

#[test]
fn night_with_a_lamp_on_the_balcony() {
    golden(
        &frame(&heights_world(), (5.6, 2.4), 160.0, -10.0, true),
        "night_lamp_on_balcony",
    );
}

/// A small map with a deep pit (floor −2) two cells wide, a barrel of `scale` on its bottom.
fn pit_world(sprite_x: f64, scale: &str) -> World {
    let text = format!(
        "NO textures/bricks.png\nSO textures/bricks.png\nWE textures/stone.png\nEA textures/stone.png\nF 96,88,80\nC 150,146,136\nHp -2 1\nFp 40,40,90\nWp 200,60,60\nSPRITE {sprite_x},2.5 textures/sprites/barrel.png scale={scale}\n1111111111\n1000pp0001\n1E00pp0001\n1000pp0001\n1111111111\n"
    );
    let map = halfcast::map::parse_map("pit.cub", text.as_bytes()).unwrap();
    World::load(map, &TextureSource::Embedded, true).unwrap().0
}

fn pit_frame(world: &World, doors: Option<&DoorState>) -> (Framebuffer, bool) {
    let mut scene = Scene::new(world, Camera::from_angle(Vec2::new(1.5, 2.5), 0.0, 66.0));
    if let Some(d) = doors {
        scene = scene.with_doors(d);
    }
    let mut fb = Framebuffer::for_cells(COLS, ROWS);
    let frame = scene.render_frame(&mut fb, None);
    (fb, frame.sprites[0].drawn)
}

#[test]
fn a_sprite_deep_in_a_pit_does_not_shine_through_the_floor_in_front() {
    // The barrel (height 1) stands on the pit's bottom at −2: from eye height 0.5 three cells
    // back, the rim's floor hides all of it. Drawn at floor 0 it would be in full view.
    let hidden = pit_world(4.9, "1");
    let (fb, drawn) = pit_frame(&hidden, None);
    let (without, _) = pit_frame(&pit_world(1.2, "1"), None);
    assert!(!drawn, "the barrel in the pit was drawn");
    assert_eq!(fb, without);
}

#[test]
fn a_sprite_near_the_far_side_of_a_pit_shows_only_above_the_rim_line() {
    // A barrel three units tall against the far wall rises into view over the near rim; every
    // pixel it covers is above the rows where the near rim's floor is drawn.
    let w = pit_world(5.8, "1,3");
    let (fb, drawn) = pit_frame(&w, None);
    let (without, _) = pit_frame(&pit_world(1.2, "1"), None);
    assert!(drawn);
    let changed: Vec<(usize, usize)> = (0..fb.width())
        .flat_map(|x| (0..fb.height()).map(move |y| (x, y)))
        .filter(|&(x, y)| fb.get(x, y) != without.get(x, y))
        .collect();
    assert!(!changed.is_empty());
    // The near rim's edge (x = 4, floor 0) at distance 2.5 from eye 0.5: rows at or below
    // horizon + 0.5·focal/2.5 see the rim (or nearer) floor.
    let focal = f64::from(COLS) / (2.0 * (33f64).to_radians().tan());
    let rim_row = f64::from(ROWS) + 0.5 * focal / 2.5;
    for (x, y) in changed {
        assert!(
            (y as f64) < rim_row,
            "barrel pixel ({x},{y}) below the rim line {rim_row}"
        );
    }
}

#[test]
fn doors_on_height_maps_span_their_cell_and_open() {
    // A door between a raised room (floor 0.3) and the start room.
    let text = "NO textures/bricks.png\nSO textures/bricks.png\nWE textures/stone.png\nEA textures/stone.png\nF 96,88,80\nC 150,146,136\nHr 0.3 1.5\nFr 60,120,60\n11111111\n1E0D0rr1\n11111111\n";
    let map = halfcast::map::parse_map("door.cub", text.as_bytes()).unwrap();
    let w = World::load(map, &TextureSource::Embedded, true).unwrap().0;
    let cam = Camera::from_angle(Vec2::new(1.5, 1.5), 0.0, 66.0);
    let mut shut_fb = Framebuffer::for_cells(COLS, ROWS);
    let shut = Scene::new(&w, cam).render_frame(&mut shut_fb, Some(48));
    let col = &shut.cast.heights[48];
    let door = col.faces().next().unwrap();
    assert_eq!(door.cell, (3, 1));
    assert_eq!(door.z, (0.0, 1.0));
    assert_eq!(shut.cast.columns[48].cell, (3, 1));
    let mut doors = DoorState::new(&w.map);
    doors.set_open((3, 1), 1.0);
    let mut open_fb = Framebuffer::for_cells(COLS, ROWS);
    let open = Scene::new(&w, cam)
        .with_doors(&doors)
        .render_frame(&mut open_fb, Some(48));
    let kinds: Vec<_> = open.cast.heights[48]
        .faces()
        .map(|f| (f.kind.as_str(), f.cell))
        .collect();
    // Open: the raised room's step (the first zone cell) and its lintel-free far wall.
    assert_eq!(kinds.first(), Some(&("step", (5, 1))), "{kinds:?}");
    assert_ne!(shut_fb, open_fb);
}
