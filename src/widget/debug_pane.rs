//! The DDA debug pane: one ray's derivation in Lode's names, line by line with the column's
//! numbers — `cameraX`, `rayDir`, `deltaDist`, `stepX/Y` and the first `sideDist`s, then for
//! every step the comparison that chose it and the cell it entered, then `perp`, the line
//! height and `wall_x`. On maps with heights, each face the ray passes says how it narrowed the
//! column's open window of rows. Every number comes from the trace (see
//! [`crate::render::derivation`]), the same one the JSON prints.
//!
//! While stepping, earlier steps fold to one line each and the current one is written out; a
//! pane too short for everything shows the newest lines and says how many are above, and the
//! scroll position (in steps, kept by the debugger) writes out an earlier step instead.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Widget;

mod kept;

pub use kept::KeptLines;

use super::revealed::RevealedTrace;
use crate::camera::Camera;
use crate::map::Cell;
use crate::render::cast::Side;
use crate::render::derivation::{compared, num, Choice, Derivation, PerpFrom};
use crate::render::height_cast::{Band, FaceSpan, HeightColumn};
use crate::render::raster::{heading, texture_x, wall_span};
use crate::world::World;

const LABEL: Style = Style::new().fg(Color::Rgb(128, 132, 146));
const VALUE: Style = Style::new().fg(Color::Rgb(226, 226, 232));
const NAME: Style = Style::new().fg(Color::Rgb(110, 200, 230));
const SIDE_X: Color = Color::Rgb(255, 176, 96);
const SIDE_Y: Color = Color::Rgb(126, 192, 255);
const CURRENT_BG: Color = Color::Rgb(64, 60, 22);
const HIT: Style = Style::new()
    .fg(Color::Rgb(255, 96, 96))
    .add_modifier(Modifier::BOLD);

fn side_style(side: Side) -> Style {
    Style::new().fg(match side {
        Side::X => SIDE_X,
        Side::Y => SIDE_Y,
    })
}

fn axis(side: Side) -> &'static str {
    match side {
        Side::X => "X",
        Side::Y => "Y",
    }
}

fn cell_text(c: (i64, i64)) -> String {
    format!("({},{})", c.0, c.1)
}

fn pair(v: crate::vec2::Vec2) -> String {
    format!("({},{})", num(v.x), num(v.y))
}

fn signed(s: i64) -> &'static str {
    if s < 0 {
        "−1"
    } else {
        "+1"
    }
}

/// A height in wall units, short: `1`, `0.25`, `-0.5` (at most 2 decimals).
fn fmt_height(z: f64) -> String {
    let s = format!("{z:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

/// Panes at least this wide get the roomier forms (`step y` in folded steps).
const WIDE: usize = 40;

/// One logical line of the derivation: chunks it may wrap between (a chunk never splits).
#[derive(Debug, Clone, Default)]
struct Row {
    chunks: Vec<Vec<Span<'static>>>,
    /// Drawn on the highlight background (the current step).
    current: bool,
}

impl Row {
    fn new() -> Self {
        Self::default()
    }

    /// Starts a new chunk (a place the line may wrap) with one span.
    fn chunk(mut self, text: impl Into<String>, style: Style) -> Self {
        self.chunks.push(vec![Span::styled(text.into(), style)]);
        self
    }

    /// Adds a span to the current chunk.
    fn and(mut self, text: impl Into<String>, style: Style) -> Self {
        let span = Span::styled(text.into(), style);
        match self.chunks.last_mut() {
            Some(c) => c.push(span),
            None => self.chunks.push(vec![span]),
        }
        self
    }
}

/// The derivation's parts, in order: the setup, one item per step, the hit.
#[derive(Debug, Clone)]
struct Item {
    rows: Vec<Row>,
}

/// The vertical faces the column drew, each with the open window of rows before and after it.
#[derive(Debug, Clone, PartialEq)]
struct FaceWindow {
    face: FaceSpan,
    before: (usize, usize),
    after: (usize, usize),
}

/// The traced column's draw list on an `Hz` map, as the pane prints it.
#[derive(Debug, Clone, PartialEq)]
struct Heights {
    faces: Vec<FaceWindow>,
    closed: ((i64, i64), f64),
    /// The closing face's height span (its line is that tall), if a face closed the window.
    closing_dz: Option<f64>,
}

impl Heights {
    fn new(col: &HeightColumn, rows: usize) -> Self {
        let (mut top, mut bottom) = (
            0,
            rows.max(col.bands.iter().map(|b| b.rows().1).max().unwrap_or(0)),
        );
        let mut faces = Vec::new();
        for b in &col.bands {
            let before = (top, bottom);
            let (a, z) = b.rows();
            if a <= top {
                top = z.max(top);
            } else {
                bottom = a.min(bottom);
            }
            if let Band::Face(f) = b {
                faces.push(FaceWindow {
                    face: *f,
                    before,
                    after: (top, bottom),
                });
            }
        }
        let closing_dz = col.bands.iter().rev().find_map(|b| match b {
            Band::Face(f) if f.cell == col.closed.cell => Some(f.z.1 - f.z.0),
            _ => None,
        });
        Self {
            faces,
            closed: (col.closed.cell, col.closed.perp_dist),
            closing_dz,
        }
    }
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

    fn setup_rows(&self) -> Vec<Row> {
        let d = &self.derivation;
        let mut rows = vec![
            Row::new()
                .chunk("cameraX", NAME)
                .and(" = 2x/w − 1", LABEL)
                .chunk(format!(" = 2·{}/{} − 1", d.column, d.width), LABEL)
                .chunk(" = ", LABEL)
                .and(num(d.camera_x), VALUE),
            Row::new()
                .chunk("rayDir", NAME)
                .and(" = dir + plane·cameraX", LABEL),
            Row::new()
                .chunk(format!("  = {}", pair(d.dir)), VALUE)
                .chunk(format!(" + {}·{}", pair(d.plane), num(d.camera_x)), VALUE),
            Row::new().chunk(format!("  = {}", pair(d.ray_dir)), VALUE),
            Row::new()
                .chunk("deltaDist", NAME)
                .and(" = |1/rayDir|", LABEL)
                .chunk(" = ", LABEL)
                .and(
                    format!("({}, {})", num(d.delta_dist.0), num(d.delta_dist.1)),
                    VALUE,
                ),
            Row::new()
                .chunk("pos ", LABEL)
                .and(pair(d.pos), VALUE)
                .chunk(" in map", LABEL)
                .and(cell_text(d.start_cell), VALUE),
        ];
        for (side, step, gap, delta, sd, dir) in [
            (
                Side::X,
                d.step.0,
                d.gap.0,
                d.delta_dist.0,
                d.initial_side_dist.0,
                d.ray_dir.x,
            ),
            (
                Side::Y,
                d.step.1,
                d.gap.1,
                d.delta_dist.1,
                d.initial_side_dist.1,
                d.ray_dir.y,
            ),
        ] {
            let a = axis(side);
            let why = if dir < 0.0 { "< 0" } else { "≥ 0" };
            let formula = if step < 0 {
                format!("(pos{a}−map{a})")
            } else {
                format!("(map{a}+1−pos{a})")
            };
            rows.push(
                Row::new()
                    .chunk(format!("step{a}"), side_style(side))
                    .and(format!(" = {}", signed(step)), VALUE)
                    .chunk(format!(" (rayDir{a} {why})"), LABEL),
            );
            rows.push(
                Row::new()
                    .chunk(format!("sideDist{a}"), side_style(side))
                    .and(" =", LABEL)
                    .chunk(format!(" {formula}·deltaDist{a}"), LABEL)
                    .chunk(format!(" = {}·{}", num(gap), num(delta)), VALUE)
                    .chunk(" = ", LABEL)
                    .and(num(sd), VALUE),
            );
        }
        rows
    }

    fn step_rows(&self, c: &Choice, expanded: bool, current: bool) -> Vec<Row> {
        let d = &self.derivation;
        let a = axis(c.side);
        let chosen = side_style(c.side);
        let new_value = match c.side {
            Side::X => c.after.0,
            Side::Y => c.after.1,
        };
        let mut rows = Vec::new();
        if expanded {
            let (x, sign, y) = compared(c.before.0, c.before.1);
            let step = format!("step {}", a.to_lowercase());
            rows.push(
                Row::new()
                    .chunk(format!("{:>3} ", c.index), VALUE)
                    .and("sideDistX ", side_style(Side::X))
                    .and(x, VALUE)
                    .and(format!(" {sign} "), VALUE)
                    .chunk("sideDistY ", side_style(Side::Y))
                    .and(y, VALUE)
                    .chunk(" → ", LABEL)
                    .and(step, chosen.add_modifier(Modifier::BOLD)),
            );
            let delta = match c.side {
                Side::X => d.delta_dist.0,
                Side::Y => d.delta_dist.1,
            };
            // Lode's `sideDistY += deltaDistY`, with the numbers.
            rows.push(
                Row::new()
                    .chunk("    map", LABEL)
                    .and(cell_text(c.cell), VALUE)
                    .chunk(format!("  sideDist{a}"), chosen)
                    .and(format!(" += {} → ", num(delta)), VALUE)
                    .and(num(new_value), VALUE),
            );
        } else {
            // One line: the step's number, the cell entered, the sideDist that grew.
            let compact = self.width < WIDE;
            let step = if compact {
                String::new()
            } else {
                format!("step {} ", a.to_lowercase())
            };
            rows.push(
                Row::new()
                    .chunk(format!("{:>3} ", c.index), VALUE)
                    .and(step, chosen)
                    .and("→ ", LABEL)
                    .and(cell_text(c.cell), VALUE)
                    .and(format!(" sideDist{a} "), chosen)
                    .and(num(new_value), VALUE),
            );
        }
        if let Some(h) = &self.heights {
            for f in h.faces.iter().filter(|f| f.face.cell == c.cell) {
                let face = &f.face;
                rows.push(
                    Row::new()
                        .chunk(
                            format!("    {}", face.kind.as_str()),
                            Style::new().fg(SIDE_X),
                        )
                        .and(
                            format!(" z {}..{}", fmt_height(face.z.0), fmt_height(face.z.1)),
                            VALUE,
                        )
                        .chunk(format!(" rows {}..{}", face.rows.0, face.rows.1), LABEL)
                        .chunk(
                            format!(
                                " window {}..{} → {}..{}",
                                f.before.0, f.before.1, f.after.0, f.after.1
                            ),
                            VALUE,
                        ),
                );
            }
        }
        for r in &mut rows {
            r.current = current;
        }
        rows
    }

    fn hit_rows(&self) -> Vec<Row> {
        let d = &self.derivation;
        if !self.ray.hit_reached {
            return vec![Row::new().chunk("hit ", LABEL).and(
                format!("not yet (step {} of {})", self.ray.shown, d.choices.len()),
                VALUE,
            )];
        }
        let what = match d.hit_what {
            Cell::Wall(n) => format!("wall {n}"),
            Cell::Void => "void".to_owned(),
            Cell::Floor { .. } => "floor".to_owned(),
            Cell::Door(_) => "door".to_owned(),
        };
        let mut rows = vec![Row::new()
            .chunk("hit ", LABEL)
            .and(cell_text(d.hit_cell), HIT)
            .and(format!(" {what}"), VALUE)
            .chunk(", side ", LABEL)
            .and(d.hit_side.as_str(), side_style(d.hit_side))];
        let a = axis(d.hit_side);
        // A narrow pane keeps perp's derivation and gives the rest as plain results, so the
        // last steps stay in view above the hit.
        let compact = self.width < WIDE;
        rows.push(match d.perp_from {
            PerpFrom::GridLine {
                side_dist,
                delta_dist,
                ..
            } => Row::new()
                .chunk("perp", NAME)
                .and(" =", LABEL)
                .chunk(
                    if compact {
                        format!(" sideDist{a}−deltaDist{a}")
                    } else {
                        format!(" sideDist{a} − deltaDist{a}")
                    },
                    LABEL,
                )
                .chunk(
                    format!(" = {} − {}", num(side_dist), num(delta_dist)),
                    VALUE,
                )
                .chunk(" = ", LABEL)
                .and(num(d.perp), VALUE),
            PerpFrom::DoorPanel { line, .. } => {
                let (p, r) = match d.hit_side {
                    Side::X => (d.pos.x, d.ray_dir.x),
                    Side::Y => (d.pos.y, d.ray_dir.y),
                };
                Row::new()
                    .chunk("perp", NAME)
                    .and(" =", LABEL)
                    .chunk(format!(" (map{a}+0.5−pos{a})/rayDir{a}"), LABEL)
                    .chunk(format!(" = ({} − {})/{}", num(line), num(p), num(r)), VALUE)
                    .chunk(" = ", LABEL)
                    .and(num(d.perp), VALUE)
            }
        });
        if compact {
            rows.push(
                Row::new()
                    .chunk("line ", NAME)
                    .and(num(self.line_height), VALUE)
                    .and(" px", LABEL)
                    .chunk("  wall_x ", NAME)
                    .and(num(d.wall_x), VALUE),
            );
            rows.push(self.texture_row());
            rows.extend(self.closed_row());
            return rows;
        }
        let line = match self.heights.as_ref().map(|h| h.closing_dz) {
            None => Row::new()
                .chunk("line", NAME)
                .and(" = focal/perp", LABEL)
                .chunk(format!(" = {}/{}", num(self.focal), num(d.perp)), VALUE),
            Some(Some(dz)) => Row::new()
                .chunk("line", NAME)
                .and(" = Δz·focal/perp", LABEL)
                .chunk(
                    format!(" = {}·{}/{}", fmt_height(dz), num(self.focal), num(d.perp)),
                    VALUE,
                ),
            Some(None) => Row::new()
                .chunk("line", NAME)
                .and(" none (floors closed it)", LABEL),
        };
        rows.push(
            line.chunk(" = ", LABEL)
                .and(num(self.line_height), VALUE)
                .and(" px", LABEL),
        );
        // wall_x runs along the face: the other axis from the one the ray crossed.
        let (posn, rayn, p, r) = match d.hit_side {
            Side::X => ("posY", "rayDirY", d.pos.y, d.ray_dir.y),
            Side::Y => ("posX", "rayDirX", d.pos.x, d.ray_dir.x),
        };
        rows.push(if matches!(d.hit_what, Cell::Door(_)) {
            Row::new()
                .chunk("wall_x", NAME)
                .and(" (along the open panel) = ", LABEL)
                .and(num(d.wall_x), VALUE)
        } else {
            Row::new()
                .chunk("wall_x", NAME)
                .and(format!(" = {posn} + perp·{rayn}"), LABEL)
                .chunk(format!(" = {} + {}·{}", num(p), num(d.perp), num(r)), VALUE)
                .chunk(format!(" = {}", num(d.wall_along)), VALUE)
                .chunk(" → ", LABEL)
                .and(num(d.wall_x), VALUE)
        });
        rows.push(self.texture_row());
        rows.extend(self.closed_row());
        rows
    }

    /// Which texture column the hit samples, of how many.
    fn texture_row(&self) -> Row {
        Row::new()
            .chunk("texture x ", LABEL)
            .and(
                texture_x(&self.ray.trace.hit, self.tex_width).to_string(),
                VALUE,
            )
            .and(format!(" of {}", self.tex_width), LABEL)
    }

    /// On maps with heights: where the column's window of rows closed.
    fn closed_row(&self) -> Option<Row> {
        self.heights.as_ref().map(|h| {
            Row::new()
                .chunk("window closed ", LABEL)
                .and(cell_text(h.closed.0), HIT)
                .chunk(format!(" at {}", num(h.closed.1)), VALUE)
        })
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
        for (i, item) in wrapped.into_iter().enumerate() {
            for row in item {
                starts.extend((0..row.len()).map(|k| k == 0));
                lines.extend(row);
            }
            if self.scroll > 0 && i == focus {
                focus_end = Some(lines.len());
            }
        }
        let focus_end = focus_end.unwrap_or(lines.len());
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

    /// One row wrapped to `width`: chunks fill a line, the rest continue indented by two.
    fn wrap(&self, row: Row, width: usize) -> Vec<Line<'static>> {
        let current = row.current;
        let fix = |s: Span<'static>| -> Span<'static> {
            if self.ascii {
                Span::styled(to_ascii(&s.content), s.style)
            } else {
                s
            }
        };
        let bg = |s: Span<'static>| {
            if current {
                let st = s.style.bg(CURRENT_BG).add_modifier(Modifier::BOLD);
                s.style(st)
            } else {
                s
            }
        };
        let mut out: Vec<Vec<Span<'static>>> = vec![Vec::new()];
        let mut used = 0;
        for chunk in row.chunks {
            let spans: Vec<Span<'static>> = chunk.into_iter().map(fix).collect();
            let w: usize = spans.iter().map(|s| s.content.chars().count()).sum();
            if used > 0 && used + w > width {
                // Continue on a new line, indented, without the chunk's leading spaces.
                let mut first = true;
                let mut line = vec![Span::styled("  ", VALUE)];
                used = 2;
                for s in spans {
                    let s = if first {
                        first = false;
                        let t = s.content.trim_start().to_owned();
                        Span::styled(t, s.style)
                    } else {
                        s
                    };
                    used += s.content.chars().count();
                    line.push(s);
                }
                out.push(line);
            } else {
                used += w;
                out.last_mut().expect("one line at least").extend(spans);
            }
        }
        out.into_iter()
            .map(|spans| Line::from(spans.into_iter().map(bg).collect::<Vec<_>>()))
            .collect()
    }
}

/// Mono terminals get plain ASCII.
fn to_ascii(s: &str) -> String {
    s.replace('−', "-")
        .replace('·', "*")
        .replace('→', "->")
        .replace('≥', ">=")
        .replace('Δ', "d")
        .replace('↑', "^")
        .replace('↓', "v")
}

/// The `rows` lines ending at `focus_end` (or later, if they fit): the first says how many are
/// above when some are cut, the last how many below.
fn window(
    lines: Vec<Line<'static>>,
    starts: &[bool],
    pinned: &[Line<'static>],
    rows: usize,
    focus_end: usize,
    ascii: bool,
) -> Vec<Line<'static>> {
    let total = lines.len();
    if total <= rows || rows == 0 {
        return lines.into_iter().take(rows).collect();
    }
    let end = focus_end.max(rows).min(total);
    let mut start = end - rows;
    let (up, down, keys) = if ascii {
        ("^", "v", "w/s")
    } else {
        ("↑", "↓", "↑↓")
    };
    let keep = rows > pinned.len() + 4;
    if start > 0 {
        // The note (and the ray, when there is room) take the first rows; what follows starts
        // at the start of a line of the derivation, not half-way through one.
        start += 1 + if keep { pinned.len() } else { 0 };
        while start < end && !starts[start] {
            start += 1;
        }
    }
    let mut out: Vec<Line<'static>> = Vec::new();
    if start > 0 {
        out.push(Line::styled(
            format!("{up} {start} more above ({keys} scroll)"),
            LABEL,
        ));
        if keep {
            out.extend(pinned.iter().cloned());
        }
    }
    out.extend(lines.into_iter().take(end).skip(start));
    if end < total && rows > 1 {
        let last = out.len() - 1;
        out[last] = Line::styled(format!("{down} {} more below", total - end + 1), LABEL);
    }
    out
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

    #[test]
    fn heights_are_printed_short() {
        assert_eq!(fmt_height(0.25), "0.25");
        assert_eq!(fmt_height(1.0), "1");
        assert_eq!(fmt_height(-0.5), "-0.5");
        assert_eq!(fmt_height(-0.0001), "0");
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
