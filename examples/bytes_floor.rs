//! What a 256-colour picture of `halfcast bench`'s paths costs in bytes, whatever the mapping:
//! the same frames sent by the encoder as halfcast maps them, as each pixel's nearest palette
//! colour (no pattern, so no colour changes of its own) and as
//! Floyd–Steinberg draws them, each as a share of stock ratatui's truecolor bytes (the bench's
//! yardstick); and the nearest frames against stock ratatui at 256 colours, to show what is
//! left to the encoder. The issue's byte goal is read against these (docs/colour.md, "Where it
//! falls short"). `cargo run --release --example bytes_floor [frames]`
use halfcast::bench::scielab::{floyd_steinberg, nearest};
use halfcast::bench::{camera_path, BenchScene, RatatuiReference};
use halfcast::encode::palette::xterm_rgb;
use halfcast::encode::{ColorLevel, EncodeOptions, Encoder};
use halfcast::world::World;
use halfcast::{Framebuffer, Rgb, Scene};

/// Mean bytes per frame after the first (which is a full redraw).
fn after_first(sizes: impl Iterator<Item = usize>) -> f64 {
    let sizes: Vec<usize> = sizes.skip(1).collect();
    sizes.iter().sum::<usize>() as f64 / sizes.len() as f64
}

/// The encoder's bytes per frame at 256 colours.
fn encoded(frames: &[Framebuffer]) -> f64 {
    let mut enc = Encoder::new(EncodeOptions::new(ColorLevel::Ansi256));
    after_first(frames.iter().map(|fb| enc.encode(fb, 0, 0).len()))
}

/// Stock ratatui's bytes per frame at `level`.
fn stock(frames: &[Framebuffer], level: ColorLevel) -> f64 {
    let fb = &frames[0];
    let mut r = RatatuiReference::new(fb.width() as u16, fb.cell_rows() as u16, level);
    after_first(frames.iter().map(|fb| r.draw(fb).len()))
}

/// `fb`'s pixels replaced by `f`'s, with no surface pattern (as a frame from elsewhere: a new
/// framebuffer carries no dither phases, so the encoder uses its no-pattern mixes).
fn redrawn(fb: &Framebuffer, f: impl Fn(&[Rgb], usize) -> Vec<Rgb>) -> Framebuffer {
    let w = fb.width();
    let shown = f(fb.pixels(), w);
    let mut out = Framebuffer::for_cells(w as u16, fb.cell_rows() as u16);
    for (i, &c) in shown.iter().enumerate() {
        out.set(i % w, i / w, c);
    }
    out
}

fn main() {
    let frames: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(60);
    // The entries the 256-colour level sends: never 0–15, whose colours the terminal's theme sets.
    let palette: Vec<Rgb> = (16..=255).map(xterm_rgb).collect();
    let world = World::default_world();
    println!(
        "256 colours, bytes per frame after the first as a share of stock ratatui truecolor's"
    );
    println!("path  size    | halfcast | nearest |  FS    | nearest / stock 256");
    for size in [(240u16, 68u16), (160, 48)] {
        let mut sums = [0.0; 3];
        for scene in BenchScene::ALL {
            let shots: Vec<Framebuffer> = camera_path(&world.map, scene, frames + 1)
                .into_iter()
                .map(|cam| {
                    let mut fb = Framebuffer::for_cells(size.0, size.1);
                    Scene::new(&world, cam).render_into(&mut fb, None);
                    fb
                })
                .collect();
            let truecolor = stock(&shots, ColorLevel::TrueColor);
            let near: Vec<Framebuffer> = shots
                .iter()
                .map(|fb| redrawn(fb, |px, _| nearest(px, &palette)))
                .collect();
            let fs: Vec<Framebuffer> = shots
                .iter()
                .map(|fb| redrawn(fb, |px, w| floyd_steinberg(px, w, &palette)))
                .collect();
            let near_bytes = encoded(&near);
            let shares = [encoded(&shots), near_bytes, encoded(&fs)].map(|b| 100.0 * b / truecolor);
            let left = 100.0 * near_bytes / stock(&near, ColorLevel::Ansi256);
            for (s, v) in sums.iter_mut().zip(shares) {
                *s += v / BenchScene::ALL.len() as f64;
            }
            println!(
                "{:5} {}x{} | {:7.1}% | {:6.1}% | {:5.1}% | {:5.1}%",
                scene.name(),
                size.0,
                size.1,
                shares[0],
                shares[1],
                shares[2],
                left
            );
        }
        println!(
            "mean  {}x{} | {:7.1}% | {:6.1}% | {:5.1}%",
            size.0, size.1, sums[0], sums[1], sums[2]
        );
    }
}
