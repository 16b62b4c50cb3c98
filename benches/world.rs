//! Cast + rasterize of the default map with its world features on: 37 sprites (animated,
//! 8-view, translucent), 3 doors half open, fog; at 240×68 cells (240×136 pixels). The `night`
//! cases add night light and the map's lamps (a light-map lookup per floor pixel).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use halfcast::camera::Camera;
use halfcast::world::door::DoorState;
use halfcast::world::World;
use halfcast::{Framebuffer, Scene, Vec2, View};

fn world_frame(c: &mut Criterion) {
    let world = World::default_world();
    assert!(world.sprites.len() >= 30 && world.map.fog.is_some());
    let mut doors = DoorState::new(&world.map);
    assert!(!doors.cells().is_empty());
    for cell in doors.cells().to_vec() {
        doors.set_open(cell, 0.5);
    }
    let poses = [
        ("start", Vec2::new(15.5, 5.5), 90.0, View::default()),
        (
            "big-room-west",
            Vec2::new(26.5, 6.5),
            165.0,
            View::default(),
        ),
        (
            "west-door",
            Vec2::new(16.5, 5.2),
            180.0,
            View::new(-8.0, 0.4),
        ),
        ("garden", Vec2::new(20.5, 19.5), 160.0, View::new(6.0, 0.6)),
    ];
    assert!(!world.lightmap.is_empty());
    let (cols, rows) = (240u16, 68u16);
    let mut group = c.benchmark_group(format!("world {cols}x{rows}"));
    for (name, pos, angle, view) in poses {
        let day = Scene::new(&world, Camera::from_angle(pos, angle, 66.0))
            .with_doors(&doors)
            .with_view(view)
            .at_time(1.3);
        let mut night = day;
        night.light.night = true;
        for (scene, label) in [(day, name.to_owned()), (night, format!("{name}-night"))] {
            let mut fb = Framebuffer::for_cells(cols, rows);
            group.bench_with_input(BenchmarkId::from_parameter(label), &(), |b, ()| {
                b.iter(|| scene.render_frame(&mut fb, Some(usize::from(cols) / 2)));
            });
        }
    }
    group.finish();
}

criterion_group!(benches, world_frame);
criterion_main!(benches);
