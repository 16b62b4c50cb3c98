//! Terminal screens side by side as one PNG: each a capture of what a terminal shows (ANSI as
//! `tmux capture-pane -e -p` prints it, cells text or a PNG frame), read back through
//! halfcast's terminal model, each cell painted as its two half-block pixels (a text cell: its
//! foreground over its background), scaled up. Made for `docs/colour.md`'s tmux screenshots
//! (`docs/screenshots/tmux_colour.sh` captures them).
//!
//! `cargo run --release --features vt100 --example screen_sheet -- OUT.png SCALE CAPTURE...`

use halfcast::termframe::{load, FramePixels};
use halfcast::Framebuffer;

/// Black pixels between screens.
const GAP: usize = 6;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [out, scale, captures @ ..] = args.as_slice() else {
        eprintln!("usage: screen_sheet OUT.png SCALE CAPTURE...");
        std::process::exit(2);
    };
    let scale: usize = match scale.parse() {
        Ok(s) if (1..=16).contains(&s) => s,
        _ => {
            eprintln!("screen_sheet: SCALE must be 1 to 16, not {scale:?}");
            std::process::exit(2);
        }
    };
    let screens: Vec<Framebuffer> = captures
        .iter()
        .map(|path| match load(std::path::Path::new(path)) {
            Ok((frame, _)) => frame.to_framebuffer(),
            Err(e) => {
                eprintln!("screen_sheet: {path}: {e}");
                std::process::exit(2);
            }
        })
        .collect();
    let width = screens
        .iter()
        .map(|s| s.width() * scale + GAP)
        .sum::<usize>();
    let height = screens
        .iter()
        .map(|s| s.height() * scale)
        .max()
        .unwrap_or(0);
    let mut sheet = Framebuffer::new(width.saturating_sub(GAP), height);
    let mut left = 0;
    for s in &screens {
        for y in 0..s.height() * scale {
            for x in 0..s.width() * scale {
                sheet.set(left + x, y, s.get(x / scale, y / scale));
            }
        }
        left += s.width() * scale + GAP;
    }
    std::fs::write(out, sheet.to_png().expect("PNG encodes")).expect("the sheet is written");
    println!("{out}: {} screens, left to right as given", screens.len());
}
