//! One way to put a frame on a terminal: ratatui's cell diff for the panes (written as
//! [`crate::LeanBackend`] writes it), halfcast's encoder for the 3D view (the shortcut: pixels
//! straight to bytes, with the glyph choice per cell), one synchronized update. The TUI, replays
//! and the SSH server all use it.
//!
//! Anything drawn over the view must stay on top, but the encoder paints the whole view region.
//! - A few cells (a game message's banner, at most two rows' worth): the encoder sends the view
//!   with those cells painted in their own colours (so it resends the scene once they go), and
//!   the cells themselves follow its bytes in every frame the encoder writes to or the cells
//!   change in. The view keeps the encoder's bytes and look while a message shows.
//! - More (the help box, the results): while the screen buffer shows them, the view goes through
//!   the cell diff like the panes (around the overlay), and the encoder starts afresh once the
//!   overlay is gone.

use ratatui::buffer::{Buffer, Cell, CellDiffOption};
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier};

use crate::color::Rgb;
use crate::encode::cell_diff::cell_diff;
use crate::encode::cells::CellWriter;
use crate::encode::glyph_cell::GlyphCell;
use crate::encode::glyph_frame::glyph_cells;
use crate::encode::{ColorLevel, EncodeOptions, Encoder, SYNC_BEGIN, SYNC_END};
use crate::render::framebuffer::Framebuffer;
use crate::render::glyphs::Glyphs;
use crate::termframe::ratatui_rgb;
use crate::widget::half_block::{is_view_cell, row_cells, to_color, UPPER_HALF};

/// Turns whole screens into the bytes that update a terminal from the previous screen.
#[derive(Debug)]
pub struct Presenter {
    encoder: Encoder,
    cells: CellWriter,
    previous: Option<Buffer>,
    out: Vec<u8>,
    /// Whether the last frame had an overlay over the view (drawn without the encoder).
    overlaid: bool,
    /// The few cells drawn after the encoder's bytes last frame (a banner).
    over: Vec<(u16, u16)>,
    /// The view with a few cells painted over (see the module notes); reused between frames.
    painted: Framebuffer,
    /// The view's cells at a finer glyph setting, chosen once a frame: checked against the
    /// screen for overlays, then handed to the encoder.
    chosen: Vec<GlyphCell>,
}

/// The most cells over the view, in rows of the view's width, that still go after the
/// encoder's bytes (a banner); more switch the view to the cell diff.
const FEW_ROWS: usize = 2;

impl Presenter {
    /// A presenter for a terminal that shows nothing known yet (the first frame redraws all).
    #[must_use]
    pub fn new(mut opts: EncodeOptions) -> Self {
        opts.sync = false;
        Self {
            encoder: Encoder::new(opts),
            // The panes' half blocks (the minimap) keep their `▀`: the game's recorded screens
            // are pinned glyph by glyph (tests/snapshots/replay_pty__*.snap).
            cells: CellWriter::new(opts.level).keeping_half_blocks(),
            previous: None,
            out: Vec::new(),
            overlaid: false,
            over: Vec::new(),
            painted: Framebuffer::new(0, 0),
            chosen: Vec::new(),
        }
    }

    /// The colour level frames are sent at.
    #[must_use]
    pub fn level(&self) -> ColorLevel {
        self.encoder.options().level
    }

    /// Forgets the terminal's contents: the next frame clears and redraws everything.
    pub fn invalidate(&mut self) {
        self.previous = None;
        self.encoder.invalidate();
    }

    /// Switches colour level (a full redraw follows).
    pub fn set_level(&mut self, level: ColorLevel) {
        let mut opts = *self.encoder.options();
        opts.level = level;
        *self = Self::new(opts);
    }

    /// The bytes for one frame: `screen` holds the panes (the view's cells are ignored),
    /// `view` the 3D view's pixels shown at `view_area` (empty area = no view).
    /// Cells of the view area that show something else (an overlay) are drawn on top of it.
    pub fn frame(&mut self, screen: &Buffer, view: &Framebuffer, view_area: Rect) -> &[u8] {
        let mut next = screen.clone();
        self.frame_taking(&mut next, view, view_area)
    }

    /// [`Presenter::frame`] without copying the screen: `screen` is kept as the terminal's
    /// contents for the next frame's diff, and swapped for a buffer to draw the next screen into
    /// (the one kept last frame, or an empty one; its contents are left over, reset it).
    pub fn frame_taking(
        &mut self,
        screen: &mut Buffer,
        view: &Framebuffer,
        view_area: Rect,
    ) -> &[u8] {
        let mut next = std::mem::take(screen);
        let area = next.area;
        let wire = Wire::at(self.level());
        let view_area = view_area.intersection(area);
        let path = self.view_path(&next, view, view_area);
        let overlaid = matches!(path, ViewPath::CellDiff);
        if overlaid != self.overlaid {
            // The terminal holds the other path's drawing: start both afresh.
            self.previous = None;
            self.overlaid = overlaid;
        }
        match path {
            ViewPath::CellDiff => self.view_as_cells(&mut next, view, view_area, wire),
            ViewPath::Encoder { skipped: true, .. } => {}
            // The encoder draws the view: the cell diff skips all of it (a row at a time).
            _ => skip_view(&mut next, view_area),
        }
        wire.plain(&mut next);
        self.out.clear();
        wire.begin(&mut self.out);
        let previous = self.previous_or_cleared(area, wire);
        let diff = cell_diff(&previous, &next);
        if !diff.is_empty() {
            self.cells.forget_cursor();
            self.cells.draw(&mut self.out, diff.into_iter());
        }
        self.over = match path {
            ViewPath::Encoder { over, .. } => {
                // The cells over the view are on the terminal as they are now when they were
                // drawn last frame too and nothing has been written over them since.
                let over_kept = over == self.over
                    && over.iter().all(|&(x, y)| previous[(x, y)] == next[(x, y)]);
                self.encode_view(view, view_area, &next, &over, over_kept);
                over
            }
            _ => Vec::new(),
        };
        *screen = previous;
        wire.end(&mut self.out);
        self.previous = Some(next);
        &self.out
    }

    /// Which way this frame's view goes, the cells chosen for it at a finer glyph setting.
    fn view_path(&mut self, next: &Buffer, view: &Framebuffer, view_area: Rect) -> ViewPath {
        self.chosen.clear();
        let usable = view_area.area() > 0 && view.cell_cols() == usize::from(view_area.width);
        if !usable {
            // No view this frame: the cell diff writes over where it was, so the next view is
            // sent whole.
            self.encoder.invalidate();
            return ViewPath::Absent;
        }
        // The view's cells at a finer setting, chosen once here when anything needs them: the
        // truecolor encoder, or a view area holding more than VIEW_CELL (a view drawn by the
        // caller, to tell from what is drawn over it, or overlays, which may send the view
        // through the cell diff). Where the palette mixes, the encoder works from the pixels.
        if view.glyphs() != Glyphs::Half
            && (self.level() == ColorLevel::TrueColor
                || view_area.positions().any(|p| !is_view_cell(&next[p])))
        {
            glyph_cells(view, &mut self.chosen);
        }
        let (over, skipped) = covering(next, view, &self.chosen, view_area);
        if over.len() <= usize::from(view_area.width) * FEW_ROWS {
            ViewPath::Encoder { over, skipped }
        } else {
            ViewPath::CellDiff
        }
    }

    /// The view area sent through the cell diff: the view's own cells as `HalfBlockView` draws
    /// them, and what was drawn over them (which may have kept their skip mark) sent too.
    fn view_as_cells(&self, next: &mut Buffer, view: &Framebuffer, view_area: Rect, wire: Wire) {
        for y in view_area.top()..view_area.bottom() {
            for x in view_area.left()..view_area.right() {
                let (cx, cy) = (usize::from(x - view_area.x), usize::from(y - view_area.y));
                let Some(c) = next.cell_mut((x, y)) else {
                    continue;
                };
                if is_view_cell(c) {
                    *c = Cell::EMPTY;
                    if cy < view.cell_rows() {
                        let (ch, fg, bg) = view_look(view, &self.chosen, (cx, cy));
                        c.set_char(ch).set_fg(fg).set_bg(bg);
                    }
                } else {
                    c.set_diff_option(CellDiffOption::None);
                }
                if wire.mono && c.symbol() == UPPER_HALF && cy < view.cell_rows() {
                    let (top, bottom) = view.cell(cx, cy);
                    c.set_char(crate::encode::quantize::mono_char(top, bottom));
                }
            }
        }
    }

    /// The screen the terminal shows, to diff against: last frame's, or after a clear (which is
    /// sent) a blank one.
    fn previous_or_cleared(&mut self, area: Rect, wire: Wire) -> Buffer {
        match self.previous.take() {
            Some(p) if p.area == area => p,
            _ => {
                wire.clear(&mut self.out);
                self.encoder.invalidate();
                let mut blank = Buffer::empty(area);
                // Cells that differ from a cleared screen are all that must be drawn.
                blank.reset();
                blank
            }
        }
    }

    /// The encoder's bytes for the view, then the `over` cells drawn over it (a banner) when the
    /// encoder wrote or they are not on the terminal as they are (`over_kept`).
    fn encode_view(
        &mut self,
        view: &Framebuffer,
        view_area: Rect,
        next: &Buffer,
        over: &[(u16, u16)],
        over_kept: bool,
    ) {
        let shown = if over.is_empty() {
            view
        } else {
            // The covered cells in their own colours: what the encoder believes the terminal
            // shows there (they are written over it right after).
            self.painted.clone_from(view);
            for &(x, y) in over {
                // Its colours: `next` differs from the screen drawn only in diff options and,
                // at mono, symbols and modifiers.
                let c = &next[(x, y)];
                let (cx, cy) = (usize::from(x - view_area.x), usize::from(y - view_area.y));
                let top = ratatui_rgb(c.fg).unwrap_or(Rgb::new(0, 0, 0));
                let bottom = ratatui_rgb(c.bg).unwrap_or(Rgb::new(0, 0, 0));
                // The cell's upper pixels in its fg, lower in its bg (at any sub-grid).
                let (w, h) = view.glyphs().cell_size();
                for dy in 0..h {
                    let c = if 2 * dy < h { top } else { bottom };
                    for dx in 0..w {
                        self.painted.set(cx * w + dx, cy * h + dy, c);
                    }
                }
            }
            &self.painted
        };
        let bytes = if over.is_empty() && !self.chosen.is_empty() {
            self.encoder
                .encode_chosen(view, &self.chosen, view_area.x, view_area.y)
        } else {
            self.encoder.encode(shown, view_area.x, view_area.y)
        };
        let encoded = !bytes.is_empty();
        self.out.extend_from_slice(bytes);
        if !over.is_empty() && (encoded || !over_kept) {
            // After the encoder's bytes, which end with the default colours (the cell writer's
            // plain pen) but leave the cursor anywhere.
            self.cells.forget_cursor();
            self.cells.draw(
                &mut self.out,
                over.iter().map(|&(x, y)| (x, y, &next[(x, y)])),
            );
        }
    }
}

/// Which way a frame's view reaches the terminal.
enum ViewPath {
    /// No view this frame (no area, or a view of another width).
    Absent,
    /// The encoder sends the view; the few cells drawn `over` it (a banner, or none) follow its
    /// bytes. `skipped`: every cell of the view area is already skipped by the cell diff.
    Encoder {
        over: Vec<(u16, u16)>,
        skipped: bool,
    },
    /// An overlay covers more than a few rows of it: the view goes through the cell diff, around
    /// the overlay.
    CellDiff,
}

/// What the colour level changes in a frame's bytes besides its colours: mono sends plain
/// ASCII and no escape it does not need (no synchronized update, no colour reset).
#[derive(Clone, Copy)]
struct Wire {
    mono: bool,
}

impl Wire {
    fn at(level: ColorLevel) -> Self {
        Self {
            mono: level == ColorLevel::Mono,
        }
    }

    /// Starts the frame's synchronized update.
    fn begin(self, out: &mut Vec<u8>) {
        if !self.mono {
            out.extend_from_slice(SYNC_BEGIN);
        }
    }

    /// Ends the frame's synchronized update.
    fn end(self, out: &mut Vec<u8>) {
        if !self.mono {
            out.extend_from_slice(SYNC_END);
        }
    }

    /// Clears the screen (mono output carries no SGR at all: its colours are always the
    /// defaults).
    fn clear(self, out: &mut Vec<u8>) {
        if !self.mono {
            out.extend_from_slice(b"\x1b[m");
        }
        out.extend_from_slice(b"\x1b[2J");
    }

    /// The screen's cells as this level shows them.
    fn plain(self, buf: &mut Buffer) {
        if self.mono {
            plain_ascii(buf);
        }
    }
}

/// Marks the view area skipped by the cell diff (the encoder draws it), a row at a time.
fn skip_view(next: &mut Buffer, view_area: Rect) {
    let area = next.area;
    for y in view_area.top()..view_area.bottom() {
        for c in &mut next.content[row_cells(area, view_area, y)] {
            c.set_diff_option(CellDiffOption::Skip);
        }
    }
}

/// Cell `at` of the view as [`crate::widget::HalfBlockView`] draws it in 24-bit colour: its
/// character, foreground and background (`▀` over two pixels, or at a finer glyph setting its
/// `chosen` cell's glyph). What the cell diff sends for the view, and what tells a view drawn
/// by the caller from what is drawn over it.
fn view_look(view: &Framebuffer, chosen: &[GlyphCell], at: (usize, usize)) -> (char, Color, Color) {
    let (cx, cy) = at;
    match chosen.get(cy * view.cell_cols() + cx) {
        Some(g) => (
            crate::encode::glyph_mask::glyph(view.glyphs(), g.mask),
            to_color(g.fg),
            to_color(g.bg),
        ),
        None => {
            let (top, bottom) = view.cell(cx, cy);
            ('▀', to_color(top), to_color(bottom))
        }
    }
}

/// Mono shows plain ASCII: no attributes, and line-drawing symbols as `|`, `-`, `+`…
/// (colours are dropped by the cell writer at mono).
fn plain_ascii(buf: &mut Buffer) {
    for cell in buf.content.iter_mut() {
        cell.modifier = Modifier::empty();
        if !cell.symbol().is_ascii() {
            let ascii = match cell.symbol() {
                "│" | "┃" | "║" => "|",
                "─" | "━" | "═" => "-",
                "╭" | "╮" | "╰" | "╯" | "┌" | "┐" | "└" | "┘" | "┼" | "├" | "┤" | "┬" | "┴" => {
                    "+"
                }
                "←" => "<",
                "→" => ">",
                "↑" => "^",
                "↓" => "v",
                "·" | "…" => ".",
                "×" => "x",
                "°" => "o",
                _ => "#",
            };
            cell.set_symbol(ascii);
        }
    }
}

/// The cells drawn over the view, row by row: cells of the view area that are neither the
/// view's own cell (`▀`, or at a finer glyph setting its `chosen` cell) nor left empty (callers
/// may leave the view's cells blank); and whether every cell of the view area is already
/// skipped by the cell diff (as [`VIEW_CELL`](crate::widget::half_block::VIEW_CELL) is, and what
/// is drawn over it keeps), read in the same pass so the view's cells need no second one to be
/// marked.
fn covering(
    screen: &Buffer,
    view: &Framebuffer,
    chosen: &[GlyphCell],
    at: Rect,
) -> (Vec<(u16, u16)>, bool) {
    let rows = usize::from(at.height).min(view.cell_rows());
    let blank = ratatui::buffer::Cell::default();
    let mut out = Vec::new();
    // Rows of the area below the view's own rows are only read for their marks.
    let skipped = (at.y + rows as u16..at.bottom()).all(|y| {
        screen.content[row_cells(screen.area, at, y)]
            .iter()
            .all(|c| c.diff_option == CellDiffOption::Skip)
    });
    let mut skipped_too = true;
    for cy in 0..rows {
        let y = at.y + cy as u16;
        for (cx, c) in screen.content[row_cells(screen.area, at, y)]
            .iter()
            .enumerate()
        {
            let x = at.x + cx as u16;
            skipped_too &= c.diff_option == CellDiffOption::Skip;
            let is_view = is_view_cell(c) || {
                let (ch, fg, bg) = view_look(view, chosen, (cx, cy));
                c.symbol() == ch.encode_utf8(&mut [0u8; 4]) && c.fg == fg && c.bg == bg
            };
            if !is_view && *c != blank {
                out.push((x, y));
            }
        }
    }
    (out, skipped && skipped_too)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use crate::termframe::{appearance, from_screen, FramePixels, TermFrame};
    use crate::widget::half_block::VIEW_CELL;
    use ratatui::style::{Color, Style};
    use ratatui::widgets::Widget;

    fn screen(text: &str) -> Buffer {
        let mut b = Buffer::empty(Rect::new(0, 0, 20, 6));
        b.set_string(
            0,
            5,
            text,
            Style::new()
                .fg(Color::Rgb(200, 100, 50))
                .bg(Color::Rgb(10, 10, 30)),
        );
        b
    }

    fn view(shade: u8) -> Framebuffer {
        let mut fb = Framebuffer::new(10, 8);
        for y in 0..8 {
            for x in 0..10 {
                fb.set(
                    x,
                    y,
                    Rgb::new(shade.wrapping_add((x * 20) as u8), (y * 30) as u8, 90),
                );
            }
        }
        fb
    }

    /// What a person should see: the panes, with the view's half-blocks at its area.
    fn intended(screen: &Buffer, view: &Framebuffer, at: Rect) -> TermFrame {
        let mut f = TermFrame::from_buffer(screen);
        let v = TermFrame::from_framebuffer(view);
        for y in 0..usize::from(at.height) {
            for x in 0..usize::from(at.width) {
                f.cells[(y + usize::from(at.y)) * f.cols + x + usize::from(at.x)] =
                    v.cell(x, y).clone();
            }
        }
        f
    }

    /// Asserts that every cell of the 20×6 test screen `seen` (frame `i`) looks as `want`'s.
    fn same_screen(seen: &TermFrame, want: &TermFrame, i: usize) {
        for y in 0..6 {
            for x in 0..20 {
                assert_eq!(
                    appearance(seen.cell(x, y)),
                    appearance(want.cell(x, y)),
                    "frame {i} cell ({x},{y})"
                );
            }
        }
    }

    #[test]
    fn a_sequence_of_frames_reaches_the_screen_exactly() {
        let mut p = Presenter::new(EncodeOptions::new(ColorLevel::TrueColor));
        let at = Rect::new(3, 1, 10, 4);
        let mut term = vt100::Parser::new(6, 20, 0);
        for (i, text) in ["status one", "status two", "status two", "three"]
            .iter()
            .enumerate()
        {
            let (s, v) = (screen(text), view(i as u8 * 40));
            let bytes = p.frame(&s, &v, at).to_vec();
            assert!(bytes.starts_with(SYNC_BEGIN) && bytes.ends_with(SYNC_END));
            term.process(&bytes);
            let seen = from_screen(term.screen(), 20, 6);
            let want = intended(&s, &v, at);
            same_screen(&seen, &want, i);
        }
    }

    #[test]
    fn frames_taking_the_screen_send_the_same_bytes_as_frames_copying_it() {
        // The serve loop's way: draw into the buffer handed back, reset, every frame; through
        // plain frames, a banner, a box over the view, a new size and back.
        for level in [ColorLevel::TrueColor, ColorLevel::Ansi256, ColorLevel::Mono] {
            let (mut copying, mut taking) = (
                Presenter::new(EncodeOptions::new(level)),
                Presenter::new(EncodeOptions::new(level)),
            );
            let at = Rect::new(3, 1, 10, 4);
            let mut spare = Buffer::empty(Rect::default());
            for i in 0..8u8 {
                let v = view(i * 30);
                let mut want = with_view(&format!("frame {i}"), &v, at);
                match i {
                    2 => want.set_string(5, 2, "HI", Style::new()),
                    3 | 4 => {
                        for y in 1..4 {
                            want.set_string(3, y, "==========", Style::new());
                        }
                    }
                    5 => want.resize(Rect::new(0, 0, 20, 5)),
                    _ => {}
                }
                let copied = copying.frame(&want, &v, at).to_vec();
                if spare.area == want.area {
                    spare.reset();
                } else {
                    spare = Buffer::empty(want.area);
                }
                spare.content.clone_from_slice(&want.content);
                let taken = taking.frame_taking(&mut spare, &v, at).to_vec();
                assert_eq!(copied, taken, "{level:?} frame {i}");
            }
        }
    }

    /// The panes of [`screen`] with the view's half-blocks drawn at `at`, as `draw` does.
    fn with_view(text: &str, v: &Framebuffer, at: Rect) -> Buffer {
        let mut b = screen(text);
        crate::widget::HalfBlockView::new(v).render(at, &mut b);
        b
    }

    #[test]
    fn an_overlay_over_the_view_stays_visible_and_the_view_returns_after_it() {
        // A banner (a few cells, sent after the encoder) and a box of three rows (more than
        // FEW_ROWS: the view goes through the cell diff meanwhile).
        for (level, tall) in [ColorLevel::TrueColor, ColorLevel::Ansi256, ColorLevel::Mono]
            .into_iter()
            .flat_map(|l| [(l, false), (l, true)])
        {
            let mut p = Presenter::new(EncodeOptions::new(level));
            let at = Rect::new(3, 1, 10, 4);
            let mut term = vt100::Parser::new(6, 20, 0);
            let v = view(40);
            term.process(p.frame(&with_view("s", &v, at), &v, at));
            for shade in [40u8, 80] {
                let v = view(shade);
                let mut b = with_view("s", &v, at);
                b.set_string(5, 2, "HELP", Style::new());
                if tall {
                    for y in [1, 3] {
                        b.set_string(3, y, "==========", Style::new());
                    }
                }
                term.process(p.frame(&b, &v, at));
                let row: Vec<char> = (0..20)
                    .map(|x| {
                        term.screen()
                            .cell(2, x)
                            .map_or(' ', |c| c.contents().chars().next().unwrap_or(' '))
                    })
                    .collect();
                assert_eq!(
                    row[5..9].iter().collect::<String>(),
                    "HELP",
                    "{level:?} shade {shade}: {row:?}"
                );
            }
            let v = view(120);
            term.process(p.frame(&with_view("s", &v, at), &v, at));
            let seen = from_screen(term.screen(), 20, 6);
            let want = TermFrame::from_framebuffer(&v);
            for x in 0..10 {
                let cell = seen.cell(x + 3, 1);
                if level == ColorLevel::Mono {
                    let (t, b) = v.cell(x, 0);
                    assert_eq!(
                        cell.glyph,
                        crate::encode::quantize::mono_char(t, b),
                        "{level:?}"
                    );
                } else if level == ColorLevel::TrueColor {
                    assert_eq!(
                        appearance(cell),
                        appearance(want.cell(x, 0)),
                        "{level:?} {x}"
                    );
                } else {
                    assert!(
                        matches!(cell.glyph.first_char(), '▀' | '▄' | ' ' | '█'),
                        "{level:?} {cell:?}"
                    );
                }
            }
        }
    }

    /// The player's view under a game message: one row of text on the top row.
    fn with_banner(v: &Framebuffer, at: Rect) -> Buffer {
        let mut b = with_view("s", v, at);
        let style = Style::new()
            .fg(Color::Rgb(255, 226, 140))
            .bg(Color::Rgb(22, 24, 32));
        b.set_string(at.x + 1, at.y, " got it ", style);
        b
    }

    #[test]
    fn a_banner_over_a_still_view_is_sent_once_and_again_when_it_changes() {
        for level in [ColorLevel::TrueColor, ColorLevel::Ansi256, ColorLevel::Mono] {
            let at = Rect::new(3, 1, 10, 4);
            let mut p = Presenter::new(EncodeOptions::new(level));
            let mut term = vt100::Parser::new(6, 20, 0);
            let v = view(60);
            let banner = with_banner(&v, at);
            term.process(p.frame(&with_view("s", &v, at), &v, at));
            term.process(p.frame(&banner, &v, at));
            let nothing: &[u8] = if level == ColorLevel::Mono {
                b""
            } else {
                &[SYNC_BEGIN, SYNC_END].concat()
            };
            assert_eq!(p.frame(&banner, &v, at), nothing, "{level:?}");
            // Another text in the same cells, and the same banner over a changed view.
            let mut other = banner.clone();
            other.set_string(5, 1, "GOT", Style::new());
            for (b, v) in [(&other, view(60)), (&other, view(90))] {
                let bytes = p.frame(b, &v, at).to_vec();
                assert_ne!(bytes, nothing, "{level:?}");
                term.process(&bytes);
                let seen = from_screen(term.screen(), 20, 6);
                let top: String = (0..10)
                    .map(|x| seen.cell(x + 3, 1).glyph.as_str())
                    .collect();
                assert!(top.contains("GOT"), "{level:?}: {top}");
            }
        }
    }

    #[test]
    fn a_banner_over_a_moving_view_keeps_the_encoder_and_is_on_the_screen_every_frame() {
        for level in [ColorLevel::TrueColor, ColorLevel::Ansi256, ColorLevel::Mono] {
            let at = Rect::new(3, 1, 10, 4);
            let (mut with, mut without) = (
                Presenter::new(EncodeOptions::new(level)),
                Presenter::new(EncodeOptions::new(level)),
            );
            let mut term = vt100::Parser::new(6, 20, 0);
            let v = view(0);
            let _ = without.frame(&with_view("s", &v, at), &v, at);
            term.process(with.frame(&with_view("s", &v, at), &v, at));
            let (mut bytes_with, mut bytes_without) = (0, 0);
            // The banner comes, stays while the view changes under it, then goes.
            for (i, shown) in [true, true, true, true, false, false]
                .into_iter()
                .enumerate()
            {
                let v = view(30 * (i as u8 + 1));
                let b = if shown {
                    with_banner(&v, at)
                } else {
                    with_view("s", &v, at)
                };
                let bytes = with.frame(&b, &v, at).to_vec();
                // No full redraw to come or go: the view stays on the encoder's path.
                assert!(!contains(&bytes, b"\x1b[2J"), "{level:?} frame {i}");
                term.process(&bytes);
                bytes_with += bytes.len();
                bytes_without += without.frame(&with_view("s", &v, at), &v, at).len();
                let seen = from_screen(term.screen(), 20, 6);
                let top: String = (0..10)
                    .map(|x| seen.cell(x + 3, 1).glyph.as_str())
                    .collect();
                if shown {
                    assert!(top.contains(" got it "), "{level:?} frame {i}: {top}");
                } else {
                    assert!(!top.contains("got"), "{level:?} frame {i}: {top}");
                }
                if level == ColorLevel::TrueColor {
                    let want = if shown {
                        TermFrame::from_buffer(&b)
                    } else {
                        intended(&b, &v, at)
                    };
                    same_screen(&seen, &want, i);
                }
            }
            // What the banner costs: its own cells each frame, and the scene under it once.
            assert!(
                bytes_with < bytes_without + 6 * 40 + 4 * 8 * 40,
                "{level:?}: {bytes_with} bytes with the banner, {bytes_without} without"
            );
        }
    }

    #[test]
    fn a_screen_left_for_the_presenter_sends_the_bytes_of_one_with_the_view_drawn() {
        // The game draws its screens with the view's cells left as VIEW_CELL (so they are chosen
        // once, here); replays draw the view itself. Both must reach the terminal alike: plain,
        // under a banner (sent after the encoder), under a box (the cell diff), and through a
        // cleared box that stays blank. (Text that sets no colour of its own would keep the view's
        // colours under it where the view is drawn; the game's overlays clear or colour theirs.)
        let at = Rect::new(3, 1, 10, 4);
        let overlays: [fn(&mut Buffer); 4] = [
            |_| {},
            |b| {
                let banner = Style::new()
                    .fg(Color::Rgb(255, 226, 140))
                    .bg(Color::Rgb(22, 24, 32));
                b.set_string(4, 1, " got it ", banner);
            },
            |b| {
                let boxed = Style::new().fg(Color::White).bg(Color::Rgb(22, 24, 32));
                for y in 1..4 {
                    b.set_string(3, y, "====HELP==", boxed);
                }
            },
            |b| {
                ratatui::widgets::Clear.render(Rect::new(4, 1, 8, 3), b);
                b.set_string(5, 2, "box", Style::new());
            },
        ];
        for level in [ColorLevel::TrueColor, ColorLevel::Ansi256, ColorLevel::Mono] {
            for glyphs in [Glyphs::Half, Glyphs::Quadrant, Glyphs::Octant] {
                let (mut drawn, mut left) = (
                    Presenter::new(EncodeOptions::new(level)),
                    Presenter::new(EncodeOptions::new(level)),
                );
                for (i, overlay) in overlays.iter().chain(&overlays).enumerate() {
                    let mut v = Framebuffer::for_glyphs(at.width, at.height, glyphs);
                    for y in 0..v.height() {
                        for x in 0..v.width() {
                            let c = (x * 23 + y * 41 + i * 17) as u8;
                            v.set(x, y, Rgb::new(c, c.wrapping_mul(3), 90 + (x % 3) as u8));
                        }
                    }
                    let mut with = screen("s");
                    crate::widget::HalfBlockView::new(&v).render(at, &mut with);
                    let mut without = screen("s");
                    for p in at.positions() {
                        without[p] = VIEW_CELL;
                    }
                    overlay(&mut with);
                    overlay(&mut without);
                    assert_eq!(
                        String::from_utf8_lossy(left.frame(&without, &v, at)),
                        String::from_utf8_lossy(drawn.frame(&with, &v, at)),
                        "{level:?} {glyphs:?} frame {i}"
                    );
                }
            }
        }
    }

    fn contains(hay: &[u8], needle: &[u8]) -> bool {
        hay.windows(needle.len()).any(|w| w == needle)
    }

    #[test]
    fn an_unchanged_frame_sends_only_the_sync_markers() {
        let mut p = Presenter::new(EncodeOptions::new(ColorLevel::TrueColor));
        let at = Rect::new(0, 0, 10, 4);
        let _ = p.frame(&screen("x"), &view(1), at);
        let again = p.frame(&screen("x"), &view(1), at).to_vec();
        assert_eq!(again, [SYNC_BEGIN, SYNC_END].concat());
    }

    #[test]
    fn mono_frames_have_no_colour_sequences() {
        let mut p = Presenter::new(EncodeOptions::new(ColorLevel::Mono));
        let bytes = p
            .frame(&screen("╭─ mono"), &view(3), Rect::new(0, 0, 10, 4))
            .to_vec();
        let text = String::from_utf8(bytes).unwrap();
        assert!(text.is_ascii(), "{text:?}");
        for seq in text.split('\x1b').skip(1) {
            let fin = seq.bytes().skip(1).find(|b| (0x40..=0x7e).contains(b));
            assert!(
                seq.starts_with('[') && matches!(fin, Some(b'H' | b'J' | b'C')),
                "{seq:?} in {text:?}"
            );
        }
        assert!(text.contains("+-") && text.contains("mono"), "{text:?}");
    }

    #[test]
    fn mono_view_lands_at_its_origin() {
        let mut p = Presenter::new(EncodeOptions::new(ColorLevel::Mono));
        let at = Rect::new(3, 1, 10, 4);
        let mut term = vt100::Parser::new(6, 20, 0);
        for shade in [0u8, 90, 180] {
            let v = view(shade);
            term.process(p.frame(&screen("m"), &v, at));
            let seen = from_screen(term.screen(), 20, 6);
            for y in 0..4 {
                for x in 0..10 {
                    let (top, bottom) = v.cell(x, y);
                    let want = crate::encode::quantize::mono_char(top, bottom);
                    assert_eq!(
                        seen.cell(x + 3, y + 1).glyph,
                        want,
                        "shade {shade} cell ({x},{y})"
                    );
                }
            }
            assert_eq!(seen.cell(0, 5).glyph, 'm');
        }
    }
}
