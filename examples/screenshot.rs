//! Any terminal frame as a PNG screenshot, text in halfcast's own bitmap font, every cell 8×16
//! pixels, attributes drawn: a replayed game screen, a ratatui `Buffer`'s `Debug` or cells text
//! in an insta `.snap`, ANSI (with the `vt100` feature).
//!
//! The README's screenshot is made from a replay this way:
//!
//! ```sh
//! halfcast replay docs/screenshots/readme.hcr --frames 19 --format cells --out /tmp/readme/
//! cargo run --example screenshot -- /tmp/readme/frame-00019.cells.txt docs/screenshot.png
//! ```

use halfcast::output::screenshot::screenshot;
use halfcast::termframe::load;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [frame, out] = args.as_slice() else {
        eprintln!("usage: screenshot FRAME OUT.png");
        std::process::exit(2);
    };
    let frame = match load(std::path::Path::new(frame)) {
        Ok((frame, _)) => frame,
        Err(e) => {
            eprintln!("screenshot: {e}");
            std::process::exit(2);
        }
    };
    let png = screenshot(&frame).to_png().unwrap_or_else(|e| {
        eprintln!("screenshot: {e}");
        std::process::exit(1);
    });
    if let Err(e) = std::fs::write(out, png) {
        eprintln!("screenshot: {out}: {e}");
        std::process::exit(1);
    }
}
