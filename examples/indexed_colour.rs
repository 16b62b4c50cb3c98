//! Measures what an indexed-colour renderer (textures and shading already in the xterm-256 palette)
//! would change: the picture error of mapping truecolor frames to 256/16 colours (OKLab ΔE), and the
//! bytes the encoder sends for palette-exact frames at truecolor vs 256.
//!
//! `cargo run --release --example indexed_colour`

use halfcast::bench::{camera_path, BenchScene};
use halfcast::encode::palette::oklab;
use halfcast::encode::{ColorLevel, EncodeOptions, Encoder, Palette};
use halfcast::{Framebuffer, Scene, World};

fn delta_e(a: halfcast::Rgb, b: halfcast::Rgb) -> f64 {
    let (p, q) = (oklab(a), oklab(b));
    f64::from(((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt())
}

fn mapped(fb: &Framebuffer, p: &Palette) -> Framebuffer {
    let mut out = fb.clone();
    for y in 0..fb.height() {
        for x in 0..fb.width() {
            out.set(x, y, p.rgb(p.code(fb.get(x, y))));
        }
    }
    out
}

fn bytes(frames: &[Framebuffer], level: ColorLevel) -> f64 {
    let mut e = Encoder::new(EncodeOptions::new(level));
    let sizes: Vec<usize> = frames.iter().map(|f| e.encode(f, 0, 0).len()).collect();
    sizes[1..].iter().sum::<usize>() as f64 / (sizes.len() - 1) as f64
}

fn main() {
    let world = World::default_world();
    for scene in BenchScene::ALL {
        let frames: Vec<Framebuffer> = camera_path(&world.map, scene, 41)
            .into_iter()
            .map(|c| Scene::new(&world, c).render(240, 68))
            .collect();
        for level in [ColorLevel::Ansi256, ColorLevel::Ansi16] {
            let p = Palette::new(level);
            let q: Vec<Framebuffer> = frames.iter().map(|f| mapped(f, &p)).collect();
            let (mut sum, mut n) = (0.0, 0usize);
            for (f, g) in frames.iter().zip(&q) {
                for (a, b) in f.pixels().iter().zip(g.pixels()) {
                    sum += delta_e(*a, *b);
                    n += 1;
                }
            }
            let distinct: std::collections::HashSet<_> = frames
                .iter()
                .flat_map(|f| f.pixels().iter().copied())
                .collect();
            println!(
                "{:<5} {:>4} mean ΔE(OKLab×100) {:5.2} | distinct truecolour colours {:6} | \
                 truecolor B/f: raw {:8.0}, palette-exact frames {:8.0} | {} B/f {:8.0}",
                scene.name(),
                level.name(),
                100.0 * sum / n as f64,
                distinct.len(),
                bytes(&frames, ColorLevel::TrueColor),
                bytes(&q, ColorLevel::TrueColor),
                level.name(),
                bytes(&frames, level),
            );
        }
    }
}
