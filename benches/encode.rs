//! The terminal encoder's cost per frame: 21 frames (a full redraw, then 20 diffs) of the bench's
//! turn and walk paths at 240×68 cells at each colour level; divide by 21 for a frame (the issue's
//! target: ≤ 0.7 ms).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use halfcast::bench::{camera_path, BenchScene};
use halfcast::encode::{ColorLevel, EncodeOptions, Encoder};
use halfcast::world::World;
use halfcast::{Framebuffer, Scene};

fn encode(c: &mut Criterion) {
    let world = World::default_world();
    let mut group = c.benchmark_group("encode 21 frames 240x68");
    for scene in [BenchScene::Turn, BenchScene::Walk] {
        let frames: Vec<Framebuffer> = camera_path(&world.map, scene, 21)
            .into_iter()
            .map(|cam| Scene::new(&world, cam).render(240, 68))
            .collect();
        for level in ColorLevel::ALL {
            group.bench_with_input(
                BenchmarkId::new(scene.name(), level.name()),
                &frames,
                |b, frames| {
                    let mut enc = Encoder::new(EncodeOptions::new(level));
                    b.iter(|| {
                        // A full redraw first, so every iteration encodes the same bytes.
                        enc.invalidate();
                        frames
                            .iter()
                            .map(|f| enc.encode(f, 0, 0).len())
                            .sum::<usize>()
                    });
                },
            );
        }
    }
    group.finish();
}

criterion_group!(benches, encode);
criterion_main!(benches);
