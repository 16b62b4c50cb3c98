//! Side-by-side picture of three views as truecolor | 256 colours | 16 colours: what a terminal
//! shows for each (the encoder's own cells, two pixels per cell), for `docs/colour.md`.
//!
//! `cargo run --release --example colour_sheet -- docs/colour-sheet.png`

use halfcast::encode::{ColorLevel, EncodeOptions, Encoder};
use halfcast::{Camera, Framebuffer, Scene, Vec2, World};

/// Cells across and down each view.
const VIEW: (u16, u16) = (80, 24);

/// Screen pixels per half-block pixel in the sheet.
const SCALE: usize = 3;

/// Black pixels between panels.
const GAP: usize = 4;

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "colour-sheet.png".to_string());
    let world = World::default_world();
    let poses = [(15.5, 5.5, 90.0), (12.5, 9.5, 160.0), (20.5, 3.5, 270.0)];
    let levels = [
        ColorLevel::TrueColor,
        ColorLevel::Ansi256,
        ColorLevel::Ansi16,
    ];
    let (vw, vh) = (usize::from(VIEW.0), 2 * usize::from(VIEW.1));
    let (pw, ph) = (vw * SCALE, vh * SCALE);
    let mut sheet = Framebuffer::new(3 * pw + 2 * GAP, 3 * ph + 2 * GAP);
    for (row, &(x, y, a)) in poses.iter().enumerate() {
        let fb =
            Scene::new(&world, Camera::from_angle(Vec2::new(x, y), a, 66.0)).render(VIEW.0, VIEW.1);
        for (col, &level) in levels.iter().enumerate() {
            let mut enc = Encoder::new(EncodeOptions::new(level));
            let _ = enc.encode(&fb, 0, 0);
            let shown = enc.shown_frame().expect("a colour level");
            let (ox, oy) = (col * (pw + GAP), row * (ph + GAP));
            for py in 0..ph {
                for px in 0..pw {
                    sheet.set(ox + px, oy + py, shown.get(px / SCALE, py / SCALE));
                }
            }
        }
    }
    std::fs::write(&out, sheet.to_png().expect("PNG encodes")).expect("the sheet is written");
    println!("{out}: rows are three default-map views; columns truecolor | 256 | 16");
}
