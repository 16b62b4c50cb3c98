//! Frame cost as thread CPU time (read from /proc/thread-self/schedstat, Linux), the minimum over
//! batches: steadier than wall-clock criterion runs on a machine shared with other work.
//! `cargo run --release --example frame_cpu [heights]`.
use halfcast::camera::Camera;
use halfcast::world::World;
use halfcast::{Framebuffer, Scene, Vec2};

#[path = "../benches/support/stepped_hall.rs"]
mod stepped_hall;
use stepped_hall::stepped_hall;

fn cpu_ns() -> u128 {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").unwrap();
    s.split_whitespace().next().unwrap().parse().unwrap()
}

fn measure(name: &str, scene: &Scene, cols: u16, rows: u16) {
    let mut fb = Framebuffer::for_cells(cols, rows);
    let mut best = u128::MAX;
    for _ in 0..15 {
        let t0 = cpu_ns();
        for _ in 0..100 {
            scene.render_into(&mut fb, Some(usize::from(cols) / 2));
        }
        best = best.min((cpu_ns() - t0) / 100);
    }
    println!(
        "{name} {cols}x{rows}: {:.1} us/frame (min of 15 batches of 100, thread CPU time)",
        best as f64 / 1000.0
    );
}

fn main() {
    let world = World::default_world();
    let scene = Scene::new(&world, Camera::from_angle(Vec2::new(14.5, 9.5), 30.0, 66.0));
    measure("flat default", &scene, 240, 68);
    measure("flat default", &scene, 120, 40);
    let mut night = scene;
    night.light.night = true;
    measure("flat default night (lamps)", &night, 240, 68);
    if std::env::args().nth(1).as_deref() == Some("heights") {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("maps/heights.cub");
        let (hw, _) = World::from_file(&path, true).unwrap();
        let s = Scene::new(&hw, Camera::from_angle(Vec2::new(13.5, 5.5), 180.0, 66.0));
        measure("heights.cub start", &s, 240, 68);
        let s = Scene::new(&hw, Camera::from_angle(Vec2::new(8.5, 7.5), 135.0, 66.0));
        measure("heights.cub hall", &s, 240, 68);
        // Night: the balcony lamp and the one by the pit light the hall (3-D lamp light).
        let mut s = Scene::new(&hw, Camera::from_angle(Vec2::new(8.5, 7.5), 135.0, 66.0));
        s.light.night = true;
        measure("heights.cub hall night (lamps)", &s, 240, 68);
        let mut s = Scene::new(&hw, Camera::from_angle(Vec2::new(13.5, 5.5), 0.0, 66.0));
        s.light.night = true;
        measure("heights.cub pit night (lamps)", &s, 240, 68);
        let mut dark = hw.clone();
        dark.lightmap = Default::default();
        let mut s = Scene::new(&dark, Camera::from_angle(Vec2::new(8.5, 7.5), 135.0, 66.0));
        s.light.night = true;
        measure("heights.cub hall night (no lamps)", &s, 240, 68);
        let hall = stepped_hall();
        let s = Scene::new(&hall, Camera::from_angle(Vec2::new(2.5, 2.5), -45.0, 66.0))
            .with_view(halfcast::View::new(-10.0, 0.5));
        measure("stepped hall (worst case)", &s, 240, 68);
    }
}
