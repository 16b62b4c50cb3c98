//! Writes ratatui cells (a buffer diff) the lean way: one merged SGR per change, the cheapest
//! cursor move, colours mapped down the ladder. [`crate::LeanBackend`] and
//! [`crate::present::Presenter`] both draw through it.

use ratatui::buffer::Cell;
use ratatui::style::{Color, Modifier};
use unicode_width::UnicodeWidthStr;

use super::cursor::{write_move, Cursor};
use super::level::ColorLevel;
use super::palette::{xterm_rgb, Code, Palette, DEFAULT, UNKNOWN};
use super::plan::{write_span, RowPlanner, RowStart, DEFAULT_BEAM};
use super::sgr;
use crate::color::Rgb;

/// A colour as it is written: the SGR form (`kind`) and its code in that form.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Paint {
    kind: ColorLevel,
    code: Code,
}

/// The terminal's default colour.
const RESET: Paint = Paint {
    kind: ColorLevel::Mono,
    code: DEFAULT,
};

/// What the terminal draws the next glyph with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Pen {
    fg: Paint,
    bg: Paint,
    /// The underline colour (`RESET`: the foreground's).
    ul: Paint,
    modifier: Modifier,
}

/// The pen after `ESC[m`.
const PLAIN: Pen = Pen {
    fg: RESET,
    bg: RESET,
    ul: RESET,
    modifier: Modifier::empty(),
};

/// Each attribute's SGR parameter to set it, in the order they are written.
const ATTRS: [(Modifier, u8); 9] = [
    (Modifier::BOLD, 1),
    (Modifier::DIM, 2),
    (Modifier::ITALIC, 3),
    (Modifier::UNDERLINED, 4),
    (Modifier::SLOW_BLINK, 5),
    (Modifier::RAPID_BLINK, 6),
    (Modifier::REVERSED, 7),
    (Modifier::HIDDEN, 8),
    (Modifier::CROSSED_OUT, 9),
];

/// The parameters that switch attributes off, and what each switches off (22 ends bold and dim
/// together, 25 both blinks).
const ATTRS_OFF: [(Modifier, u8); 7] = [
    (Modifier::BOLD.union(Modifier::DIM), 22),
    (Modifier::ITALIC, 23),
    (Modifier::UNDERLINED, 24),
    (Modifier::SLOW_BLINK.union(Modifier::RAPID_BLINK), 25),
    (Modifier::REVERSED, 27),
    (Modifier::HIDDEN, 28),
    (Modifier::CROSSED_OUT, 29),
];

/// Draws ratatui cells at one colour level, remembering the cursor and pen between calls.
#[derive(Debug)]
pub struct CellWriter {
    palette: Palette,
    cursor: Cursor,
    pen: Pen,
    /// Scratch space for choosing between two forms of one SGR change.
    scratch: (Vec<u8>, Vec<u8>),
    /// Plans runs of `▀` cells (the glyph choice that saves colour changes).
    planner: RowPlanner,
    /// A run's cells as `[top, bottom]` codes, and its skippable flags (all false).
    run: (Vec<[Code; 2]>, Vec<bool>),
    /// Whether runs of `▀` cells are planned (else each is sent as `▀`, as drawn).
    plan_half_blocks: bool,
}

/// The upper half block that half-block pictures are drawn with.
const UPPER_HALF: &str = "▀";

impl CellWriter {
    /// A writer for `level` that knows nothing of the cursor or the colours yet.
    #[must_use]
    pub fn new(level: ColorLevel) -> Self {
        Self {
            palette: Palette::new(level),
            cursor: Cursor::Unknown,
            pen: PLAIN,
            scratch: (Vec::new(), Vec::new()),
            planner: RowPlanner::default(),
            run: (Vec::new(), Vec::new()),
            plan_half_blocks: true,
        }
    }

    /// Sends every `▀` cell as drawn instead of planning runs of them (the screen looks the
    /// same either way; this keeps the glyphs too, for screens pinned glyph by glyph).
    #[must_use]
    pub fn keeping_half_blocks(mut self) -> Self {
        self.plan_half_blocks = false;
        self
    }

    /// The colour level cells are written at.
    #[must_use]
    pub fn level(&self) -> ColorLevel {
        self.palette.level()
    }

    /// Forgets where the cursor is (someone else moved it, or the screen was cleared).
    pub fn forget_cursor(&mut self) {
        self.cursor = Cursor::Unknown;
    }

    /// Moves the cursor to (col, row) the cheapest way.
    pub fn move_to(&mut self, out: &mut Vec<u8>, col: u16, row: u16) {
        write_move(out, self.cursor, col, row);
        self.cursor = Cursor::At { col, row };
    }

    /// Writes `cells` (positions and contents, as a buffer diff yields them), then returns the
    /// terminal to its default colours and attributes, as every ratatui draw ends.
    ///
    /// Runs of neighbouring `▀` cells (a half-block picture such as [`crate::HalfBlockView`]'s)
    /// go through the frame encoder's row planner: each may be sent as `▀`, or as `▄`, a space
    /// or `█` with the colours arranged to match, whichever needs fewer colour changes. The
    /// screen looks the same; the glyph may differ.
    pub fn draw<'a>(
        &mut self,
        out: &mut Vec<u8>,
        cells: impl Iterator<Item = (u16, u16, &'a Cell)>,
    ) {
        let cells: Vec<(u16, u16, &Cell)> = cells.collect();
        let mut i = 0;
        while i < cells.len() {
            let run = self.half_block_run(&cells[i..]);
            if run > 0 {
                self.draw_half_blocks(out, &cells[i..i + run]);
                i += run;
                continue;
            }
            let (x, y, cell) = cells[i];
            self.move_to(out, x, y);
            let pen = self.pen_of(cell);
            self.change_pen(out, pen);
            let symbol = cell.symbol();
            out.extend_from_slice(symbol.as_bytes());
            // A glyph one column wide advances the cursor by one (what ratatui's own backends
            // assume too); after any other width the next cell gets an absolute move.
            self.cursor = if symbol.len() == 1 || symbol.width() == 1 {
                Cursor::At { col: x + 1, row: y }
            } else {
                Cursor::Unknown
            };
            i += 1;
        }
        self.change_pen(out, PLAIN);
    }

    /// The code of a colour when it is of the level's own kind (24-bit at truecolor, a palette
    /// index at 256 or 16 colours), the only kind the row planner writes.
    fn planned_code(&self, p: Paint) -> Option<Code> {
        (p.kind == self.level() && p.kind != ColorLevel::Mono).then_some(p.code)
    }

    /// How many cells from the start of `cells` form a run of neighbouring plain `▀` cells
    /// the planner can send (0: the first cell is not one).
    fn half_block_run(&self, cells: &[(u16, u16, &Cell)]) -> usize {
        let plannable = |c: &Cell| {
            c.symbol() == UPPER_HALF
                && c.modifier.is_empty()
                && self.underline_paint(c.underline_color) == RESET
                && self.planned_code(self.paint(c.fg)).is_some()
                && self.planned_code(self.paint(c.bg)).is_some()
        };
        let Some(&(x0, y0, first)) = cells.first() else {
            return 0;
        };
        if !self.plan_half_blocks || !plannable(first) {
            return 0;
        }
        cells
            .iter()
            .enumerate()
            .take_while(|&(k, &(x, y, c))| {
                y == y0 && usize::from(x) == usize::from(x0) + k && plannable(c)
            })
            .count()
    }

    /// Sends a run of `▀` cells (one row, neighbours) as the row planner chooses.
    fn draw_half_blocks(&mut self, out: &mut Vec<u8>, run: &[(u16, u16, &Cell)]) {
        if !self.pen.modifier.is_empty() || self.pen.ul != RESET {
            self.change_pen(out, PLAIN);
        }
        let level = self.level();
        let code = |p: Paint| {
            if p == RESET {
                DEFAULT
            } else {
                self.planned_code(p).unwrap_or(UNKNOWN)
            }
        };
        let mut colours = (code(self.pen.fg), code(self.pen.bg));
        let (x0, row) = (run[0].0, run[0].1);
        let (mut codes, mut skippable) = std::mem::take(&mut self.run);
        codes.clear();
        skippable.clear();
        for &(_, _, c) in run {
            let paint = |col| self.planned_code(self.paint(col)).unwrap_or(UNKNOWN);
            codes.push([paint(c.fg), paint(c.bg)]);
            skippable.push(false);
        }
        let start = RowStart {
            level,
            colours,
            cursor: self.cursor,
            origin_col: x0,
            row,
        };
        let spans = self.planner.plan(&start, &codes, &skippable, DEFAULT_BEAM);
        for span in spans {
            let cell = codes[usize::from(span.x)];
            write_span(
                out,
                level,
                span,
                cell,
                (x0, row),
                &mut colours,
                &mut self.cursor,
            );
        }
        self.run = (codes, skippable);
        // A colour the run never set (a space keeps the foreground) is still the pen's own.
        let paint = |c: Code, before: Paint| match c {
            DEFAULT => RESET,
            UNKNOWN => before,
            c => Paint {
                kind: level,
                code: c,
            },
        };
        self.pen = Pen {
            fg: paint(colours.0, self.pen.fg),
            bg: paint(colours.1, self.pen.bg),
            ul: RESET,
            modifier: Modifier::empty(),
        };
    }

    /// How `cell` is drawn at this level.
    fn pen_of(&self, cell: &Cell) -> Pen {
        Pen {
            fg: self.paint(cell.fg),
            bg: self.paint(cell.bg),
            ul: self.underline_paint(cell.underline_color),
            modifier: cell.modifier,
        }
    }

    /// The underline colour as sent: at truecolor and 256 colours as [`Self::paint`] maps a
    /// colour (a palette index or 24-bit; SGR 58 has no short form for the 16), and not at all
    /// at 16 colours or mono, whose terminals predate coloured underlines.
    fn underline_paint(&self, c: Color) -> Paint {
        match self.level() {
            ColorLevel::TrueColor | ColorLevel::Ansi256 => self.paint(c),
            ColorLevel::Ansi16 | ColorLevel::Mono => RESET,
        }
    }

    /// A ratatui colour at this level: 24-bit colours go through the palette below truecolor,
    /// indexed ones stay indexed (the 16 ANSI colours in their short `3x`/`9x` form).
    fn paint(&self, c: Color) -> Paint {
        let level = self.level();
        let index = match c {
            Color::Reset => return RESET,
            _ if level == ColorLevel::Mono => return RESET,
            Color::Rgb(r, g, b) if level == ColorLevel::TrueColor => {
                return Paint {
                    kind: ColorLevel::TrueColor,
                    code: (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b),
                }
            }
            Color::Rgb(r, g, b) => {
                return self.palette_paint(Rgb::new(r, g, b));
            }
            Color::Indexed(n) => n,
            named => named_index(named),
        };
        if index < 16 {
            Paint {
                kind: ColorLevel::Ansi16,
                code: u32::from(index),
            }
        } else if level == ColorLevel::Ansi16 {
            self.palette_paint(xterm_rgb(index))
        } else {
            Paint {
                kind: ColorLevel::Ansi256,
                code: u32::from(index),
            }
        }
    }

    /// The palette's nearest colour (256 or 16 colours).
    fn palette_paint(&self, c: Rgb) -> Paint {
        Paint {
            kind: self.level(),
            code: self.palette.code(c),
        }
    }

    /// Writes the shortest SGR that takes the terminal from the current pen to `to`: only what
    /// changed (attributes switched off by their own codes), or a reset and all of `to`; then
    /// the underline colour when it changed (or a reset cleared it).
    fn change_pen(&mut self, out: &mut Vec<u8>, to: Pen) {
        let from = self.pen;
        if from == to {
            return;
        }
        self.pen = to;
        if to == PLAIN {
            out.extend_from_slice(b"\x1b[m");
            return;
        }
        let reset = self.change_colours_and_attributes(out, from, to);
        let ul_before = if reset { RESET } else { from.ul };
        if to.ul != ul_before {
            let ul = (to.ul != RESET).then_some((to.ul.kind, to.ul.code));
            sgr::write_underline(out, ul);
        }
    }

    /// The colours and attributes part of [`Self::change_pen`]; whether it began with a reset
    /// (which also ends the underline colour).
    fn change_colours_and_attributes(&mut self, out: &mut Vec<u8>, from: Pen, to: Pen) -> bool {
        let colour = |p: Paint| (p.kind, p.code);
        let (fg_changed, bg_changed) = (from.fg != to.fg, from.bg != to.bg);
        if from.modifier == to.modifier {
            sgr::write_mixed(
                out,
                &[],
                fg_changed.then(|| colour(to.fg)),
                bg_changed.then(|| colour(to.bg)),
            );
            return false;
        }
        // Attributes changed: by their own codes, or a reset first; the shorter one wins.
        let removed = from.modifier - to.modifier;
        let mut attrs = [0u8; 16];
        let mut n = 0;
        let mut off = Modifier::empty();
        for (m, code) in ATTRS_OFF {
            if removed.intersects(m) {
                attrs[n] = code;
                n += 1;
                off |= m;
            }
        }
        // Attributes to (re)set: the new ones, and any kept one an off code also ended.
        let kept_but_cleared = to.modifier & from.modifier & off;
        for (m, code) in ATTRS {
            if (to.modifier - from.modifier).contains(m) || kept_but_cleared.contains(m) {
                attrs[n] = code;
                n += 1;
            }
        }
        let (by_codes, by_reset) = &mut self.scratch;
        by_codes.clear();
        sgr::write_mixed(
            by_codes,
            &attrs[..n],
            fg_changed.then(|| colour(to.fg)),
            bg_changed.then(|| colour(to.bg)),
        );
        let mut reset = [0u8; 10];
        reset[0] = 0;
        let mut r = 1;
        for (m, code) in ATTRS {
            if to.modifier.contains(m) {
                reset[r] = code;
                r += 1;
            }
        }
        by_reset.clear();
        sgr::write_mixed(
            by_reset,
            &reset[..r],
            (to.fg != RESET).then(|| colour(to.fg)),
            (to.bg != RESET).then(|| colour(to.bg)),
        );
        let reset = by_reset.len() < by_codes.len();
        out.extend_from_slice(if reset { by_reset } else { by_codes });
        reset
    }
}

/// The ANSI index of one of ratatui's named colours (as crossterm writes them).
fn named_index(c: Color) -> u8 {
    match c {
        Color::Black => 0,
        Color::Red => 1,
        Color::Green => 2,
        Color::Yellow => 3,
        Color::Blue => 4,
        Color::Magenta => 5,
        Color::Cyan => 6,
        Color::Gray => 7,
        Color::DarkGray => 8,
        Color::LightRed => 9,
        Color::LightGreen => 10,
        Color::LightYellow => 11,
        Color::LightBlue => 12,
        Color::LightMagenta => 13,
        Color::LightCyan => 14,
        Color::White => 15,
        // Reset, Rgb and Indexed are handled by the caller.
        _ => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::buffer::Buffer;
    use ratatui::layout::Rect;
    use ratatui::style::Style;

    fn text(cells: &Buffer, level: ColorLevel) -> String {
        let mut w = CellWriter::new(level);
        let mut out = Vec::new();
        let blank = Buffer::empty(cells.area);
        w.draw(&mut out, blank.diff(cells).into_iter());
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn neighbours_share_one_move_and_colours_change_only_when_they_change() {
        let mut b = Buffer::empty(Rect::new(0, 0, 10, 2));
        let red = Style::new().fg(Color::Rgb(200, 0, 0));
        b.set_string(2, 0, "ab", red);
        b.set_string(4, 0, "c", red.bg(Color::Blue));
        b.set_string(0, 1, "d", red.bg(Color::Blue));
        assert_eq!(
            text(&b, ColorLevel::TrueColor),
            "\x1b[;3H\x1b[38;2;200;0;0mab\x1b[44mc\r\nd\x1b[m"
        );
    }

    #[test]
    fn attributes_switch_off_by_their_own_code_or_by_a_reset_whichever_is_shorter() {
        let mut b = Buffer::empty(Rect::new(0, 0, 6, 1));
        let s = Style::new().fg(Color::Indexed(100));
        b.set_string(0, 0, "a", s.add_modifier(Modifier::BOLD | Modifier::ITALIC));
        b.set_string(1, 0, "b", s.add_modifier(Modifier::ITALIC));
        b.set_string(2, 0, "c", s.add_modifier(Modifier::ITALIC | Modifier::DIM));
        b.set_string(3, 0, "d", Style::new());
        assert_eq!(
            text(&b, ColorLevel::TrueColor),
            "\x1b[H\x1b[1;3;38;5;100ma\x1b[22mb\x1b[2mc\x1b[md"
        );
    }

    /// A row of `▀` cells, each (upper, lower) grey level.
    fn half_blocks(cells: &[(u8, u8)]) -> Buffer {
        let mut b = Buffer::empty(Rect::new(0, 0, cells.len() as u16, 1));
        for (x, &(t, l)) in cells.iter().enumerate() {
            b[(x as u16, 0)]
                .set_symbol("▀")
                .set_fg(Color::Rgb(t, t, t))
                .set_bg(Color::Rgb(l, l, l));
        }
        b
    }

    #[test]
    fn half_block_runs_turn_cells_over_to_keep_a_shared_colour() {
        // 1 over 2, 2 over 3, 3 over 3: `▄` with 2 over 1, then `▀` 2 over 3 keeps 2 as the
        // foreground; the last cell is a space on the 3 already set: one change after the first.
        assert_eq!(
            text(
                &half_blocks(&[(1, 2), (2, 3), (3, 3)]),
                ColorLevel::TrueColor
            ),
            "\x1b[H\x1b[38;2;2;2;2;48;2;1;1;1m▄\x1b[48;2;3;3;3m▀ \x1b[m"
        );
    }

    #[test]
    fn kept_half_blocks_are_sent_as_drawn() {
        let b = half_blocks(&[(1, 2), (2, 2)]);
        let mut w = CellWriter::new(ColorLevel::TrueColor).keeping_half_blocks();
        let mut out = Vec::new();
        w.draw(&mut out, Buffer::empty(b.area).diff(&b).into_iter());
        assert_eq!(
            String::from_utf8(out).unwrap(),
            "\x1b[H\x1b[38;2;1;1;1;48;2;2;2;2m▀\x1b[38;2;2;2;2m▀\x1b[m"
        );
    }

    #[test]
    fn the_underline_colour_is_sent_where_the_level_allows() {
        let mut b = Buffer::empty(Rect::new(0, 0, 3, 1));
        let ul = Style::new().add_modifier(Modifier::UNDERLINED);
        b.set_string(0, 0, "a", ul.underline_color(Color::Rgb(1, 2, 3)));
        b.set_string(1, 0, "b", ul.underline_color(Color::Indexed(9)));
        b.set_string(2, 0, "c", ul);
        assert_eq!(
            text(&b, ColorLevel::TrueColor),
            "\x1b[H\x1b[4m\x1b[58:2::1:2:3ma\x1b[58:5:9mb\x1b[59mc\x1b[m"
        );
        assert_eq!(
            text(&b, ColorLevel::Ansi256),
            "\x1b[H\x1b[4m\x1b[58:5:16ma\x1b[58:5:9mb\x1b[59mc\x1b[m"
        );
        assert_eq!(text(&b, ColorLevel::Ansi16), "\x1b[H\x1b[4mabc\x1b[m");
    }

    #[test]
    fn colours_follow_the_level() {
        let mut b = Buffer::empty(Rect::new(0, 0, 3, 1));
        b.set_string(
            0,
            0,
            "x",
            Style::new()
                .fg(Color::Rgb(255, 0, 0))
                .bg(Color::Indexed(196)),
        );
        assert_eq!(
            text(&b, ColorLevel::Ansi256),
            "\x1b[H\x1b[38;5;196;48;5;196mx\x1b[m"
        );
        assert_eq!(text(&b, ColorLevel::Ansi16), "\x1b[H\x1b[91;101mx\x1b[m");
        assert_eq!(text(&b, ColorLevel::Mono), "\x1b[Hx");
    }
}
