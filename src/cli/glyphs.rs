//! `halfcast glyphs`: a test card showing every block character of each glyph setting and one
//! small picture drawn at each, so a player sees at once which sets this terminal draws.

use clap::Args;
use halfcast::encode::glyph_mask::glyph;
use halfcast::encode::{full_frame, ColorLevel, EncodeOptions};
use halfcast::{Framebuffer, Glyphs, Rgb};

use super::{detect_level, parse_level, Failure};

#[derive(Args, Debug)]
pub(crate) struct GlyphsArgs {
    /// Colour level of the pictures (default: detected from COLORTERM, TERM, NO_COLOR).
    #[arg(long, value_parser = parse_level)]
    pub(crate) colors: Option<ColorLevel>,
}

/// Picture size in cells.
const CARD: (u16, u16) = (18, 7);

/// What each setting needs, for the card.
fn needs(g: Glyphs) -> &'static str {
    match g {
        Glyphs::Half => "every terminal",
        Glyphs::Quadrant => "Unicode 1.1: nearly every font",
        Glyphs::Sextant => "Unicode 13: a terminal that draws them, or a font with them",
        Glyphs::Octant => "Unicode 16: a terminal that draws them (kitty, ghostty, foot, VTE …)",
    }
}

/// A disc over stripes at the setting's sub-grid, the same picture at every setting.
fn pattern(g: Glyphs) -> Framebuffer {
    let mut fb = Framebuffer::for_glyphs(CARD.0, CARD.1, g);
    let (w, h) = (fb.width() as f64, fb.height() as f64);
    for y in 0..fb.height() {
        for x in 0..fb.width() {
            // Cell units, a cell 1 wide and 2 tall: the picture's shape is the same everywhere.
            let (u, v) = ((x as f64 + 0.5) / w * 18.0, (y as f64 + 0.5) / h * 14.0);
            let (du, dv) = (u - 9.0, v - 7.0);
            let c = if du * du + dv * dv < 25.0 {
                Rgb::new(230, 180, 40)
            } else if ((u + v) as i64) % 4 < 2 {
                Rgb::new(40, 60, 150)
            } else {
                Rgb::new(20, 20, 40)
            };
            fb.set(x, y, c);
        }
    }
    fb
}

pub(crate) fn glyphs(args: &GlyphsArgs) -> Result<(), Failure> {
    let level = args.colors.unwrap_or_else(detect_level);
    let mut out = String::from(
        "halfcast glyphs: which block characters does this terminal draw?\n\
         Each set below should show solid shapes filling their cells: no gaps, boxes or '?'.\n\
         Choose one with `halfcast --glyphs NAME`, `glyphs = \"NAME\"` in the config, or the U key.\n\n",
    );
    for g in Glyphs::ALL {
        let n = 1usize << g.pixels_per_cell();
        out.push_str(&format!("{:<9} {}\n", g.name(), needs(g)));
        let chars: Vec<char> = (0..n).map(|m| glyph(g, m as u8)).collect();
        for line in chars.chunks(64) {
            out.push_str("          ");
            out.extend(line.iter());
            out.push('\n');
        }
    }
    out.push('\n');
    // The same picture at each setting, side by side.
    let opts = EncodeOptions::new(level);
    let pictures: Vec<Vec<String>> = Glyphs::ALL
        .iter()
        .map(|&g| {
            String::from_utf8_lossy(&full_frame(&pattern(g), &opts))
                .lines()
                .map(str::to_owned)
                .collect()
        })
        .collect();
    let width = usize::from(CARD.0) + 2;
    for g in Glyphs::ALL {
        out.push_str(&format!("{:<width$}", g.name()));
    }
    out.push('\n');
    for row in 0..usize::from(CARD.1) {
        for p in &pictures {
            out.push_str(p.get(row).map_or("", String::as_str));
            out.push_str("  ");
        }
        out.push('\n');
    }
    std::io::Write::write_all(&mut std::io::stdout(), out.as_bytes()).map_err(Failure::io)
}
