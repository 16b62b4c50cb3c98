//! Cast + rasterize of the default map, single thread: the engine core's frame cost.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use halfcast::camera::Camera;
use halfcast::world::World;
use halfcast::{Framebuffer, Scene, Vec2};

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

criterion_group!(benches, frame);
criterion_main!(benches);
