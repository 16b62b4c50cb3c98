//! Frame cost as thread CPU time (read from /proc/thread-self/schedstat, Linux), the minimum over
//! batches: steadier than wall-clock criterion runs on a machine shared with other work.
//! `cargo run --release --example frame_cpu [heights]`.
use halfcast::camera::Camera;
use halfcast::world::World;
use halfcast::{Framebuffer, Scene, Vec2};

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
    if std::env::args().nth(1).as_deref() == Some("heights") {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("maps/heights.cub");
        let (hw, _) = World::from_file(&path, true).unwrap();
        let s = Scene::new(&hw, Camera::from_angle(Vec2::new(13.5, 5.5), 180.0, 66.0));
        measure("heights.cub start", &s, 240, 68);
        let s = Scene::new(&hw, Camera::from_angle(Vec2::new(8.5, 7.5), 135.0, 66.0));
        measure("heights.cub hall", &s, 240, 68);
        let hall = stepped_hall();
        let s = Scene::new(&hall, Camera::from_angle(Vec2::new(2.5, 2.5), -45.0, 66.0))
            .with_view(halfcast::View::new(-10.0, 0.5));
        measure("stepped hall (worst case)", &s, 240, 68);
    }
}

/// The worst case of benches/frame.rs: a 40 × 40 hall whose every cell differs in height from
/// its neighbours.
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
