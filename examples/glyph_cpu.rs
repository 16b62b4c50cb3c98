//! Render and encode cost of each glyph setting along the bench's walk path (30 frames after the
//! first, which is a full redraw): each frame's fastest of several passes, so other work on a
//! shared machine mostly drops out, then the mean per frame.
//! `cargo run --release --example glyph_cpu [passes] [half|quadrant|sextant|octant] [WxH]
//! [truecolor|256|16]` (one pass of one setting and size is for a profiler such as callgrind:
//! build it with `--profile profiling` so the profiler sees line tables, docs/testing.md).
use std::time::Instant;

use halfcast::bench::{camera_path, BenchScene};
use halfcast::encode::glyph_frame::glyph_cells;
use halfcast::encode::{ColorLevel, EncodeOptions, Encoder};
use halfcast::world::World;
use halfcast::{Framebuffer, Glyphs, Scene};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let passes: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(5);
    let only: Option<Glyphs> = args.get(1).and_then(|a| a.parse().ok());
    let size = args.get(2).and_then(|a| {
        let (w, h) = a.split_once('x')?;
        Some((w.parse().ok()?, h.parse().ok()?))
    });
    let sizes: Vec<(u16, u16)> = size.map_or(vec![(80, 24), (240, 68)], |s| vec![s]);
    let level = match args.get(3).map(String::as_str) {
        Some("256") => ColorLevel::Ansi256,
        Some("16") => ColorLevel::Ansi16,
        _ => ColorLevel::TrueColor,
    };
    let world = World::default_world();
    let cams = camera_path(&world.map, BenchScene::Walk, 31);
    for (cols, rows) in sizes {
        let mut base = None;
        for glyphs in Glyphs::ALL {
            if only.is_some_and(|o| o != glyphs) {
                continue;
            }
            let mut render = vec![f64::MAX; cams.len()];
            let mut encode = vec![f64::MAX; cams.len()];
            let mut fit = vec![f64::MAX; cams.len()];
            let mut cells = Vec::new();
            for _ in 0..passes {
                let mut enc = Encoder::new(EncodeOptions::new(level));
                let mut fb = Framebuffer::for_glyphs(cols, rows, glyphs);
                // Only the palette levels read dither phases: the game and the server skip them
                // elsewhere.
                fb.set_phases_wanted(level.mixes());
                for (i, &cam) in cams.iter().enumerate() {
                    let t = Instant::now();
                    Scene::new(&world, cam).render_into(&mut fb, None);
                    let m = Instant::now();
                    std::hint::black_box(enc.encode(&fb, 0, 0).len());
                    let e = m.elapsed().as_secs_f64() * 1e3;
                    render[i] = render[i].min((m - t).as_secs_f64() * 1e3);
                    encode[i] = encode[i].min(e);
                    if glyphs != Glyphs::Half {
                        let t = Instant::now();
                        glyph_cells(&fb, &mut cells);
                        fit[i] = fit[i].min(t.elapsed().as_secs_f64() * 1e3);
                    }
                }
            }
            let mean = |v: &[f64]| v[1..].iter().sum::<f64>() / (v.len() - 1) as f64;
            let (r, e) = (mean(&render), mean(&encode));
            let f = if glyphs == Glyphs::Half {
                0.0
            } else {
                mean(&fit)
            };
            let b = *base.get_or_insert(r + e);
            println!(
                "{glyphs:<8} {cols}x{rows}: render {r:.3} ms, encode {e:.3} ms (cells chosen in {f:.3}), total {:.3} ms \
                 ({:.2}x half, {:.0} fps)",
                r + e,
                (r + e) / b,
                1000.0 / (r + e)
            );
        }
    }
}
