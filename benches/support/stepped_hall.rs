//! The heights worst case shared by `benches/frame.rs` and `examples/frame_cpu.rs`.

use halfcast::world::World;

/// A 40 × 40 hall of cells whose floors and ceilings all differ from their neighbours'.
pub fn stepped_hall() -> World {
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
