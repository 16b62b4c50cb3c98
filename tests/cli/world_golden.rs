//! Golden frames of the world features: sprites, translucency, 8 views, fog, night, pitch,
//! eye height and a half-open door. Update after an intended change:
//! `HALFCAST_UPDATE_GOLDEN=1 cargo test --test world_golden` (and look at every image).

use crate::world_common;

use halfcast::camera::Camera;
use halfcast::render::light::{Fog, Lighting};
use halfcast::world::door::DoorState;
use halfcast::{Framebuffer, Rgb, Scene, Vec2, View};
use world_common::{golden, world, ROOM};

const COLS: u16 = 96;
const ROWS: u16 = 32;

fn east_from(x: f64, y: f64) -> Camera {
    Camera::from_angle(Vec2::new(x, y), 0.0, 66.0)
}

fn render(scene: &Scene) -> Framebuffer {
    scene.render(COLS, ROWS)
}

#[test]
fn sprites_in_front_of_and_behind_a_wall() {
    // A barrel in front of the wall block at (6, 3); a creature behind it, half hidden.
    let w = world(
        "SPRITE 3.5,4.2 textures/sprites/barrel.png\nSPRITE 7.5,2.6 textures/sprites/creature.png views=8 frames=4 facing=180\n",
        ROOM,
    );
    let scene = Scene::new(&w, east_from(1.5, 3.5));
    let mut fb = Framebuffer::for_cells(COLS, ROWS);
    let frame = scene.render_frame(&mut fb, None);
    golden(&fb, "sprites_front_and_behind_wall");
    let (barrel, creature) = (&frame.sprites[0], &frame.sprites[1]);
    assert!(barrel.drawn && creature.drawn);
    let p = creature.projection.unwrap();
    let hidden: Vec<usize> = (p.cols.0..p.cols.1)
        .filter(|&x| frame.cast.columns[x].perp_dist < p.depth)
        .collect();
    assert!(!hidden.is_empty() && hidden.len() < p.cols.1 - p.cols.0);
    // Where the wall is nearer, the creature leaves no trace: same pixels as without it.
    let alone = world("SPRITE 3.5,4.2 textures/sprites/barrel.png\n", ROOM);
    let without = render(&Scene::new(&alone, east_from(1.5, 3.5)));
    for &x in &hidden {
        for y in 0..fb.height() {
            assert_eq!(fb.get(x, y), without.get(x, y), "column {x} row {y}");
        }
    }
}

#[test]
fn two_overlapping_sprites_are_drawn_far_to_near_whatever_their_order() {
    let near = "SPRITE 3.5,3.4 textures/sprites/barrel.png\n";
    let far = "SPRITE 4.6,2.9 textures/sprites/creature.png views=8 frames=4 facing=180\n";
    let a = world(&format!("{near}{far}"), ROOM);
    let b = world(&format!("{far}{near}"), ROOM);
    let cam = east_from(1.5, 3.5);
    let fa = render(&Scene::new(&a, cam));
    let fb = render(&Scene::new(&b, cam));
    assert_eq!(fa, fb);
    golden(&fa, "sprites_overlapping");
}

#[test]
fn translucent_sprites_average_and_add() {
    let w = world(
        "SPRITE 4.5,2.8 textures/sprites/creature.png views=8 frames=4 facing=180 blend=average\nSPRITE 4.5,4.2 textures/sprites/lamp.png blend=additive\n",
        ROOM,
    );
    let fb = render(&Scene::new(&w, east_from(1.5, 3.5)));
    golden(&fb, "sprites_translucent");
    // The same creature opaque differs: the wall shows through the average.
    let opaque = world(
        "SPRITE 4.5,2.8 textures/sprites/creature.png views=8 frames=4 facing=180\nSPRITE 4.5,4.2 textures/sprites/lamp.png blend=additive\n",
        ROOM,
    );
    assert_ne!(fb, render(&Scene::new(&opaque, east_from(1.5, 3.5))));
}

#[test]
fn each_of_the_eight_views() {
    let mut frames = Vec::new();
    for k in 0..8 {
        // The viewer is west of the creature (seen from 180°); facing 180 − 45k shows view k.
        let facing = 180 - 45 * k;
        let w = world(
            &format!(
                "SPRITE 3.5,3.5 textures/sprites/creature.png views=8 frames=4 facing={facing}\n"
            ),
            ROOM,
        );
        let fb = render(&Scene::new(&w, east_from(1.5, 3.5)));
        golden(&fb, &format!("creature_view_{k}"));
        frames.push(fb);
    }
    for a in 0..8 {
        for b in a + 1..8 {
            assert_ne!(frames[a], frames[b], "views {a} and {b} look the same");
        }
    }
}

#[test]
fn animation_frames_come_from_scene_time() {
    let w = world(
        "SPRITE 3.5,3.5 textures/sprites/creature.png views=8 frames=4 fps=4 facing=180\n",
        ROOM,
    );
    let scene = Scene::new(&w, east_from(1.5, 3.5));
    let f0 = render(&scene.at_time(0.0));
    assert_eq!(f0, render(&scene.at_time(0.2)));
    assert_ne!(f0, render(&scene.at_time(0.3)));
    assert_eq!(f0, render(&scene.at_time(1.0)));
    golden(&render(&scene.at_time(0.3)), "creature_frame_1");
}

/// A long view down the room with sprites at several depths, for the light cases.
fn long_view() -> (halfcast::World, Camera) {
    let w = world(
        "SPRITE 3.5,2.5 textures/sprites/barrel.png\nSPRITE 8.5,4.5 textures/sprites/plant.png\nSPRITE 5.5,2.0 textures/sprites/lamp.png scale=0.5 hang\n",
        "1111111111111111\n1000000000000001\n1000000000000001\n1E00000000000001\n1000000000000001\n1111111111111111\n",
    );
    (w, Camera::from_angle(Vec2::new(1.5, 3.5), -8.0, 66.0))
}

#[test]
fn fog_fades_to_its_colour_with_distance() {
    let (w, cam) = long_view();
    let light = Lighting {
        fog: Some(Fog {
            colour: Rgb::new(200, 205, 215),
            density: 0.25,
        }),
        ..Lighting::default()
    };
    let fb = render(&Scene::new(&w, cam).with_light(light));
    golden(&fb, "fog");
    // The far wall at the centre is nearly fog-coloured.
    let c = fb.get(usize::from(COLS) / 2, usize::from(ROWS));
    assert!(c.r > 150 && c.b > 160, "{c:?}");
}

#[test]
fn night_is_dark_except_near_the_player() {
    let (w, cam) = long_view();
    let light = Lighting {
        night: true,
        ..Lighting::default()
    };
    let fb = render(&Scene::new(&w, cam).with_light(light));
    golden(&fb, "night");
    let far = fb.get(usize::from(COLS) / 2, usize::from(ROWS));
    let near_floor = fb.get(usize::from(COLS) / 2, fb.height() - 1);
    assert!(
        far.luma() < 20 && near_floor.luma() > 60,
        "{far:?} {near_floor:?}"
    );
}

#[test]
fn map_fog_and_shade_lines_light_the_scene() {
    let w = world("FOG 20,24,30 0.2\nSHADE 0.1\n", ROOM);
    let lit = Scene::new(&w, east_from(1.5, 3.5));
    assert!(lit.light.fog.is_some() && lit.light.falloff == 0.1);
    let plain = Scene::new(&w, east_from(1.5, 3.5)).with_light(Lighting::default());
    assert_ne!(render(&lit), render(&plain));
}

#[test]
fn looking_up_and_down() {
    let (w, cam) = long_view();
    let up = render(&Scene::new(&w, cam).with_view(View::new(12.0, 0.5)));
    let down = render(&Scene::new(&w, cam).with_view(View::new(-12.0, 0.5)));
    golden(&up, "look_up");
    golden(&down, "look_down");
    let level = render(&Scene::new(&w, cam));
    assert_ne!(up, level);
    assert_ne!(down, level);
}

#[test]
fn crouching_and_jumping() {
    let (w, cam) = long_view();
    let crouch = render(&Scene::new(&w, cam).with_view(View::new(0.0, 0.25)));
    let jump = render(&Scene::new(&w, cam).with_view(View::new(0.0, 0.8)));
    golden(&crouch, "crouch");
    golden(&jump, "jump");
}

#[test]
fn a_half_open_door() {
    let w = world(
        "SPRITE 7.5,2.5 textures/sprites/barrel.png\n",
        "1111111111\n1000100001\n1E00D00001\n1000100001\n1111111111\n",
    );
    let mut doors = DoorState::new(&w.map);
    assert_eq!(doors.cells(), &[(4, 2)]);
    let cam = east_from(1.5, 2.5);
    let shut = render(&Scene::new(&w, cam).with_doors(&doors));
    doors.set_open((4, 2), 0.5);
    let half = render(&Scene::new(&w, cam).with_doors(&doors));
    golden(&shut, "door_shut");
    golden(&half, "door_half_open");
    assert_ne!(shut, half);
    // Without a door state, doors are drawn shut.
    assert_eq!(shut, render(&Scene::new(&w, cam)));
}
