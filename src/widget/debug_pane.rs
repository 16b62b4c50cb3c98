//! The DDA debug pane: one ray's derivation in Lode's names, line by line with the column's
//! numbers — `cameraX`, `rayDir`, `deltaDist`, `stepX/Y` and the first `sideDist`s, then for
//! every step the comparison that chose it and the cell it entered, then `perp`, the line
//! height and `wall_x`. On maps with heights, each face the ray passes says how it narrowed the
//! column's open window of rows. Every number comes from the trace (see
//! [`crate::render::derivation`]), the same one the JSON prints.
//!
//! While stepping, earlier steps fold to one line each and the current one is written out; a
//! pane too short for everything shows the newest lines and says how many are above, and the
//! scroll position (in steps, kept by the debugger) writes out an earlier step instead; scrolled
//! back past the first step, the pane ends at an earlier part of the setup, up to `cameraX`.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;
use ratatui::widgets::Widget;

mod heights;
mod items;
mod kept;
mod row;
mod window;

pub use kept::KeptLines;

use super::revealed::RevealedTrace;
use crate::camera::Camera;
use crate::render::derivation::{num, Derivation, SETUP_PARTS};
use crate::render::height_cast::HeightColumn;
use crate::render::raster::{heading, wall_span};
use crate::world::World;
use heights::Heights;
use items::SETUP_PART_ROWS;
use row::{Row, NAME, VALUE};
use window::window;

/// The derivation's parts, in order: the setup, one item per step, the hit.
#[derive(Debug, Clone)]
struct Item {
    rows: Vec<Row>,
}

/// The debugged ray's derivation as text; the current step is highlighted.
#[derive(Debug, Clone)]
pub struct DebugPane<'a> {
    ray: RevealedTrace<'a>,
    derivation: Derivation,
    tex_width: usize,
    focal: f64,
    line_height: f64,
    heights: Option<Heights>,
    /// Pixel rows of the view (the heights' window starts as all of them).
    view_rows: usize,
    /// Steps scrolled back from the newest (0 = follow the current step).
    scroll: usize,
    /// Parts of the setup scrolled back from its end, once scrolled back to it.
    into_setup: usize,
    ascii: bool,
    /// Columns the pane has (set when it is drawn): lines wrap to it.
    width: usize,
}

impl<'a> DebugPane<'a> {
    /// The pane for `ray`, cast by `camera` in a view of `view_cells` (columns, rows).
    #[must_use]
    pub fn new(
        ray: RevealedTrace<'a>,
        world: &World,
        camera: &Camera,
        view_cells: (usize, usize),
    ) -> Self {
        let hit = &ray.trace.hit;
        let tex_width = world.wall_texture(hit.what, heading(hit)).width();
        let focal = camera.focal_length(view_cells.0);
        let line_height = wall_span(hit.perp_dist, focal, view_cells.1 * 2).height;
        Self {
            derivation: Derivation::new(ray.trace, camera, view_cells.0),
            ray,
            tex_width,
            focal,
            line_height,
            heights: None,
            view_rows: view_cells.1 * 2,
            scroll: 0,
            into_setup: 0,
            ascii: false,
            width: usize::MAX,
        }
    }

    /// Also says, at each face the ray passes, how the column's open window of rows narrowed
    /// (from its draw list, `Cast::heights` of an `Hz` map).
    #[must_use]
    pub fn heights(mut self, col: &HeightColumn) -> Self {
        let h = Heights::new(col, self.view_rows);
        // The hit's line is the face that closed the window, as tall as the heights it spans
        // (a flat wall's formula would say one wall high); none when a floor or ceiling closed it.
        self.line_height = h
            .closing_dz
            .map_or(0.0, |dz| dz * self.focal / self.derivation.perp.max(1e-9));
        self.heights = Some(h);
        self
    }

    /// Writes out the step `steps` back from the newest instead (the scroll key).
    #[must_use]
    pub fn scroll(mut self, steps: usize) -> Self {
        self.scroll = steps;
        self
    }

    /// Scrolled back to the setup, ends the pane `parts` of the setup's parts before its end
    /// instead (at most to `cameraX`): a setup taller than the pane is read a part at a time.
    #[must_use]
    pub fn scroll_into_setup(mut self, parts: usize) -> Self {
        self.into_setup = parts.min(SETUP_PARTS - 1);
        self
    }

    /// Plain ASCII only (a mono terminal): `-` for −, `*` for ·, `->` for →.
    #[must_use]
    pub fn ascii(mut self, on: bool) -> Self {
        self.ascii = on;
        self
    }

    /// Item `k` of the setup (0), the revealed steps (1 to `shown`) and the hit (`shown` + 1),
    /// with `expanded` steps written out and the others folded to one line.
    fn item(&self, k: usize, expanded: &dyn Fn(usize) -> bool) -> Item {
        let shown = self.ray.shown;
        let rows = if k == 0 {
            self.setup_rows()
        } else if k <= shown {
            let c = &self.derivation.choices[k - 1];
            let current = !self.ray.hit_reached && c.index == shown;
            self.step_rows(c, expanded(c.index), current)
        } else {
            self.hit_rows()
        };
        Item { rows }
    }

    /// An item's rows, each wrapped to `width`.
    fn wrapped(&self, item: Item, width: usize) -> Vec<Vec<Line<'static>>> {
        item.rows.into_iter().map(|r| self.wrap(r, width)).collect()
    }

    /// Whether item `k` is a folded step of one line: one chunk, so it never wraps, and no
    /// face of the heights in its cell. Its line count is known without writing it.
    fn one_line(&self, k: usize, expanded: &dyn Fn(usize) -> bool) -> bool {
        if k == 0 || k > self.ray.shown {
            return false;
        }
        let c = &self.derivation.choices[k - 1];
        !expanded(c.index)
            && self
                .heights
                .as_ref()
                .is_none_or(|h| h.faces.iter().all(|f| f.face.cell != c.cell))
    }

    /// Every item wrapped to `width` with `expanded` steps written out, except folded steps
    /// [`window`] cuts from a pane of `rows` rows: those are one empty line each (they only
    /// count). `setup` is item 0 when it is already written.
    fn wrap_items(
        &self,
        expanded: &dyn Fn(usize) -> bool,
        width: usize,
        rows: usize,
        focus: usize,
        mut setup: Option<Vec<Vec<Line<'static>>>>,
    ) -> Vec<Vec<Vec<Line<'static>>>> {
        let items = self.ray.shown + 2;
        let mut written: Vec<Option<Vec<Vec<Line<'static>>>>> = (0..items)
            .map(|k| match setup.take() {
                Some(s) if k == 0 => Some(s),
                _ if self.one_line(k, expanded) => None,
                _ => Some(self.wrapped(self.item(k, expanded), width)),
            })
            .collect();
        let count = |w: &Option<Vec<Vec<Line<'static>>>>| {
            w.as_ref()
                .map_or(1, |rows| rows.iter().map(Vec::len).sum::<usize>())
        };
        // The lines `window` shows, as it picks them.
        let total: usize = written.iter().map(count).sum();
        let focus_end = if self.scroll > 0 {
            written.iter().take(focus + 1).map(count).sum()
        } else {
            total
        };
        let (lo, hi) = if total <= rows || rows == 0 {
            (0, total)
        } else {
            let end = focus_end.max(rows).min(total);
            (end - rows, end)
        };
        let mut at = 0;
        for (k, w) in written.iter_mut().enumerate() {
            let n = count(w);
            if w.is_none() && at < hi && at + n > lo {
                *w = Some(self.wrapped(self.item(k, expanded), width));
            }
            at += n;
        }
        written
            .into_iter()
            .map(|w| w.unwrap_or_else(|| vec![vec![Line::default()]]))
            .collect()
    }

    /// The pane's lines for `width` columns and `rows` rows: the derivation wrapped to the width,
    /// shortened to fit (earlier steps folded, then the top cut) with the focus — the current
    /// step, or the hit — at the bottom, moved back by the scroll.
    #[must_use]
    pub fn lines(&self, rows: usize) -> Vec<Line<'static>> {
        let width = self.width.max(16);
        let shown = self.ray.shown;
        // The items a scroll can focus: the setup (0), each revealed step, and the hit.
        let last = shown + usize::from(self.ray.hit_reached);
        let focus = last.saturating_sub(self.scroll);
        let stepping = !self.ray.hit_reached || self.scroll > 0;
        let all_open = |_: usize| true;
        let items = shown + 2;
        let wrapped = if stepping {
            self.wrap_items(&|i| i == focus, width, rows, focus, None)
        } else {
            // Every step written out, as long as that fits; written out one item at a time, so a
            // long ray stops at the first item past the pane instead of formatting every step.
            let mut open = Vec::with_capacity(items);
            let mut count = 0;
            for k in 0..items {
                let item = self.wrapped(self.item(k, &all_open), width);
                count += item.iter().map(Vec::len).sum::<usize>();
                open.push(item);
                if count > rows {
                    break;
                }
            }
            if count > rows {
                // Too long to write every step out: fold all but the last (the setup is the
                // same either way).
                let setup = open.swap_remove(0);
                self.wrap_items(&|i| i == shown, width, rows, focus, Some(setup))
            } else {
                open
            }
        };
        self.windowed(wrapped, focus, width, rows)
    }

    /// One row wrapped to the pane's `width`.
    fn wrap(&self, row: Row, width: usize) -> Vec<Line<'static>> {
        row::wrap(row, width, self.ascii)
    }

    /// The wrapped items laid out as the pane's `rows` rows: their lines in order, cut to the
    /// window that ends at the focus item (moved back by the scroll), `rayDir` pinned on top.
    fn windowed(
        &self,
        wrapped: Vec<Vec<Vec<Line<'static>>>>,
        focus: usize,
        width: usize,
        rows: usize,
    ) -> Vec<Line<'static>> {
        let mut lines = Vec::new();
        let mut starts = Vec::new();
        let mut focus_end = None;
        // Scrolled into the setup (item 0): the focus ends with one of its parts.
        let setup_rows = (focus == 0 && self.into_setup > 0).then(|| {
            SETUP_PART_ROWS[..SETUP_PARTS - self.into_setup]
                .iter()
                .sum::<usize>()
        });
        for (i, item) in wrapped.into_iter().enumerate() {
            for (r, row) in item.into_iter().enumerate() {
                starts.extend((0..row.len()).map(|k| k == 0));
                lines.extend(row);
                if i == 0 && setup_rows == Some(r + 1) {
                    // One line further: the part's own last line shows, the next one gives way
                    // to the note of what is below.
                    focus_end = Some(lines.len() + 1);
                }
            }
            if self.scroll > 0 && i == focus && focus_end.is_none() {
                focus_end = Some(lines.len());
            }
        }
        let focus_end = focus_end.unwrap_or(lines.len()).min(lines.len());
        // Cut at the top, the pane still says which ray it follows.
        let d = &self.derivation;
        let pinned = self.wrap(
            Row::new().chunk("rayDir", NAME).and(
                format!(" = ({}, {})", num(d.ray_dir.x), num(d.ray_dir.y)),
                VALUE,
            ),
            width,
        );
        window(lines, &starts, &pinned, rows, focus_end, self.ascii)
    }
}

impl Widget for DebugPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        if let Some((pane, area)) = self.fitted(area, buf.area) {
            put_lines(&pane.lines(usize::from(area.height)), area, buf);
        }
    }
}

impl DebugPane<'_> {
    /// Draws the pane as [`Widget::render`] does, its lines kept in `kept` for the next frame
    /// (see [`DebugPane::lines_kept`]).
    pub fn render_kept(self, area: Rect, buf: &mut Buffer, kept: &mut KeptLines) {
        if let Some((pane, area)) = self.fitted(area, buf.area) {
            put_lines(pane.lines_kept(usize::from(area.height), kept), area, buf);
        }
    }

    /// The pane at the width of `area` cut to the buffer, and that area (none when empty).
    fn fitted(self, area: Rect, buffer: Rect) -> Option<(Self, Rect)> {
        let area = area.intersection(buffer);
        let pane = DebugPane {
            width: usize::from(area.width),
            ..self
        };
        (!area.is_empty()).then_some((pane, area))
    }
}

/// The pane's lines, wrapped and cut to `area` already: each goes straight to its row (a
/// Paragraph would lay them out again, every frame of every SSH session).
fn put_lines(lines: &[Line<'static>], area: Rect, buf: &mut Buffer) {
    for (row, line) in lines.iter().enumerate() {
        let y = area.y + row as u16;
        if y >= area.bottom() {
            break;
        }
        super::text::put_line(buf, area.x, y, line, area.width);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::cast::trace_column;
    use crate::vec2::Vec2;

    fn text(lines: &[Line]) -> Vec<String> {
        lines.iter().map(ToString::to_string).collect()
    }

    fn setup() -> (World, Camera) {
        let w = World::default_world();
        // Exactly north: rayDirX is 0 on the centre column (deltaDistX is Lode's 1e30).
        let cam = Camera::from_dir(Vec2::new(15.5, 5.5), Vec2::new(0.0, -1.0), 66.0);
        (w, cam)
    }

    fn pane_text(pane: DebugPane, width: usize, rows: usize) -> Vec<String> {
        let pane = DebugPane { width, ..pane };
        text(&pane.lines(rows))
    }

    #[test]
    fn centre_ray_north_derives_every_number() {
        let (w, cam) = setup();
        let t = trace_column(&w.map, &cam, 20, 40);
        let pane = DebugPane::new(RevealedTrace::full(&t), &w, &cam, (40, 12));
        let lines = pane_text(pane, 60, 40);
        insta::assert_snapshot!(lines.join("\n"));
        let all = lines.join("\n");
        for want in [
            "cameraX = 2x/w − 1 = 2·20/40 − 1 = 0.00",
            "deltaDist = |1/rayDir| = (1e30, 1.00)",
            "sideDistX = (mapX+1−posX)·deltaDistX = 0.50·1e30 = 5e29",
            "  1 sideDistX 5e29 > sideDistY 0.50 → step y",
            "perp = sideDistY − deltaDistY = 5.50 − 1.00 = 4.50",
        ] {
            assert!(all.contains(want), "{want:?} missing:\n{all}");
        }
    }

    #[test]
    fn a_long_ray_in_a_short_pane_keeps_the_hit_and_says_what_is_above() {
        let (w, _) = setup();
        let cam = Camera::from_angle(Vec2::new(1.5, 5.5), 0.0, 66.0);
        let t = trace_column(&w.map, &cam, 20, 40);
        assert!(t.steps.len() > 8, "{}", t.steps.len());
        let pane = DebugPane::new(RevealedTrace::full(&t), &w, &cam, (40, 12));
        let lines = pane_text(pane, 46, 13);
        assert_eq!(lines.len(), 13);
        assert!(lines[0].contains("more above"), "{lines:#?}");
        assert!(lines.iter().any(|l| l.starts_with("perp")), "{lines:#?}");
        assert!(lines.last().unwrap().starts_with("texture x"), "{lines:#?}");
    }

    #[test]
    fn while_stepping_earlier_steps_fold_and_the_hit_is_not_shown_yet() {
        let (w, cam) = setup();
        let t = trace_column(&w.map, &cam, 20, 40);
        let pane = DebugPane::new(RevealedTrace::partial(&t, 2), &w, &cam, (40, 12));
        let lines = pane_text(pane, 60, 40);
        let all = lines.join("\n");
        assert!(all.contains("  1 step y → (15,4) sideDistY 1.50"), "{all}");
        assert!(
            all.contains("  2 sideDistX 5e29 > sideDistY 1.50 → step y"),
            "{all}"
        );
        assert!(
            all.contains("    map(15,3)  sideDistY += 1.00 → 2.50"),
            "{all}"
        );
        assert!(
            lines.last().unwrap().contains("not yet (step 2 of 5)"),
            "{all}"
        );
    }

    #[test]
    fn scrolling_writes_out_an_earlier_step() {
        let (w, cam) = setup();
        let t = trace_column(&w.map, &cam, 20, 40);
        let pane = DebugPane::new(RevealedTrace::partial(&t, 3), &w, &cam, (40, 12)).scroll(2);
        let all = pane_text(pane, 60, 40).join("\n");
        assert!(all.contains("  1 sideDistX 5e29 > sideDistY 0.50"), "{all}");
        assert!(all.contains("  3 step y → (15,2) sideDistY 3.50"), "{all}");
    }

    #[test]
    fn a_narrow_pane_wraps_between_the_parts_of_a_line() {
        let (w, cam) = setup();
        let t = trace_column(&w.map, &cam, 20, 40);
        let pane = DebugPane::new(RevealedTrace::full(&t), &w, &cam, (40, 12));
        let lines = pane_text(pane, 28, 200);
        for l in &lines {
            assert!(l.chars().count() <= 28, "{l:?} is wider than the pane");
        }
        assert!(
            lines.iter().any(|l| l == "  = 5.50 − 1.00 = 4.50"),
            "{lines:#?}"
        );
    }

    #[test]
    fn mono_is_ascii_only() {
        let (w, cam) = setup();
        let t = trace_column(&w.map, &cam, 20, 40);
        let pane = DebugPane::new(RevealedTrace::partial(&t, 3), &w, &cam, (40, 12)).ascii(true);
        for l in pane_text(pane, 28, 11) {
            assert!(l.is_ascii(), "{l:?}");
        }
    }

    #[test]
    fn scrolled_into_the_setup_a_short_pane_shows_every_line_of_the_setup() {
        let w = World::default_world();
        for angle in [0.0, 33.0, 62.0, 181.0, 270.0] {
            let cam = Camera::from_angle(Vec2::new(15.3, 5.6), angle, 66.0);
            let t = trace_column(&w.map, &cam, 39, 50);
            let pane = DebugPane::new(RevealedTrace::full(&t), &w, &cam, (50, 23));
            let top = t.steps.len() + 1;
            for (width, rows) in [(28, 9), (28, 11), (28, 14), (40, 9)] {
                let setup: Vec<String> = pane_text(pane.clone(), width, 400)
                    .into_iter()
                    .take_while(|l| !l.starts_with("  1 "))
                    .collect();
                assert!(setup[0].starts_with("cameraX"), "{setup:#?}");
                // Every stop ↑ reaches: each step back to the setup's end, then each part of
                // the setup back to cameraX.
                let mut seen = Vec::new();
                for back in 0..top {
                    seen.extend(pane_text(pane.clone().scroll(back), width, rows));
                }
                for parts in 0..SETUP_PARTS {
                    let at = pane.clone().scroll(top).scroll_into_setup(parts);
                    seen.extend(pane_text(at, width, rows));
                }
                for line in &setup {
                    assert!(
                        seen.contains(line),
                        "{line:?} never shows at {width}x{rows}, angle {angle}"
                    );
                }
                let last = pane.clone().scroll(top).scroll_into_setup(SETUP_PARTS - 1);
                assert_eq!(pane_text(last, width, rows)[0], setup[0]);
            }
        }
    }

    /// A corridor east: a quarter step up at x = 3, a lintel down to 0.7 at x = 5, a wall at 8.
    fn heights_world() -> World {
        let text = "NO textures/bricks.png\nSO textures/bricks.png\nWE textures/stone.png\n\
                    EA textures/stone.png\nF 96,88,80\nC 150,146,136\nHa 0.25 1\nHb 0.25 0.7\n\
                    111111111\n1E0aabbb1\n111111111\n";
        let map = crate::map::parse_map("h.cub", text.as_bytes()).unwrap();
        let source = crate::world::TextureSource::Embedded;
        World::load(map, &source, true).unwrap().0
    }

    fn heights_pane_lines(shown: Option<usize>, rows: usize) -> Vec<String> {
        let w = heights_world();
        let cam = Camera::from_angle(Vec2::new(1.5, 1.5), 0.0, 66.0);
        let view = crate::render::view::View::default();
        let proj = crate::render::height_cast::Projection::new(&cam, &view, 40, 24);
        let doors = crate::world::door::DoorState::new(&w.map);
        let cast =
            crate::render::height_cast::cast_heights(&w.map, &doors, &cam, &proj, 40, Some(20));
        let t = cast.trace.as_ref().unwrap();
        let ray = match shown {
            Some(n) => RevealedTrace::partial(t, n),
            None => RevealedTrace::full(t),
        };
        let pane = DebugPane::new(ray, &w, &cam, (40, 12)).heights(&cast.heights[20]);
        pane_text(pane, 60, rows)
    }

    #[test]
    fn on_a_heights_map_each_face_says_how_the_window_narrowed() {
        let lines = heights_pane_lines(None, 60);
        let all = lines.join("\n");
        insta::assert_snapshot!(all);
        for want in [
            "    step z 0..0.25 rows 17..22 window 2..22 → 2..17",
            "    lintel z 0.7..1 rows 8..10 window 8..14 → 10..14",
            "window closed (8,1) at 6.50",
            // The closing wall shows only its 0.25..0.7 beside (7,1): 0.45 of the flat 4.74 px.
            "line = Δz·focal/perp = 0.45·30.80/6.50 = 2.13 px",
        ] {
            assert!(all.contains(want), "{want:?} missing:\n{all}");
        }
        // While stepping, only the faces of cells reached so far.
        let early = heights_pane_lines(Some(1), 60).join("\n");
        assert!(
            !early.contains("0..0.25") && !early.contains("closed"),
            "{early}"
        );
    }

    /// The pane's lines as [`DebugPane::lines`] picked them before it skipped folded steps the
    /// window cuts: every item written, then the window.
    fn every_item_written(pane: &DebugPane, rows: usize) -> Vec<Line<'static>> {
        let width = pane.width.max(16);
        let shown = pane.ray.shown;
        let last = shown + usize::from(pane.ray.hit_reached);
        let focus = last.saturating_sub(pane.scroll);
        let stepping = !pane.ray.hit_reached || pane.scroll > 0;
        let write = |expanded: &dyn Fn(usize) -> bool| -> Vec<Vec<Vec<Line<'static>>>> {
            (0..shown + 2)
                .map(|k| pane.wrapped(pane.item(k, expanded), width))
                .collect()
        };
        let open = write(&|_| true);
        let count: usize = open.iter().flatten().map(Vec::len).sum();
        let wrapped = if stepping {
            write(&|i| i == focus)
        } else if count > rows {
            write(&|i| i == shown)
        } else {
            open
        };
        pane.windowed(wrapped, focus, width, rows)
    }

    #[test]
    fn skipping_the_folded_steps_the_window_cuts_changes_no_line() {
        let plain = World::default_world();
        let heights = heights_world();
        let mut checked = 0;
        for (w, pos) in [
            (&plain, Vec2::new(15.5, 5.5)),
            (&heights, Vec2::new(1.5, 1.5)),
        ] {
            let doors = crate::world::door::DoorState::new(&w.map);
            for angle in [0.0, 7.0, 33.0, 95.0, 181.0, 270.0] {
                let cam = Camera::from_angle(pos, angle, 66.0);
                let proj = crate::render::height_cast::Projection::new(
                    &cam,
                    &crate::render::view::View::default(),
                    40,
                    24,
                );
                let cast = crate::render::height_cast::cast_heights(
                    &w.map,
                    &doors,
                    &cam,
                    &proj,
                    40,
                    Some(20),
                );
                let flat = trace_column(&w.map, &cam, 20, 40);
                let t = cast.trace.as_ref().unwrap_or(&flat);
                for shown in [0, 1, 2, 4, t.steps.len()] {
                    for scroll in [0, 1, 3] {
                        for (width, rows) in [(28, 9), (28, 20), (48, 6), (48, 25), (60, 60)] {
                            for ascii in [false, true] {
                                let mut pane = DebugPane::new(
                                    RevealedTrace::partial(t, shown),
                                    w,
                                    &cam,
                                    (40, 12),
                                )
                                .scroll(scroll)
                                .ascii(ascii);
                                if std::ptr::eq(w, &heights) {
                                    pane = pane.heights(&cast.heights[20]);
                                }
                                let pane = DebugPane { width, ..pane };
                                assert_eq!(
                                    pane.lines(rows),
                                    every_item_written(&pane, rows),
                                    "angle {angle} shown {shown} scroll {scroll} {width}x{rows}"
                                );
                                checked += 1;
                            }
                        }
                    }
                }
            }
        }
        assert!(checked > 500);
    }
}
