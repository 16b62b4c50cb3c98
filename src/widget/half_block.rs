//! Shows a [`Framebuffer`] in a terminal buffer: one `▀` cell per two stacked pixels, or at a
//! finer glyph setting one quadrant, sextant or octant cell per 2×2, 2×3 or 2×4 pixels.

use ratatui::buffer::{Buffer, Cell, CellDiffOption};
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::widgets::Widget;

use crate::color::Rgb;
use crate::encode::glyph_frame::{as_half_blocks, coded_cells, glyph_cells};
use crate::encode::glyph_mask::glyph;
use crate::encode::quantize::quantize;
use crate::encode::{ColorLevel, Palette};
use crate::render::framebuffer::Framebuffer;
use crate::render::glyphs::Glyphs;

/// The upper-half block: its foreground paints the upper pixel, its background the lower.
pub const UPPER_HALF: &str = "▀";

/// A view cell left for an encoder to draw (halfcast's presenter): blank, and skipped by
/// ratatui's diff, which is ratatui's mark for a cell drawn by other means. A widget drawn over
/// it changes it, so what is still exactly this cell shows the view.
pub const VIEW_CELL: Cell = {
    let mut c = Cell::EMPTY;
    c.diff_option = CellDiffOption::Skip;
    c
};

/// Whether `cell` is still exactly [`VIEW_CELL`]: `*cell == VIEW_CELL`, the cheap fields first
/// and the symbol against one constant byte. The presenter asks this of every view cell of
/// every frame, and ratatui's `==` is a call that compares every field and both symbols.
#[must_use]
#[inline]
pub fn is_view_cell(cell: &Cell) -> bool {
    #[allow(deprecated)] // ratatui's old skip flag is still part of a cell's equality
    let skip = cell.skip;
    cell.diff_option == CellDiffOption::Skip
        && !skip
        && cell.style() == VIEW_CELL.style()
        && cell.symbol().as_bytes() == b" "
}

/// Where row `y` of `at` lies in the cells of a buffer over `area` (`at` within `area`): the view's
/// cells and the panes around them are walked a row slice at a time, not a cell lookup each.
#[must_use]
pub fn row_cells(area: Rect, at: Rect, y: u16) -> std::ops::Range<usize> {
    let start = usize::from(y - area.y) * usize::from(area.width) + usize::from(at.x - area.x);
    start..start + usize::from(at.width)
}

/// The terminal colour of a pixel (24-bit).
#[must_use]
#[inline]
pub fn to_color(c: Rgb) -> Color {
    Color::Rgb(c.r, c.g, c.b)
}

/// A ratatui widget drawing a framebuffer at one terminal cell per 1 × 2 pixels, 24-bit colour
/// unless told another [`ColorLevel`] ([`HalfBlockView::level`]).
///
/// Cell (cx, cy) of the area shows pixel (cx, 2·cy) as the `▀` foreground and (cx, 2·cy + 1)
/// as the background. Nothing is scaled: render the framebuffer at the area's size
/// ([`Framebuffer::for_cells`]`(area.width, area.height)`); any part of the area the
/// framebuffer does not cover is left untouched, and nothing outside the area (or the
/// buffer) is ever written.
///
/// ```
/// use halfcast::widget::HalfBlockView;
/// use halfcast::{Framebuffer, Rgb};
/// use ratatui::{buffer::Buffer, layout::Rect, style::Color, widgets::Widget};
///
/// let area = Rect::new(0, 0, 4, 2);
/// let mut fb = Framebuffer::for_cells(area.width, area.height);
/// fb.set(0, 0, Rgb::new(255, 0, 0)); // upper pixel of cell (0, 0)
/// fb.set(0, 1, Rgb::new(0, 0, 255)); // lower pixel of cell (0, 0)
///
/// let mut buf = Buffer::empty(area);
/// HalfBlockView::new(&fb).render(area, &mut buf);
/// assert_eq!(buf[(0, 0)].symbol(), "▀");
/// assert_eq!(buf[(0, 0)].fg, Color::Rgb(255, 0, 0));
/// assert_eq!(buf[(0, 0)].bg, Color::Rgb(0, 0, 255));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct HalfBlockView<'a> {
    fb: &'a Framebuffer,
    level: ColorLevel,
}

impl<'a> HalfBlockView<'a> {
    /// Wraps a framebuffer for drawing (24-bit colour).
    #[must_use]
    pub fn new(fb: &'a Framebuffer) -> Self {
        Self {
            fb,
            level: ColorLevel::TrueColor,
        }
    }

    /// Draws at `level`, for apps on a stock backend whose terminal shows fewer colours:
    /// 256 and 16 colours choose each cell's two palette colours together as halfcast's own
    /// encoder does (so the scene keeps its hue), as `Color::Indexed` cells; mono draws the
    /// ASCII shade ramp with default colours.
    ///
    /// ```
    /// use halfcast::{ColorLevel, Framebuffer, HalfBlockView, Rgb};
    /// use ratatui::{buffer::Buffer, layout::Rect, style::Color, widgets::Widget};
    ///
    /// let mut fb = Framebuffer::for_cells(1, 1);
    /// fb.set(0, 0, Rgb::new(255, 0, 0));
    /// fb.set(0, 1, Rgb::new(255, 0, 0));
    /// let mut buf = Buffer::empty(Rect::new(0, 0, 1, 1));
    /// HalfBlockView::new(&fb).level(ColorLevel::Ansi256).render(buf.area, &mut buf);
    /// assert_eq!(buf[(0, 0)].fg, Color::Indexed(196));
    /// ```
    #[must_use]
    pub fn level(mut self, level: ColorLevel) -> Self {
        self.level = level;
        self
    }
}

impl HalfBlockView<'_> {
    /// A framebuffer at a finer glyph setting ([`Framebuffer::for_glyphs`]): each cell the
    /// character of its chosen mask, fg the mask's colour, bg the rest's (the palette's nearest
    /// entries below truecolor, as the encoder sends them).
    fn render_glyphs(&self, area: Rect, buf: &mut Buffer) {
        let area = area.intersection(buf.area);
        let glyphs = self.fb.glyphs();
        let cols = usize::from(area.width).min(self.fb.cell_cols());
        let rows = usize::from(area.height).min(self.fb.cell_rows());
        let (mut cells, mut coded) = (Vec::new(), Vec::new());
        let palette = Palette::new(self.level);
        if self.level == ColorLevel::TrueColor {
            glyph_cells(self.fb, &mut cells);
        } else {
            coded_cells(self.fb, &palette, &mut cells, &mut coded);
        }
        let w = self.fb.cell_cols();
        for cy in 0..rows {
            for cx in 0..cols {
                let (mask, fg, bg) = if let Some(c) = coded.get(cy * w + cx) {
                    (
                        c.mask,
                        Color::Indexed(c.fg as u8),
                        Color::Indexed(c.bg as u8),
                    )
                } else {
                    let chosen = cells[cy * w + cx];
                    (chosen.mask, to_color(chosen.fg), to_color(chosen.bg))
                };
                buf[(area.x + cx as u16, area.y + cy as u16)]
                    .set_char(glyph(glyphs, mask))
                    .set_fg(fg)
                    .set_bg(bg);
            }
        }
    }
}

impl Widget for HalfBlockView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        (&self).render(area, buf);
    }
}

impl Widget for &HalfBlockView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        if self.fb.glyphs() != Glyphs::Half {
            if self.level == ColorLevel::Mono {
                let half = as_half_blocks(self.fb);
                HalfBlockView::new(&half)
                    .level(self.level)
                    .render(area, buf);
            } else {
                self.render_glyphs(area, buf);
            }
            return;
        }
        let area = area.intersection(buf.area);
        let cols = usize::from(area.width).min(self.fb.width());
        let rows = usize::from(area.height).min(self.fb.cell_rows());
        if self.level != ColorLevel::TrueColor {
            // The encoder's own choice per cell (with the surface-anchored alternation where the
            // frame carries dither phases), so a stock backend shows what the encoder would send.
            let palette = Palette::new(self.level);
            let mut codes = Vec::new();
            quantize(&palette, self.fb, &mut codes);
            let w = self.fb.width();
            for cy in 0..rows {
                let y = area.y + cy as u16;
                for cx in 0..cols {
                    let [t, b] = codes[cy * w + cx];
                    let cell = &mut buf[(area.x + cx as u16, y)];
                    if self.level == ColorLevel::Mono {
                        cell.set_char(char::from_u32(t).unwrap_or(' '))
                            .set_fg(Color::Reset)
                            .set_bg(Color::Reset);
                        continue;
                    }
                    cell.set_symbol(UPPER_HALF)
                        .set_fg(Color::Indexed(t as u8))
                        .set_bg(Color::Indexed(b as u8));
                }
            }
            return;
        }
        for cy in 0..rows {
            let upper = self.fb.row(2 * cy);
            let lower = self.fb.row(2 * cy + 1);
            let y = area.y + cy as u16;
            for cx in 0..cols {
                let cell = &mut buf[(area.x + cx as u16, y)];
                cell.set_symbol(UPPER_HALF)
                    .set_fg(to_color(upper[cx]))
                    .set_bg(to_color(lower[cx]));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quick_view_cell_test_agrees_with_equality() {
        use ratatui::style::{Color, Modifier};
        let mut cells = vec![VIEW_CELL, Cell::EMPTY, Cell::default()];
        let mut spaced = VIEW_CELL;
        spaced.set_symbol(" ");
        cells.push(spaced);
        let changes: [fn(&mut Cell); 6] = [
            |c| {
                c.set_char('x');
            },
            |c| {
                c.set_symbol("  ");
            },
            |c| {
                c.set_fg(Color::Red);
            },
            |c| {
                c.set_bg(Color::Rgb(0, 0, 0));
            },
            |c| {
                c.modifier = Modifier::BOLD;
            },
            |c| {
                c.set_diff_option(CellDiffOption::None);
            },
        ];
        for change in changes {
            let mut c = VIEW_CELL;
            change(&mut c);
            cells.push(c);
        }
        #[allow(deprecated)]
        {
            let mut c = VIEW_CELL;
            c.skip = true;
            cells.push(c);
        }
        for c in &cells {
            assert_eq!(is_view_cell(c), *c == VIEW_CELL, "{c:?}");
        }
        assert_eq!(cells.iter().filter(|c| is_view_cell(c)).count(), 2);
    }

    fn pattern(cols: u16, rows: u16) -> Framebuffer {
        let mut fb = Framebuffer::for_cells(cols, rows);
        for y in 0..fb.height() {
            for x in 0..fb.width() {
                fb.set(x, y, Rgb::new((x * 7) as u8, (y * 13) as u8, (x ^ y) as u8));
            }
        }
        fb
    }

    #[test]
    fn reading_the_buffer_back_gives_exactly_the_pixels() {
        let fb = pattern(23, 9);
        let area = Rect::new(5, 3, 23, 9);
        let mut buf = Buffer::empty(Rect::new(0, 0, 40, 20));
        HalfBlockView::new(&fb).render(area, &mut buf);
        let mut back = Framebuffer::for_cells(23, 9);
        for cy in 0..9u16 {
            for cx in 0..23u16 {
                let cell = &buf[(area.x + cx, area.y + cy)];
                assert_eq!(cell.symbol(), UPPER_HALF);
                let px = |c: Color| match c {
                    Color::Rgb(r, g, b) => Rgb::new(r, g, b),
                    other => panic!("not 24-bit: {other:?}"),
                };
                back.set(cx.into(), 2 * usize::from(cy), px(cell.fg));
                back.set(cx.into(), 2 * usize::from(cy) + 1, px(cell.bg));
            }
        }
        assert_eq!(back, fb);
    }

    #[test]
    fn a_rendered_frame_shows_the_encoders_surface_anchored_choice() {
        let world = crate::World::default_world();
        let start = world.map.start;
        let cam = crate::Camera::from_angle(start.pos(), start.angle_deg(), 66.0);
        let fb = crate::Scene::new(&world, cam).render(60, 20);
        assert!(
            fb.phases().is_some(),
            "walls and sprites write dither phases"
        );
        let area = Rect::new(0, 0, 60, 20);
        let mut buf = Buffer::empty(area);
        HalfBlockView::new(&fb)
            .level(ColorLevel::Ansi256)
            .render(area, &mut buf);
        let mut codes = Vec::new();
        quantize(&Palette::new(ColorLevel::Ansi256), &fb, &mut codes);
        let mut alternated = 0;
        for cy in 0..20u16 {
            for cx in 0..60u16 {
                let [t, b] = codes[usize::from(cy) * 60 + usize::from(cx)];
                let cell = &buf[(cx, cy)];
                assert_eq!(
                    (cell.fg, cell.bg),
                    (Color::Indexed(t as u8), Color::Indexed(b as u8))
                );
                let (pt, pb) = fb.cell(cx.into(), cy.into());
                let plain = Palette::new(ColorLevel::Ansi256).cell(pt, pb);
                alternated += usize::from(plain != [t, b]);
            }
        }
        assert!(alternated > 0, "some cells take their second pair");
    }

    #[test]
    fn lower_levels_draw_the_encoders_palette_pair_or_the_shade_ramp() {
        let fb = pattern(12, 4);
        let area = Rect::new(0, 0, 12, 4);
        for level in [ColorLevel::Ansi256, ColorLevel::Ansi16] {
            let mut buf = Buffer::empty(area);
            HalfBlockView::new(&fb).level(level).render(area, &mut buf);
            let palette = Palette::new(level);
            for cy in 0..4u16 {
                for cx in 0..12u16 {
                    let (t, b) = fb.cell(cx.into(), cy.into());
                    let [pt, pb] = palette.cell(t, b);
                    let cell = &buf[(cx, cy)];
                    assert_eq!(cell.fg, Color::Indexed(pt as u8), "{level} ({cx},{cy})");
                    assert_eq!(cell.bg, Color::Indexed(pb as u8), "{level} ({cx},{cy})");
                    assert!(level != ColorLevel::Ansi16 || pt < 16 && pb < 16);
                }
            }
        }
        let mut buf = Buffer::empty(area);
        HalfBlockView::new(&fb)
            .level(ColorLevel::Mono)
            .render(area, &mut buf);
        let (t, b) = fb.cell(5, 2);
        assert_eq!(
            buf[(5, 2)].symbol(),
            crate::encode::quantize::mono_char(t, b).to_string()
        );
        assert_eq!(
            (buf[(5, 2)].fg, buf[(5, 2)].bg),
            (Color::Reset, Color::Reset)
        );
    }

    #[test]
    fn nothing_outside_the_area_or_buffer_is_touched() {
        let fb = pattern(50, 30);
        let whole = Rect::new(0, 0, 20, 10);
        let mut buf = Buffer::empty(whole);
        let area = Rect::new(4, 2, 30, 30);
        HalfBlockView::new(&fb).render(area, &mut buf);
        for y in 0..10 {
            for x in 0..20 {
                let inside = x >= 4 && y >= 2;
                assert_eq!(buf[(x, y)].symbol() == UPPER_HALF, inside, "({x},{y})");
            }
        }
    }

    #[test]
    fn a_smaller_framebuffer_leaves_the_rest_of_the_area_alone() {
        let fb = pattern(3, 1);
        let area = Rect::new(0, 0, 6, 3);
        let mut buf = Buffer::empty(area);
        HalfBlockView::new(&fb).render(area, &mut buf);
        assert_eq!(buf[(2, 0)].symbol(), UPPER_HALF);
        assert_eq!(buf[(3, 0)].symbol(), " ");
        assert_eq!(buf[(0, 1)].symbol(), " ");
        HalfBlockView::new(&Framebuffer::new(0, 0)).render(area, &mut buf);
    }
}
