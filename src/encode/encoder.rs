//! The frame encoder: keeps what the terminal shows and sends only the bytes that change it.

use super::cursor::{write_move, Cursor};
use super::glyph_cell::GlyphCell;
use super::glyph_frame::GlyphFrames;
use super::level::ColorLevel;
use super::palette::{distance, Code, Palette, DEFAULT, UNKNOWN};
use super::plan::{write_span, Choice, RowPlanner, RowStart, DEFAULT_BEAM};
use super::quantize::quantize;
use super::sgr;
use crate::render::framebuffer::Framebuffer;
use crate::render::glyphs::Glyphs;

/// DEC private mode 2026: the terminal holds the screen until the end marker, so frames never tear.
pub const SYNC_BEGIN: &[u8] = b"\x1b[?2026h";
/// End of a synchronized update.
pub const SYNC_END: &[u8] = b"\x1b[?2026l";

/// How frames are encoded; exact and tear-free by default.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EncodeOptions {
    /// The colour level frames are sent at.
    pub level: ColorLevel,
    /// Lossy: don't resend a cell whose colours moved less than this (0–255 perceptual scale).
    pub delta: Option<u8>,
    /// Wrap each frame in synchronized-output markers (never in mono).
    pub sync: bool,
    /// States the row planner keeps per cell (1 = greedy).
    pub beam: usize,
}

impl EncodeOptions {
    /// Exact output at `level` with synchronized updates.
    #[must_use]
    pub fn new(level: ColorLevel) -> Self {
        Self {
            level,
            delta: None,
            sync: true,
            beam: DEFAULT_BEAM,
        }
    }
}

impl Default for EncodeOptions {
    fn default() -> Self {
        Self::new(ColorLevel::TrueColor)
    }
}

/// Diffs each framebuffer against what the terminal shows and emits the cheapest update.
///
/// It owns a rectangle of the terminal: `cols × rows` cells at (`origin_col`, `origin_row`)
/// (0-based). It assumes nobody else writes into that rectangle; others may move the cursor and
/// draw elsewhere between frames, as long as they leave the colours at the default (ratatui does:
/// every `Terminal::draw` ends with a reset), because every frame starts with an absolute move and
/// ends with `ESC[m`. After anything that clears or scrolls the screen (a resize, `Terminal::clear`)
/// call [`Encoder::invalidate`]; a new framebuffer size or origin invalidates by itself.
///
/// Sharing a terminal with ratatui: draw the other panes with `terminal.draw` leaving the view's
/// `Rect` untouched (render nothing there, so both of ratatui's buffers stay blank and it never
/// writes into it), then write `encoder.encode(&fb, rect.x, rect.y)` to the same writer and flush:
/// one write per frame. With `sync: false` the caller can put `BeginSynchronizedUpdate` before the
/// ratatui draw and `EndSynchronizedUpdate` after the encoder's bytes, so panes and view update
/// together.
///
/// ```
/// use halfcast::encode::{ColorLevel, EncodeOptions, Encoder};
/// use halfcast::{Scene, World};
///
/// let world = World::default_world();
/// let start = world.map.start;
/// let mut camera = halfcast::Camera::from_angle(start.pos(), start.angle_deg(), 66.0);
/// let mut encoder = Encoder::new(EncodeOptions::new(ColorLevel::Ansi256));
/// let first = encoder.encode(&Scene::new(&world, camera).render(40, 12), 2, 1).len();
/// camera.rotate(0.05);
/// let next = encoder.encode(&Scene::new(&world, camera).render(40, 12), 2, 1).len();
/// assert!(next < first); // only what changed is sent
/// ```
#[derive(Debug)]
pub struct Encoder {
    opts: EncodeOptions,
    palette: Palette,
    cols: usize,
    rows: usize,
    origin: (u16, u16),
    /// What each cell of the terminal shows: (top, bottom) codes, or `[UNKNOWN; 2]`.
    shown: Vec<[Code; 2]>,
    /// What each cell should show this frame.
    intent: Vec<[Code; 2]>,
    skippable: Vec<bool>,
    planner: RowPlanner,
    out: Vec<u8>,
    /// True until a frame was sent since creation, resize or `invalidate`: colours then unknown.
    fresh: bool,
    /// The same for frames at a finer glyph setting (quadrants, sextants, octants).
    glyph: GlyphFrames,
    /// Whether the last frame was at a finer glyph setting.
    glyph_mode: bool,
}

impl Encoder {
    /// An encoder that knows nothing of the screen yet (the first frame is a full redraw).
    #[must_use]
    pub fn new(opts: EncodeOptions) -> Self {
        Self {
            palette: Palette::new(opts.level),
            opts,
            cols: 0,
            rows: 0,
            origin: (0, 0),
            shown: Vec::new(),
            intent: Vec::new(),
            skippable: Vec::new(),
            planner: RowPlanner::default(),
            out: Vec::new(),
            fresh: true,
            glyph: GlyphFrames::default(),
            glyph_mode: false,
        }
    }

    /// The options it encodes with.
    #[must_use]
    pub fn options(&self) -> &EncodeOptions {
        &self.opts
    }

    /// The palette (to know what a cell will look like at this level).
    #[must_use]
    pub fn palette(&self) -> &Palette {
        &self.palette
    }

    /// Forgets what the terminal shows, so the next frame is a full redraw (after resize or clear).
    pub fn invalidate(&mut self) {
        self.shown.fill([UNKNOWN; 2]);
        self.fresh = true;
        self.glyph.invalidate();
    }

    /// What the terminal shows after the last frame, row-major `[top, bottom]` per cell.
    #[must_use]
    pub fn shown(&self) -> &[[Code; 2]] {
        &self.shown
    }

    /// The pixels the terminal shows after the last frame (what a player sees, for fidelity
    /// figures); `None` in mono, where cells are shade characters rather than colours.
    #[must_use]
    pub fn shown_frame(&self) -> Option<Framebuffer> {
        if self.opts.level == ColorLevel::Mono {
            return None;
        }
        if self.glyph_mode {
            return Some(self.glyph.shown_frame(&self.palette));
        }
        let mut fb = Framebuffer::new(self.cols, 2 * self.rows);
        for (i, cell) in self.shown.iter().enumerate() {
            let (x, y) = (i % self.cols.max(1), 2 * (i / self.cols.max(1)));
            fb.set(x, y, self.palette.rgb(cell[0]));
            fb.set(x, y + 1, self.palette.rgb(cell[1]));
        }
        Some(fb)
    }

    /// The bytes that turn the terminal's view rectangle into `fb` (empty when nothing changed).
    ///
    /// A new size or origin forces a full redraw.
    ///
    /// A framebuffer at a finer glyph setting ([`Framebuffer::for_glyphs`]) is sent as a mask
    /// and two colours per cell (in mono: as half-blocks of its mean colours). Switching setting
    /// redraws everything.
    pub fn encode(&mut self, fb: &Framebuffer, origin_col: u16, origin_row: u16) -> &[u8] {
        self.encode_with(fb, None, origin_col, origin_row)
    }

    /// [`Encoder::encode`] of a frame at a finer glyph setting whose cells the caller already
    /// chose ([`glyph_cells`](super::glyph_frame::glyph_cells) of `fb`), so they are not
    /// chosen twice.
    pub(crate) fn encode_chosen(
        &mut self,
        fb: &Framebuffer,
        chosen: &[GlyphCell],
        origin_col: u16,
        origin_row: u16,
    ) -> &[u8] {
        self.encode_with(fb, Some(chosen), origin_col, origin_row)
    }

    fn encode_with(
        &mut self,
        fb: &Framebuffer,
        chosen: Option<&[GlyphCell]>,
        origin_col: u16,
        origin_row: u16,
    ) -> &[u8] {
        let fine = fb.glyphs() != Glyphs::Half && self.opts.level != ColorLevel::Mono;
        if fine != self.glyph_mode {
            self.glyph_mode = fine;
            self.invalidate();
        }
        if fine {
            self.out.clear();
            let sync = self.opts.sync;
            let origin = (origin_col, origin_row);
            self.glyph.delta = self.opts.delta;
            self.glyph
                .encode(fb, chosen, origin, &self.palette, sync, &mut self.out);
            return &self.out;
        }
        let halved;
        let fb = if fb.glyphs() == Glyphs::Half {
            fb
        } else {
            halved = super::glyph_frame::as_half_blocks(fb);
            &halved
        };
        let (cols, rows) = (fb.width(), fb.cell_rows());
        if (cols, rows) != (self.cols, self.rows) || (origin_col, origin_row) != self.origin {
            self.cols = cols;
            self.rows = rows;
            self.origin = (origin_col, origin_row);
            self.shown.clear();
            self.shown.resize(cols * rows, [UNKNOWN; 2]);
            self.fresh = true;
        }
        quantize(&self.palette, fb, &mut self.intent);
        self.out.clear();
        if self.opts.level == ColorLevel::Mono {
            self.encode_mono();
        } else {
            self.encode_colour();
        }
        &self.out
    }

    fn encode_colour(&mut self) {
        let level = self.opts.level;
        if self.opts.sync {
            self.out.extend_from_slice(SYNC_BEGIN);
        }
        // Every frame ends with `ESC[m` (and ratatui ends its draws the same way), so colours are
        // known to be the defaults unless this is the first frame.
        let mut colours = if self.fresh {
            (UNKNOWN, UNKNOWN)
        } else {
            (DEFAULT, DEFAULT)
        };
        let mut cursor = Cursor::Unknown;
        let mut drew = false;
        let w = self.cols;
        for y in 0..self.rows {
            let row = self.origin.1 + y as u16;
            let span = y * w..(y + 1) * w;
            self.skippable.clear();
            let (shown, intent) = (&self.shown[span.clone()], &self.intent[span.clone()]);
            match self.opts.delta {
                None => self
                    .skippable
                    .extend(shown.iter().zip(intent).map(|(s, i)| s == i)),
                Some(n) => {
                    let p = &self.palette;
                    let close = |s: Code, i: Code| {
                        s == i || (s != UNKNOWN && distance(p.rgb(s), p.rgb(i)) < u32::from(n))
                    };
                    self.skippable.extend(
                        shown
                            .iter()
                            .zip(intent)
                            .map(|(s, i)| close(s[0], i[0]) && close(s[1], i[1])),
                    );
                }
            }
            let start = RowStart {
                level,
                colours,
                cursor,
                origin_col: self.origin.0,
                row,
            };
            let spans = self
                .planner
                .plan(&start, intent, &self.skippable, self.opts.beam);
            for span in spans {
                if span.choice == Choice::Skip {
                    continue;
                }
                let (x, len) = (usize::from(span.x), usize::from(span.len));
                let cell = intent[x];
                let at = (self.origin.0, row);
                write_span(
                    &mut self.out,
                    level,
                    span,
                    cell,
                    at,
                    &mut colours,
                    &mut cursor,
                );
                self.shown[y * w + x..y * w + x + len].fill(cell);
                drew = true;
            }
        }
        if !drew {
            self.out.clear();
            return;
        }
        self.fresh = false;
        sgr::write(&mut self.out, level, colours, (DEFAULT, DEFAULT));
        if self.opts.sync {
            self.out.extend_from_slice(SYNC_END);
        }
    }

    /// Mono: ASCII characters and cursor moves only; short unchanged gaps are rewritten, not skipped.
    fn encode_mono(&mut self) {
        let w = self.cols;
        let mut cursor = Cursor::Unknown;
        for y in 0..self.rows {
            let row = self.origin.1 + y as u16;
            // The column the cursor is on within this row, if it is on this row.
            let mut at: Option<usize> = None;
            for x in 0..w {
                let i = y * w + x;
                if self.shown[i] == self.intent[i] {
                    continue;
                }
                let col = self.origin.0 + x as u16;
                match at {
                    Some(c) if c < x && x - c <= 3 => {
                        // Rewriting the gap costs its length; a move costs at least three bytes.
                        for g in c..x {
                            self.out.push(self.intent[y * w + g][0] as u8);
                            self.shown[y * w + g] = self.intent[y * w + g];
                        }
                    }
                    Some(c) if c == x => {}
                    _ => write_move(&mut self.out, cursor, col, row),
                }
                self.out.push(self.intent[i][0] as u8);
                self.shown[i] = self.intent[i];
                at = Some(x + 1);
                cursor = Cursor::At { col: col + 1, row };
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    fn fb(cols: u16, rows: u16, f: impl Fn(usize, usize) -> Rgb) -> Framebuffer {
        let mut fb = Framebuffer::for_cells(cols, rows);
        for y in 0..fb.height() {
            for x in 0..fb.width() {
                fb.set(x, y, f(x, y));
            }
        }
        fb
    }

    #[test]
    fn an_unchanged_frame_sends_nothing_and_invalidate_resends_everything() {
        let frame = fb(8, 3, |x, y| Rgb::new(x as u8 * 30, y as u8 * 40, 7));
        let mut e = Encoder::new(EncodeOptions::default());
        let first = e.encode(&frame, 0, 0).to_vec();
        assert!(first.starts_with(SYNC_BEGIN) && first.ends_with(SYNC_END));
        assert!(e.encode(&frame, 0, 0).is_empty());
        e.invalidate();
        assert_eq!(e.encode(&frame, 0, 0), first.as_slice());
    }

    #[test]
    fn one_changed_cell_costs_a_move_a_colour_and_a_glyph() {
        let mut frame = fb(10, 4, |_, _| Rgb::new(10, 20, 30));
        let mut e = Encoder::new(EncodeOptions::new(ColorLevel::Ansi256));
        e.encode(&frame, 2, 1);
        frame.set(5, 5, Rgb::new(255, 0, 0));
        let bytes = String::from_utf8(e.encode(&frame, 2, 1).to_vec()).unwrap();
        assert!(bytes.starts_with("\x1b[?2026h\x1b[4;8H\x1b["), "{bytes:?}");
        assert!(
            bytes.ends_with("m▄\x1b[m\x1b[?2026l") || bytes.ends_with("m▀\x1b[m\x1b[?2026l"),
            "{bytes:?}"
        );
        assert!(bytes.contains("5;196"), "{bytes:?}");
        assert_eq!(bytes.matches('\x1b').count(), 5, "{bytes:?}");
    }

    #[test]
    fn mono_sends_only_ascii_and_moves() {
        let mut frame = fb(6, 2, |x, _| {
            Rgb::new(x as u8 * 50, x as u8 * 50, x as u8 * 50)
        });
        let mut e = Encoder::new(EncodeOptions::new(ColorLevel::Mono));
        let first = e.encode(&frame, 0, 0).to_vec();
        assert!(first.is_ascii());
        frame.set(5, 2, Rgb::default());
        frame.set(5, 3, Rgb::default());
        assert_eq!(e.encode(&frame, 0, 0), b"\x1b[2;6H ");
    }
}
