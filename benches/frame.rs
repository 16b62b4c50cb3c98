//! Cast + rasterize, single thread: the engine core's frame cost on the flat default map, on
//! `maps/heights.cub` (issue 14's variable heights) and on a worst case for heights: an open
//! hall whose every cell has its own floor and ceiling, seen looking down across it.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use halfcast::camera::Camera;
use halfcast::world::World;
use halfcast::{Framebuffer, Scene, Vec2, View};

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

/// A 40 × 40 hall of cells whose floors and ceilings all differ from their neighbours'.
fn stepped_hall() -> World {
    let mut text = String::from("NO textures/bricks.png\nSO textures/bricks.png\nWE textures/stone.png\nEA textures/stone.png\nF 96,88,80\nC 150,146,136\nFT textures/floor.png\nCT textures/ceiling.png\n");
    for (k, z) in ('a'..='h').enumerate() {
        let f = k as f64 * 0.11 - 0.4;
        text += &format!(
            "H{z} {f} {}\nW{z} textures/wood.png\n",
            f + 1.6 + (k % 3) as f64 * 0.3
        );
    }
    let n = 40;
    for j in 0..n {
        for i in 0..n {
            let ch = if i == 0 || j == 0 || i == n - 1 || j == n - 1 {
                '1'
            } else if (i, j) == (2, 2) {
                'E'
            } else {
                (b'a' + ((i * 3 + j * 5) % 8) as u8) as char
            };
            text.push(ch);
        }
        text.push('\n');
    }
    let map = halfcast::map::parse_map("hall.cub", text.as_bytes()).unwrap();
    World::load(map, &halfcast::world::TextureSource::Embedded, true)
        .unwrap()
        .0
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
    group.finish();
}

criterion_group!(benches, frame, heights);
criterion_main!(benches);
