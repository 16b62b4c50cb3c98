//! Encode time per frame at 240x68, fastest of REPS runs (beam width as the first argument).
//!
//! `cargo run --release --example enc_timing -- 2` (LEVEL=256 limits to one level).

use halfcast::bench::{camera_path, BenchScene};
use halfcast::encode::{ColorLevel, EncodeOptions, Encoder};
use halfcast::{Framebuffer, Scene, World};
use std::time::Instant;

fn main() {
    let beam: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(4);
    let world = World::default_world();
    for scene in BenchScene::ALL {
        let frames: Vec<Framebuffer> = camera_path(&world.map, scene, 21)
            .into_iter()
            .map(|c| Scene::new(&world, c).render(240, 68))
            .collect();
        for level in ColorLevel::ALL {
            if std::env::var("LEVEL").is_ok_and(|l| l != level.name()) {
                continue;
            }
            let mut opts = EncodeOptions::new(level);
            opts.beam = beam;
            let mut best = vec![f64::MAX; frames.len()];
            for _ in 0..std::env::var("REPS")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(15)
            {
                let mut e = Encoder::new(opts);
                for (i, fb) in frames.iter().enumerate() {
                    let t = Instant::now();
                    std::hint::black_box(e.encode(fb, 0, 0).len());
                    best[i] = best[i].min(t.elapsed().as_secs_f64() * 1000.0);
                }
            }
            let m: f64 = best[1..].iter().sum::<f64>() / 20.0;
            // Stock ratatui on the same frames, timed the same way (fastest of the repeats).
            let mut rbest = vec![f64::MAX; frames.len()];
            for _ in 0..5 {
                let mut r = halfcast::bench::RatatuiReference::new(240, 68, level);
                for (i, fb) in frames.iter().enumerate() {
                    let t = Instant::now();
                    std::hint::black_box(r.draw(fb).len());
                    rbest[i] = rbest[i].min(t.elapsed().as_secs_f64() * 1000.0);
                }
            }
            let rm: f64 = rbest[1..].iter().sum::<f64>() / 20.0;
            println!(
                "{} {} {:.3} ms (stock ratatui draw {:.3} ms)",
                scene.name(),
                level,
                m,
                rm
            );
        }
    }
}
