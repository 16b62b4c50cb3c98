//! Cast + rasterize, single thread: the engine core's frame cost on the flat default map, on
//! `maps/heights.cub` (issue 14's variable heights) and on a worst case for heights: an open
//! hall whose every cell has its own floor and ceiling, seen looking down across it; and at night,
//! `maps/heights.cub`'s lamps (3-D lamp light) beside the flat default map's.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use halfcast::camera::Camera;
use halfcast::world::World;
use halfcast::{Framebuffer, Scene, Vec2, View};

#[path = "support/stepped_hall.rs"]
mod stepped_hall;
use stepped_hall::stepped_hall;

fn frame(c: &mut Criterion) {
    let world = World::default_world();
    let cam = Camera::from_angle(Vec2::new(14.5, 9.5), 30.0, 66.0);
    let scene = Scene::new(&world, cam);
    let mut group = c.benchmark_group("cast+rasterize");
    for (cols, rows) in [(240u16, 68u16), (120, 40)] {
        let mut fb = Framebuffer::for_cells(cols, rows);
        group.bench_with_input(
            BenchmarkId::from_parameter(format!("{cols}x{rows}")),
            &(),
            |b, ()| {
                b.iter(|| scene.render_into(&mut fb, Some(usize::from(cols) / 2)));
            },
        );
    }
    group.finish();
}

fn heights(c: &mut Criterion) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("maps/heights.cub");
    let (world, _) = World::from_file(&path, true).unwrap();
    let hall = stepped_hall();
    let cases = [
        // The start, looking through the window into the hall.
        ("heights.cub", &world, Vec2::new(13.5, 5.5), 180.0, 0.0, 0.0),
        (
            "heights.cub-hall",
            &world,
            Vec2::new(8.5, 7.5),
            135.0,
            0.0,
            0.0,
        ),
        (
            "stepped-hall",
            &hall,
            Vec2::new(2.5, 2.5),
            -45.0,
            -10.0,
            0.0,
        ),
    ];
    let mut group = c.benchmark_group("heights");
    for (name, w, pos, angle, pitch, ground) in cases {
        let scene = Scene::new(w, Camera::from_angle(pos, angle, 66.0))
            .with_view(View::new(pitch, 0.5).on_ground(ground));
        let mut fb = Framebuffer::for_cells(240, 68);
        group.bench_with_input(BenchmarkId::new(name, "240x68"), &(), |b, ()| {
            b.iter(|| scene.render_into(&mut fb, Some(120)));
        });
    }
    // Night: its two lamps light the hall, each surface by its 3-D distance; the flat default
    // map at night (its lamps baked in 2-D) for comparison.
    let flat = World::default_world();
    let nights = [
        ("heights.cub-hall-night", &world, Vec2::new(8.5, 7.5), 135.0),
        ("flat-default-night", &flat, Vec2::new(14.5, 9.5), 30.0),
    ];
    for (name, w, pos, angle) in nights {
        let mut scene = Scene::new(w, Camera::from_angle(pos, angle, 66.0));
        scene.light.night = true;
        let mut fb = Framebuffer::for_cells(240, 68);
        group.bench_with_input(BenchmarkId::new(name, "240x68"), &(), |b, ()| {
            b.iter(|| scene.render_into(&mut fb, Some(120)));
        });
    }
    group.finish();
}

criterion_group!(benches, frame, heights);
criterion_main!(benches);
