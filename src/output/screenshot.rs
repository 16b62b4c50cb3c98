//! A picture of any terminal frame (a ratatui `Buffer`, a replayed screen, a frame read back from
//! ANSI) as a terminal would draw it: text in the project's own bitmap font, block and
//! box-drawing characters as shapes, colours as xterm's palette shows them, and the attributes
//! drawn (bold, dim, italic, underline, crossed out, reversed, hidden). Every cell is
//! [`CELL_PIXELS`], so two screenshots of one size compare pixel for pixel.

use ratatui::style::{Color, Modifier};

use crate::color::Rgb;
use crate::encode::glyph_mask::mask_of;
use crate::output::figure::font;
use crate::render::framebuffer::Framebuffer;
use crate::render::glyphs::Glyphs;
use crate::termframe::{ratatui_rgb, TermCell, TermFrame};

/// Pixels per cell (width, height): the font's 3×5 glyphs at twice their size, with room for
/// an underline.
pub const CELL_PIXELS: (usize, usize) = (8, 16);

/// The terminal's default foreground, as the screenshot shows it.
pub const DEFAULT_FG: Rgb = Rgb::new(0xd0, 0xd0, 0xd0);

/// The terminal's default background, as the screenshot shows it.
pub const DEFAULT_BG: Rgb = Rgb::new(0x10, 0x10, 0x14);

/// Font pixels to screen pixels.
const SCALE: usize = 2;

/// Where a glyph's top-left font pixel lands in its cell.
const GLYPH_AT: (usize, usize) = (1, 3);

/// The row an underline is drawn on, and the row a crossing-out line is.
const UNDERLINE_ROW: usize = 14;
const STRIKE_ROW: usize = 8;

/// Draws `frame` at [`CELL_PIXELS`] per cell.
#[must_use]
pub fn screenshot(frame: &TermFrame) -> Framebuffer {
    let (cw, ch) = CELL_PIXELS;
    let mut fb = Framebuffer::new(frame.cols * cw, frame.rows * ch);
    for y in 0..frame.rows {
        for x in 0..frame.cols {
            draw_cell(&mut fb, frame.cell(x, y), x * cw, y * ch);
        }
    }
    fb
}

/// A screenshot of `frame` with the cells at `changed` (column, row) tinted magenta and every
/// other cell dimmed to grey: where two text frames differ, as a person reads them.
#[must_use]
pub fn marked(frame: &TermFrame, changed: impl IntoIterator<Item = (usize, usize)>) -> Framebuffer {
    let mut fb = screenshot(frame);
    let mut mark = vec![false; frame.cols * frame.rows];
    for (x, y) in changed {
        if x < frame.cols && y < frame.rows {
            mark[y * frame.cols + x] = true;
        }
    }
    let (cw, ch) = CELL_PIXELS;
    for py in 0..fb.height() {
        for px in 0..fb.width() {
            let p = fb.get(px, py);
            let tinted = if mark[(py / ch) * frame.cols + px / cw] {
                Rgb::new(p.r / 2 + 127, p.g / 3, p.b / 2 + 127)
            } else {
                let l = p.luma() / 3;
                Rgb::new(l, l, l)
            };
            fb.set(px, py, tinted);
        }
    }
    fb
}

/// Half of `a` and half of `b`, for dim text and shades.
fn mix(a: Rgb, b: Rgb, k: u16) -> Rgb {
    let m = |p: u8, q: u8| ((u16::from(p) * (4 - k) + u16::from(q) * k) / 4) as u8;
    Rgb::new(m(a.r, b.r), m(a.g, b.g), m(a.b, b.b))
}

/// The ink and paper of a cell after defaults, dimming and reversal.
fn colours(c: &TermCell) -> (Rgb, Rgb) {
    let mut fg = ratatui_rgb(c.fg).unwrap_or(DEFAULT_FG);
    let mut bg = ratatui_rgb(c.bg).unwrap_or(DEFAULT_BG);
    if c.modifiers.contains(Modifier::DIM) {
        fg = mix(fg, bg, 2);
    }
    if c.modifiers.contains(Modifier::REVERSED) {
        std::mem::swap(&mut fg, &mut bg);
    }
    (fg, bg)
}

fn draw_cell(fb: &mut Framebuffer, c: &TermCell, left: usize, top: usize) {
    let (cw, ch) = CELL_PIXELS;
    let (fg, bg) = colours(c);
    let g = c.glyph.first_char();
    let hidden = c.modifiers.contains(Modifier::HIDDEN) || c.glyph.is_continuation();
    let shape = if hidden { None } else { block_shape(g) };
    for py in 0..ch {
        for px in 0..cw {
            let colour = match &shape {
                Some(Shape::Ink(ink)) => {
                    if ink(px, py) {
                        fg
                    } else {
                        bg
                    }
                }
                Some(Shape::Shade(k)) => mix(bg, fg, *k),
                None => bg,
            };
            fb.set(left + px, top + py, colour);
        }
    }
    if hidden {
        return;
    }
    if shape.is_none() {
        draw_text_glyph(fb, g, c.modifiers, fg, left, top);
    }
    let line = |fb: &mut Framebuffer, row: usize, colour: Rgb| {
        for px in 0..cw {
            fb.set(left + px, top + row, colour);
        }
    };
    if c.modifiers.contains(Modifier::UNDERLINED) {
        let colour = match c.underline {
            Color::Reset => fg,
            u => ratatui_rgb(u).unwrap_or(fg),
        };
        line(fb, UNDERLINE_ROW, colour);
    }
    if c.modifiers.contains(Modifier::CROSSED_OUT) {
        line(fb, STRIKE_ROW, fg);
    }
}

/// A letter, digit or sign in the bitmap font (a hollow box for one it lacks): bold is drawn
/// one pixel wider, italic leans the upper rows right.
fn draw_text_glyph(fb: &mut Framebuffer, g: char, m: Modifier, fg: Rgb, left: usize, top: usize) {
    let ink = font::glyph(g);
    let bold = usize::from(m.contains(Modifier::BOLD));
    let italic = m.contains(Modifier::ITALIC);
    for row in 0..font::GLYPH.1 {
        let lean = if italic {
            (font::GLYPH.1 - 1 - row) / 2
        } else {
            0
        };
        for col in 0..font::GLYPH.0 {
            if !ink(col, row) {
                continue;
            }
            for dy in 0..SCALE {
                for dx in 0..SCALE + bold {
                    let x = GLYPH_AT.0 + col * SCALE + dx + lean;
                    let y = GLYPH_AT.1 + row * SCALE + dy;
                    if x < CELL_PIXELS.0 {
                        fb.set(left + x, top + y, fg);
                    }
                }
            }
        }
    }
}

/// How a block or box-drawing character fills its cell.
enum Shape {
    /// Foreground where the function says, background elsewhere (cell pixel x, y).
    Ink(Box<dyn Fn(usize, usize) -> bool>),
    /// The background mixed `k` quarters toward the foreground (`░ ▒ ▓`).
    Shade(u16),
}

/// The shape of a block element, a mask character (half, quadrant, sextant, octant) or a
/// box-drawing line; `None` for text.
fn block_shape(g: char) -> Option<Shape> {
    let (cw, ch) = CELL_PIXELS;
    for set in [
        Glyphs::Half,
        Glyphs::Quadrant,
        Glyphs::Sextant,
        Glyphs::Octant,
    ] {
        if let Some(mask) = mask_of(set, g) {
            let (sc, sr) = set.cell_size();
            return Some(Shape::Ink(Box::new(move |x, y| {
                let bit = (y * sr / ch) * sc + x * sc / cw;
                mask >> bit & 1 == 1
            })));
        }
    }
    let n = u32::from(g);
    let eighths = |k: u32| k as usize;
    match g {
        // Lower eighths `▁`–`▇`.
        '\u{2581}'..='\u{2587}' => {
            let k = eighths(n - 0x2580);
            Some(Shape::Ink(Box::new(move |_, y| y >= ch - ch * k / 8)))
        }
        // Left eighths `▉`–`▏`.
        '\u{2589}'..='\u{258F}' => {
            let k = eighths(8 - (n - 0x2588));
            Some(Shape::Ink(Box::new(move |x, _| x < cw * k / 8)))
        }
        '▔' => Some(Shape::Ink(Box::new(move |_, y| y < ch / 8))),
        '▕' => Some(Shape::Ink(Box::new(move |x, _| x >= cw - cw / 8))),
        '░' => Some(Shape::Shade(1)),
        '▒' => Some(Shape::Shade(2)),
        '▓' => Some(Shape::Shade(3)),
        _ => box_arms(g).map(|[up, down, left, right]| {
            let (mx, my) = (cw / 2 - 1, ch / 2 - 1);
            Shape::Ink(Box::new(move |x, y| {
                (x == mx && ((up && y <= my) || (down && y >= my)))
                    || (y == my && ((left && x <= mx) || (right && x >= mx)))
            }))
        }),
    }
}

/// Which arms (up, down, left, right) a box-drawing character has; heavy, double and dashed
/// lines are drawn as light ones.
fn box_arms(g: char) -> Option<[bool; 4]> {
    const U: u8 = 1;
    const D: u8 = 2;
    const L: u8 = 4;
    const R: u8 = 8;
    let arms = match u32::from(g) {
        0x2500 | 0x2501 | 0x2504 | 0x2505 | 0x2508 | 0x2509 | 0x2550 | 0x254C | 0x254D => L | R,
        0x2502 | 0x2503 | 0x2506 | 0x2507 | 0x250A | 0x250B | 0x2551 | 0x254E | 0x254F => U | D,
        0x250C..=0x250F | 0x2552..=0x2554 | 0x256D => R | D,
        0x2510..=0x2513 | 0x2555..=0x2557 | 0x256E => L | D,
        0x2514..=0x2517 | 0x2558..=0x255A | 0x2570 => U | R,
        0x2518..=0x251B | 0x255B..=0x255D | 0x256F => U | L,
        0x251C..=0x2523 | 0x255E..=0x2560 => U | D | R,
        0x2524..=0x252B | 0x2561..=0x2563 => U | D | L,
        0x252C..=0x2533 | 0x2564..=0x2566 => L | R | D,
        0x2534..=0x253B | 0x2567..=0x2569 => L | R | U,
        0x253C..=0x254B | 0x256A..=0x256C => U | D | L | R,
        0x2574 | 0x2578 => L,
        0x2575 | 0x2579 => U,
        0x2576 | 0x257A => R,
        0x2577 | 0x257B => D,
        _ => return None,
    };
    Some([arms & U != 0, arms & D != 0, arms & L != 0, arms & R != 0])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::termframe::Glyph;

    fn one(glyph: &str, fg: Color, modifiers: Modifier) -> TermFrame {
        TermFrame {
            cols: 1,
            rows: 1,
            cells: vec![TermCell {
                glyph: Glyph::new(glyph),
                fg,
                modifiers,
                ..TermCell::default()
            }],
        }
    }

    fn inked(fb: &Framebuffer, colour: Rgb) -> usize {
        fb.pixels().iter().filter(|&&p| p == colour).count()
    }

    #[test]
    fn cells_are_a_fixed_size_and_text_is_drawn() {
        let fb = screenshot(&one("A", Color::Reset, Modifier::empty()));
        assert_eq!((fb.width(), fb.height()), CELL_PIXELS);
        // 'A' has 10 of its 15 font pixels inked, each 2×2.
        assert_eq!(inked(&fb, DEFAULT_FG), 40);
        assert_eq!(fb.get(0, 0), DEFAULT_BG);
    }

    #[test]
    fn attributes_are_drawn() {
        let plain = screenshot(&one("A", Color::Green, Modifier::empty()));
        let green = ratatui_rgb(Color::Green).unwrap();
        let bold = screenshot(&one("A", Color::Green, Modifier::BOLD));
        assert!(inked(&bold, green) > inked(&plain, green));
        let under = screenshot(&one("A", Color::Green, Modifier::UNDERLINED));
        assert!((0..8).all(|x| under.get(x, UNDERLINE_ROW) == green));
        let reversed = screenshot(&one("A", Color::Green, Modifier::REVERSED));
        assert_eq!(reversed.get(0, 0), green);
        let hidden = screenshot(&one("A", Color::Green, Modifier::HIDDEN));
        assert_eq!(inked(&hidden, green), 0);
        for m in [Modifier::DIM, Modifier::ITALIC, Modifier::CROSSED_OUT] {
            assert_ne!(screenshot(&one("A", Color::Green, m)), plain, "{m:?}");
        }
    }

    #[test]
    fn marked_cells_stand_out() {
        let mut frame = one("A", Color::Green, Modifier::empty());
        frame.cols = 2;
        frame.cells.push(TermCell::default());
        let fb = marked(&frame, [(1, 0)]);
        let (a, b) = (fb.get(0, 0), fb.get(8, 0));
        assert_eq!((a.r, a.g), (a.g, a.b), "unchanged cells are grey: {a:?}");
        assert!(b.r > b.g && b.b > b.g, "changed cells are magenta: {b:?}");
    }

    #[test]
    fn blocks_and_lines_are_shapes() {
        let upper = screenshot(&one("▀", Color::Red, Modifier::empty()));
        let red = ratatui_rgb(Color::Red).unwrap();
        assert_eq!((upper.get(3, 0), upper.get(3, 15)), (red, DEFAULT_BG));
        assert_eq!(inked(&upper, red), 8 * 8);
        let corner = screenshot(&one("┌", Color::Red, Modifier::empty()));
        assert_eq!((corner.get(7, 7), corner.get(3, 15)), (red, red));
        assert_eq!(
            (corner.get(0, 7), corner.get(3, 0)),
            (DEFAULT_BG, DEFAULT_BG)
        );
        let bar = screenshot(&one("▃", Color::Red, Modifier::empty()));
        assert_eq!(inked(&bar, red), 8 * 6);
    }
}
