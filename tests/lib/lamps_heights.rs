//! Lamps on maps with `Hz` heights light every surface by its 3-D distance (issue 14): a lamp in
//! a pit lights the pit's floor, not the top of a ledge high above it; the ceiling of a tall hall
//! straight above a lamp is as far from it as it is high. And moving lights handed to a frame
//! (`Scene::with_lights`, a projectile's glow) brighten the walls near them at night only.

use halfcast::camera::Camera;
use halfcast::map::parse_map;
use halfcast::render::light::{Lighting, ShadeTable};
use halfcast::render::{Band, PointLight, Projection};
use halfcast::world::{TextureSource, World};
use halfcast::{Framebuffer, Rgb, Scene, Vec2, View};

fn world(text: &str) -> World {
    let text = format!("NO n\nSO s\nWE w\nEA e\n{text}");
    let map = parse_map("t.cub", text.as_bytes()).unwrap();
    World::load(map, &TextureSource::Embedded, false).unwrap().0
}

fn night() -> Lighting {
    Lighting {
        night: true,
        ..Lighting::default()
    }
}

fn luma(c: Rgb) -> f64 {
    f64::from(c.r) + f64::from(c.g) + f64::from(c.b)
}

/// A pit (floor −1) in the middle of a ledge (floor 2, three above the pit's floor); every floor
/// the same grey so only light tells them apart.
const PIT: &str = "F 200,200,200\nC 200,200,200\nHp -1 3\nFp 200,200,200\nHb 2 3\nFb 200,200,200\n\
1111111111\n1N00000001\n10bbbbbbb1\n10bpppbbb1\n10bpppbbb1\n10bpppbbb1\n10bbbbbbb1\n1000000001\n1111111111\n";

/// Each floor pixel of the frame: (x, y, world point, floor height).
fn floor_pixels(scene: &Scene, w: usize, h: usize) -> Vec<(usize, usize, Vec2, f64)> {
    let mut fb = Framebuffer::new(w, h);
    let frame = scene.render_frame(&mut fb, None);
    let proj = Projection::new(&scene.camera, &scene.view, w, h);
    let mut out = Vec::new();
    for (x, col) in frame.cast.heights.iter().enumerate() {
        let ray = scene.camera.ray_dir(x, w);
        for band in &col.bands {
            let Band::Flat(f) = band else { continue };
            if f.ceiling {
                continue;
            }
            for y in f.rows.0..f.rows.1 {
                let t = (proj.eye - f.z) * proj.focal / (y as f64 + 0.5 - proj.horizon);
                let t = t.clamp(f.dist.0, f.dist.1);
                out.push((x, y, scene.camera.pos + ray * t, f.z));
            }
        }
    }
    out
}

#[test]
fn a_lamp_in_a_pit_lights_the_pit_floor_far_more_than_a_ledge_three_above_it() {
    let lamp = Vec2::new(4.5, 4.5);
    let lit = world(&format!("LIGHT {},{} 4 1\n{PIT}", lamp.x, lamp.y));
    let dark = world(PIT);
    // Standing on the ledge at the pit's east rim, looking west down into it.
    let cam = Camera::from_angle(Vec2::new(6.15, 4.5), 180.0, 90.0);
    let view = View::new(-45.0, 0.5).on_ground(2.0);
    let (w, h) = (160, 120);
    // `SHADE 3`: dark a step from the eye (at night the eye's own lantern would outshine the
    // lamp on the ledge near the eye).
    let shade = Lighting {
        falloff: 3.0,
        ..Lighting::default()
    };
    let render = |world: &World| {
        Scene::new(world, cam)
            .with_view(view)
            .with_light(shade)
            .render(w as u16, (h / 2) as u16)
    };
    let (with, without) = (render(&lit), render(&dark));
    let scene = Scene::new(&lit, cam).with_view(view).with_light(shade);
    // The lamp's gain on each floor, over points 1 to 2 cells from the lamp (in plan).
    let (mut pit, mut ledge) = (Vec::new(), Vec::new());
    for (x, y, at, z) in floor_pixels(&scene, w, h) {
        let d = (at - lamp).length();
        if !(1.0..=2.0).contains(&d) {
            continue;
        }
        let gain = luma(with.get(x, y)) - luma(without.get(x, y));
        assert!(gain >= -3.0, "({x},{y}) darkened by the lamp");
        if z < 0.0 {
            pit.push(gain);
        } else if z > 1.5 {
            ledge.push(gain);
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    println!(
        "pit floor: {} px, mean gain {:.1}; ledge top: {} px, mean gain {:.1}",
        pit.len(),
        mean(&pit),
        ledge.len(),
        mean(&ledge)
    );
    assert!(
        pit.len() > 100 && ledge.len() > 100,
        "{} {}",
        pit.len(),
        ledge.len()
    );
    assert!(
        mean(&pit) > 60.0,
        "the pit floor is hardly lit: {}",
        mean(&pit)
    );
    assert!(
        mean(&ledge) < mean(&pit) / 5.0,
        "the ledge top three above the lamp is lit like the pit floor: {} vs {}",
        mean(&ledge),
        mean(&pit)
    );
}

#[test]
fn the_ceiling_straight_above_a_lamp_in_a_tall_hall_is_lit_by_its_3d_distance() {
    // A hall three walls tall; the lamp shines from its floor up one wall height (0..1), so the
    // ceiling above it is 2 away: falloff (1 − (2/4)²)² = 0.5625 of full, where a flat bake
    // gives it full light.
    let lamp = Vec2::new(4.5, 2.5);
    let text = format!(
        "F 200,200,200\nC 200,200,200\nHh 0 3\nCh 200,200,200\nLIGHT {},{} 4 1\n\
         1111111\n1Nhhhh1\n1hhhhh1\n1hhhhh1\n1111111\n",
        lamp.x, lamp.y
    );
    let w = world(&text);
    let lm = &w.lightmap;
    assert!(lm.at_z(lamp, 0.5) >= 250, "{}", lm.at_z(lamp, 0.5));
    let above = lm.at_z(lamp, 3.0);
    assert!(
        (i32::from(above) - 144).abs() <= 3,
        "ceiling above: {above}"
    );
    // The same on screen: looking up at that ceiling from two cells west.
    let cam = Camera::from_angle(Vec2::new(2.5, 2.5), 0.0, 66.0);
    let view = View::new(40.0, 0.5);
    let scene = Scene::new(&w, cam).with_view(view).with_light(night());
    let (width, height) = (120usize, 80usize);
    let mut fb = Framebuffer::new(width, height);
    let frame = scene.render_frame(&mut fb, None);
    let proj = Projection::new(&cam, &view, width, height);
    let table = ShadeTable::new(&night());
    let mut checked = 0;
    for (x, col) in frame.cast.heights.iter().enumerate() {
        let ray = cam.ray_dir(x, width);
        for band in &col.bands {
            let Band::Flat(f) = band else { continue };
            if !f.ceiling {
                continue;
            }
            for y in f.rows.0..f.rows.1 {
                let t = (proj.eye - f.z) * proj.focal / (y as f64 + 0.5 - proj.horizon);
                let at = cam.pos + ray * t;
                if (at - lamp).length() > 0.1 {
                    continue;
                }
                let grey = Rgb::new(200, 200, 200);
                let want = table.at(t).lit(144).apply(grey);
                let flat = table.at(t).lit(256).apply(grey);
                let got = fb.get(x, y);
                assert!(
                    got.r.abs_diff(want.r) <= 3,
                    "({x},{y}) {got:?}, want {want:?} (a flat bake gives {flat:?})"
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 0, "no ceiling pixel above the lamp in view");
}

/// A room 8 cells long; walls one flat colour.
const ROOM: &str = "F 90,90,90\nC 90,90,90\nT1 200,200,200\n1111111111\n1N00000001\n1000000001\n1000000001\n1111111111\n";

#[test]
fn a_moving_light_brightens_the_wall_near_it_at_night_and_nothing_far_or_by_day() {
    // The flat renderer, and the heights renderer (an unused `Hz 0 1` zone sends the map there).
    for extra in ["", "Hz 0 1\n"] {
        let w = world(&format!("{extra}{ROOM}"));
        let cam = Camera::from_angle(Vec2::new(1.5, 2.5), 0.0, 66.0);
        let glow = [PointLight {
            pos: Vec2::new(8.6, 2.0),
            z: 0.5,
            radius: 1.2,
            strength: 1.0,
        }];
        let frame = |light: Lighting, lights: &[PointLight]| {
            Scene::new(&w, cam)
                .with_light(light)
                .with_lights(lights)
                .render(96, 32)
        };
        let (lit, dark) = (frame(night(), &glow), frame(night(), &[]));
        let (mut brighter, mut far_changed) = (0, 0);
        let mut fb = Framebuffer::for_cells(96, 32);
        let cast = Scene::new(&w, cam).render_into(&mut fb, None);
        for (x, hit) in cast.columns.iter().enumerate() {
            // The east wall's point this column sees, at eye height.
            let at = cam.pos + hit.ray_dir * hit.perp_dist;
            let near = (at - glow[0].pos).length() < 0.6;
            let far = (at - glow[0].pos).length() > 1.3;
            let centre = 32; // the horizon row: eye height on the wall
            let (a, b) = (luma(dark.get(x, centre)), luma(lit.get(x, centre)));
            if near {
                assert!(b > a + 30.0, "{extra:?} column {x}: {a} -> {b}");
                brighter += 1;
            }
            if far {
                for y in 0..64 {
                    far_changed += usize::from(dark.get(x, y) != lit.get(x, y));
                }
            }
        }
        assert!(
            brighter > 3,
            "{extra:?}: only {brighter} columns near the light"
        );
        assert_eq!(
            far_changed, 0,
            "{extra:?}: pixels far from the light changed"
        );
        // By day it changes nothing.
        assert_eq!(
            frame(Lighting::default(), &glow),
            frame(Lighting::default(), &[])
        );
    }
}
