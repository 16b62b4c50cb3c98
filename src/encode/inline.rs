//! A whole frame as a stream of lines (`render --format ansi`): no cursor addressing, so it can be
//! printed, piped or `cat` anywhere; mono is plain text without a single escape sequence.

use super::cursor::Cursor;
use super::encoder::EncodeOptions;
use super::level::ColorLevel;
use super::palette::{Palette, DEFAULT};
use super::plan::{Choice, RowPlanner, RowStart};
use super::quantize::quantize;
use super::sgr;
use crate::render::framebuffer::Framebuffer;

/// Every cell of `fb`, row by row, each row ending with a colour reset and a newline.
///
/// The cells are chosen by the same planner as the live encoder (so a row costs what a full redraw
/// of that row costs); `sync`, `delta` and cursor moves do not apply here.
#[must_use]
///
/// A frame at a finer glyph setting is written as its masks and two colours per cell (in mono,
/// as half-blocks of its means).
pub fn full_frame(fb: &Framebuffer, opts: &EncodeOptions) -> Vec<u8> {
    if fb.glyphs() != crate::render::glyphs::Glyphs::Half {
        if opts.level == ColorLevel::Mono {
            return full_frame(&super::glyph_frame::as_half_blocks(fb), opts);
        }
        return super::glyph_frame::full_lines(fb, &Palette::new(opts.level));
    }
    let palette = Palette::new(opts.level);
    let mut cells = Vec::new();
    quantize(&palette, fb, &mut cells);
    let w = fb.width();
    let mut out = Vec::with_capacity(w * fb.cell_rows() * 8);
    if opts.level == ColorLevel::Mono {
        for row in cells.chunks(w.max(1)).take(fb.cell_rows()) {
            out.extend(row.iter().map(|c| c[0] as u8));
            out.push(b'\n');
        }
        return out;
    }
    let mut planner = RowPlanner::default();
    let must = vec![false; w];
    for row in cells.chunks(w.max(1)).take(fb.cell_rows()) {
        let start = RowStart {
            level: opts.level,
            colours: (DEFAULT, DEFAULT),
            cursor: Cursor::At { col: 0, row: 0 },
            origin_col: 0,
            row: 0,
        };
        let mut colours = start.colours;
        for span in planner.plan(&start, row, &must, opts.beam) {
            debug_assert_ne!(span.choice, Choice::Skip);
            let next = span.choice.colours(row[usize::from(span.x)], colours);
            sgr::write(&mut out, opts.level, colours, next);
            for _ in 0..span.len {
                out.extend_from_slice(span.choice.glyph());
            }
            colours = next;
        }
        sgr::write(&mut out, opts.level, colours, (DEFAULT, DEFAULT));
        out.push(b'\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use crate::output::text::to_text;

    #[test]
    fn mono_is_exactly_the_text_view() {
        let mut fb = Framebuffer::for_cells(5, 3);
        fb.set(2, 2, Rgb::new(255, 255, 255));
        fb.set(2, 3, Rgb::new(255, 255, 255));
        let out = full_frame(&fb, &EncodeOptions::new(ColorLevel::Mono));
        assert_eq!(String::from_utf8(out).unwrap(), to_text(&fb));
    }

    #[test]
    fn each_row_ends_reset_and_terminated() {
        let mut fb = Framebuffer::for_cells(2, 2);
        fb.set(0, 0, Rgb::new(1, 2, 3));
        let s = String::from_utf8(full_frame(&fb, &EncodeOptions::default())).unwrap();
        let lines: Vec<&str> = s.lines().collect();
        assert_eq!(lines.len(), 2);
        assert!(lines.iter().all(|l| l.ends_with("\x1b[m")));
        assert!(lines[0].contains("38;2;1;2;3"));
    }
}
