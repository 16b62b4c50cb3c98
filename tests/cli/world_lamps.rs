//! `LIGHT` lamps at night: they brighten what they can see, never darken, cast shadows behind
//! walls, and change nothing by day. Golden: `tests/images/world/night_lamp.png`.

use crate::world_common;

use halfcast::camera::Camera;
use halfcast::map::Cell;
use halfcast::render::cast::{ColumnHit, Side};
use halfcast::render::light::Lighting;
use halfcast::{Framebuffer, Scene, Vec2, World};
use world_common::{golden, world, ROOM};

const COLS: u16 = 96;
const ROWS: u16 = 32;

fn night() -> Lighting {
    Lighting {
        night: true,
        ..Lighting::default()
    }
}

fn view(w: &World, light: Lighting) -> (Framebuffer, Vec<ColumnHit>) {
    let cam = Camera::from_angle(Vec2::new(1.5, 3.5), 0.0, 66.0);
    let mut fb = Framebuffer::for_cells(COLS, ROWS);
    let cast = Scene::new(w, cam)
        .with_light(light)
        .render_into(&mut fb, None);
    (fb, cast.columns)
}

fn luma_sum(fb: &Framebuffer) -> u64 {
    (0..fb.height())
        .flat_map(|y| fb.row(y).iter())
        .map(|p| u64::from(p.luma()))
        .sum()
}

#[test]
fn a_lamp_lights_the_dark_around_it_and_never_darkens() {
    let dark = world("", ROOM);
    let lit = world("LIGHT 5.5,1.5 3 1\n", ROOM);
    let (without, _) = view(&dark, night());
    let (with, _) = view(&lit, night());
    golden(&with, "night_lamp");
    let mut brighter = 0;
    for y in 0..with.height() {
        for x in 0..with.width() {
            let (a, b) = (without.get(x, y).luma(), with.get(x, y).luma());
            assert!(b + 1 >= a, "pixel ({x}, {y}) darkened: {a} -> {b}");
            brighter += usize::from(b > a + 8);
        }
    }
    assert!(
        brighter > with.width() * with.height() / 20,
        "only {brighter} pixels lit"
    );
    assert!(luma_sum(&with) > luma_sum(&without) * 11 / 10);
}

#[test]
fn walls_shade_the_lamp_from_their_far_side() {
    // The lamp stands east of the block at (6, 3); the block's west face, which the player
    // sees, is in its shadow and looks exactly as without the lamp.
    let dark = world("", ROOM);
    let lit = world("LIGHT 8.0,3.5 3 1\n", ROOM);
    let (without, hits) = view(&dark, night());
    let (with, _) = view(&lit, night());
    let shadowed: Vec<usize> = hits
        .iter()
        .enumerate()
        .filter(|(_, h)| h.cell == (6, 3) && h.side == Side::X && h.what == Cell::Wall(1))
        .map(|(x, _)| x)
        .collect();
    assert!(!shadowed.is_empty());
    for &x in &shadowed {
        // Wall rows only: the floor in front of the block is out of the lamp's reach anyway.
        let y = usize::from(ROWS);
        assert_eq!(with.get(x, y), without.get(x, y), "column {x}");
    }
}

#[test]
fn by_day_lamps_change_nothing() {
    let dark = world("", ROOM);
    let lit = world("LIGHT 5.5,1.5 3 1\n", ROOM);
    let (a, _) = view(&dark, Lighting::default());
    let (b, _) = view(&lit, Lighting::default());
    assert!(a == b, "daylight frames differ");
}
