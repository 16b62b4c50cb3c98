//! The DDA debug pane: one ray's setup, every grid step it took, and where and how it hit. On
//! maps with heights, also every height change along the ray: the cell, the distance, what was
//! drawn there (floor, ceiling, wall, step or lintel, at which heights) in which rows, and where
//! the column's window of open rows closed.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Widget};

use super::revealed::RevealedTrace;
use crate::camera::Camera;
use crate::map::{Cell, Map};
use crate::render::cast::{DdaStep, Side};
use crate::render::height_cast::{Band, HeightColumn};
use crate::render::raster::{heading, texture_x, wall_span};
use crate::world::World;

/// Lines around the step table: column, rayDir, deltaDist, table header; then 3 hit lines.
const FIXED_LINES: usize = 7;

/// Lines above the height list's rows: its title, which says where the window closed.
const HEIGHT_FIXED_LINES: usize = 1;

const LABEL: Style = Style::new().fg(Color::Rgb(128, 132, 146));
const VALUE: Style = Style::new().fg(Color::Rgb(226, 226, 232));
const HEAD: Style = Style::new()
    .fg(Color::Rgb(110, 200, 230))
    .add_modifier(Modifier::BOLD);
const SIDE_X: Color = Color::Rgb(255, 176, 96);
const SIDE_Y: Color = Color::Rgb(126, 192, 255);
const CURRENT_BG: Color = Color::Rgb(64, 60, 22);
const CHANGED: Style = Style::new()
    .fg(Color::Rgb(255, 236, 64))
    .add_modifier(Modifier::BOLD);
const HIT: Style = Style::new()
    .fg(Color::Rgb(255, 96, 96))
    .add_modifier(Modifier::BOLD);

/// A number with 4 decimals, or `inf` for the "never" deltaDist of an axis-parallel ray
/// (ASCII, so it reads the same at every colour level).
#[must_use]
pub fn fmt_dist(v: f64) -> String {
    if v.abs() >= 1e9 {
        "inf".to_owned()
    } else {
        format!("{v:.4}")
    }
}

/// Faces stand out from floors and ceilings in the height list.
fn kind_style(what: &str) -> Style {
    match what {
        "floor" | "ceil" => VALUE,
        _ => Style::new().fg(SIDE_X),
    }
}

fn side_style(side: Side) -> Style {
    Style::new().fg(match side {
        Side::X => SIDE_X,
        Side::Y => SIDE_Y,
    })
}

fn cell_text(c: (i64, i64)) -> String {
    format!("({},{})", c.0, c.1)
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

/// One row of the height list: a band drawn in the traced column.
#[derive(Debug, Clone, PartialEq)]
struct HeightRow {
    cell: (i64, i64),
    /// Where the ray entered the cell (a floor or ceiling) or met the face.
    dist: f64,
    /// `floor`, `ceil`, `wall`, `step` or `lintel`.
    what: &'static str,
    /// The height of a floor or ceiling, or the span of a face.
    z: String,
    rows: (usize, usize),
}

/// The traced column's height changes, ready to print.
#[derive(Debug, Clone, PartialEq)]
struct HeightList {
    rows: Vec<HeightRow>,
    closed: ((i64, i64), f64),
}

impl HeightList {
    /// The bands of `col` in cells where the open span changes along the ray (the first cell
    /// drawn, every cell whose floor or ceiling differs from the one before, every face), front
    /// to back.
    fn new(col: &HeightColumn, map: &Map) -> Self {
        let mut rows = Vec::new();
        let mut i = 0;
        let mut before = None;
        while i < col.bands.len() {
            let cell = band_cell(&col.bands[i]);
            let n = col.bands[i..]
                .iter()
                .take_while(|b| band_cell(b) == cell)
                .count();
            let group = &col.bands[i..i + n];
            let span = map.span(cell.0, cell.1);
            let face = group.iter().any(|b| matches!(b, Band::Face(_)));
            if i == 0 || face || span != before {
                rows.extend(group.iter().map(height_row));
            }
            before = span;
            i += n;
        }
        Self {
            rows,
            closed: (col.closed.cell, col.closed.perp_dist),
        }
    }
}

fn band_cell(b: &Band) -> (i64, i64) {
    match b {
        Band::Flat(f) => f.cell,
        Band::Face(f) => f.cell,
    }
}

fn height_row(b: &Band) -> HeightRow {
    match b {
        Band::Flat(f) => HeightRow {
            cell: f.cell,
            dist: f.dist.0,
            what: if f.ceiling { "ceil" } else { "floor" },
            z: fmt_height(f.z),
            rows: f.rows,
        },
        Band::Face(f) => HeightRow {
            cell: f.cell,
            dist: f.perp_dist,
            what: f.kind.as_str(),
            z: format!("{}..{}", fmt_height(f.z.0), fmt_height(f.z.1)),
            rows: f.rows,
        },
    }
}

/// Columns a height row needs in its aligned form (`cell dist drawn z rows`); narrower panes get
/// the compact one.
const HEIGHT_ROW_WIDTH: usize = 40;

/// The debugged ray's traversal as text; the last revealed step is highlighted.
#[derive(Debug, Clone)]
pub struct DebugPane<'a> {
    ray: RevealedTrace<'a>,
    view_width: usize,
    tex_width: usize,
    line_height: f64,
    focal: f64,
    heights: Option<HeightList>,
    /// Columns the pane has (set when it is drawn): narrow panes get the compact height rows.
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
            ray,
            view_width: view_cells.0,
            tex_width,
            line_height,
            focal,
            heights: None,
            width: usize::MAX,
        }
    }

    /// Also lists the traced column's height changes from its draw list (`Cast::heights` of
    /// an `Hz` map), as far as the DDA is revealed.
    #[must_use]
    pub fn heights(mut self, col: &HeightColumn, map: &Map) -> Self {
        self.heights = Some(HeightList::new(col, map));
        // The hit's line is the face that closed the window, as tall as the heights it spans
        // (a flat wall's formula would say one wall high); none when a floor or ceiling closed it.
        let closing = col.bands.iter().rev().find_map(|b| match b {
            Band::Face(f) if f.cell == col.closed.cell => Some(f),
            _ => None,
        });
        self.line_height = closing.map_or(0.0, |f| {
            (f.z.1 - f.z.0) * self.focal / f.perp_dist.max(1e-9)
        });
        self
    }

    /// All the pane's lines for a pane `rows` tall (the step list is shortened to fit).
    #[must_use]
    pub fn lines(&self, rows: usize) -> Vec<Line<'static>> {
        let t = self.ray.trace;
        let mut out = vec![
            Line::from(vec![
                Span::styled("column    ", LABEL),
                Span::styled(format!("{}", t.column), VALUE),
                Span::styled(format!(" of {}", self.view_width), LABEL),
            ]),
            Line::from(vec![
                Span::styled("rayDir    ", LABEL),
                Span::styled(format!("({:+.4}, {:+.4})", t.ray_dir.x, t.ray_dir.y), VALUE),
            ]),
            Line::from(vec![
                Span::styled("deltaDist ", LABEL),
                Span::styled(
                    format!(
                        "({}, {})",
                        fmt_dist(t.delta_dist.0),
                        fmt_dist(t.delta_dist.1)
                    ),
                    VALUE,
                ),
            ]),
            Line::styled(
                format!(
                    "{:>3} {:<9}{:>10}{:>10}{:>6}",
                    "#", "cell", "sideDistX", "sideDistY", "side"
                ),
                HEAD,
            ),
        ];
        let budget = rows.saturating_sub(FIXED_LINES);
        let Some(list) = &self.heights else {
            out.extend(self.step_rows(budget));
            out.extend(self.hit_lines());
            return out;
        };
        let shown = self.revealed_heights(list);
        // Both lists shorten to fit; the height list gets at least half of a tight pane.
        let (need_steps, need_heights) = (self.ray.shown + 1, HEIGHT_FIXED_LINES + shown.len());
        let heights = need_heights.min(budget.saturating_sub(need_steps).max(budget.div_ceil(2)));
        out.extend(self.step_rows(budget - heights));
        out.extend(self.hit_lines());
        out.extend(self.height_lines(list, &shown, heights));
        out
    }

    /// The height rows revealed so far: those in the start cell and the cells stepped into.
    fn revealed_heights<'l>(&self, list: &'l HeightList) -> Vec<&'l HeightRow> {
        let t = self.ray.trace;
        let mut cells = vec![t.start_cell];
        cells.extend(t.steps[..self.ray.shown].iter().map(|s| s.cell));
        list.rows
            .iter()
            .filter(|r| self.ray.hit_reached || cells.contains(&r.cell))
            .collect()
    }

    /// The height list: a title saying where the column's window closed (cell, distance), then
    /// its rows (elided in the middle to fit `budget` lines), each `cell dist drawn z rows`.
    fn height_lines(
        &self,
        list: &HeightList,
        shown: &[&HeightRow],
        budget: usize,
    ) -> Vec<Line<'static>> {
        if budget == 0 {
            return Vec::new();
        }
        let title = if self.ray.hit_reached {
            let (cell, dist) = list.closed;
            vec![
                Span::styled("heights ", HEAD),
                Span::styled("closed ", LABEL),
                Span::styled(cell_text(cell), HIT),
                Span::styled(format!(" {dist:.2}"), VALUE),
            ]
        } else {
            vec![
                Span::styled("heights ", HEAD),
                Span::styled("so far", LABEL),
            ]
        };
        let mut out = vec![Line::from(title)];
        let room = budget - HEIGHT_FIXED_LINES;
        let compact = self.width < HEIGHT_ROW_WIDTH;
        let row = |r: &&HeightRow| {
            if compact {
                // One space between the fields and what was drawn as its initial (f floor, c ceil,
                // w wall, s step, l lintel; coloured as in the wide form), so the rows column
                // still fits a compact pane.
                let initial: String = r.what.chars().take(1).collect();
                return Line::from(vec![
                    Span::styled(cell_text(r.cell), VALUE),
                    Span::styled(format!(" {:.2}", r.dist), VALUE),
                    Span::styled(format!(" {initial}"), kind_style(r.what)),
                    Span::styled(format!(" {}", r.z), VALUE),
                    Span::styled(format!(" {}..{}", r.rows.0, r.rows.1), LABEL),
                ]);
            }
            Line::from(vec![
                Span::styled(format!("{:<8}", cell_text(r.cell)), VALUE),
                Span::styled(format!("{:>6}", format!("{:.2}", r.dist)), VALUE),
                Span::styled(format!(" {:<6}", r.what), kind_style(r.what)),
                Span::styled(format!(" {:<9}", r.z), VALUE),
                Span::styled(format!(" {}..{}", r.rows.0, r.rows.1), LABEL),
            ])
        };
        if shown.len() <= room {
            out.extend(shown.iter().map(row));
        } else if room > 0 {
            // The first rows and the last (where the window closed), the middle counted.
            let tail = (room.saturating_sub(1) / 2).max(1);
            let head = room.saturating_sub(1 + tail);
            out.extend(shown[..head].iter().map(row));
            if room > tail {
                let hidden = shown.len() - head - tail;
                out.push(Line::styled(format!("{:<8}{hidden} more", "..."), LABEL));
            }
            out.extend(shown[shown.len() - tail..].iter().map(row));
        }
        out
    }

    /// Table rows: step 0 is the start cell, then one per revealed step, elided in the middle.
    fn step_rows(&self, budget: usize) -> Vec<Line<'static>> {
        let t = self.ray.trace;
        let total = self.ray.shown + 1;
        let row = |i: usize| {
            let current = i + 1 == total;
            if i == 0 {
                self.row(0, t.start_cell, t.initial_side_dist, None, current)
            } else {
                let s: &DdaStep = &t.steps[i - 1];
                self.row(i, s.cell, s.side_dist, Some(s.side), current)
            }
        };
        if total <= budget.max(1) {
            return (0..total).map(row).collect();
        }
        if budget <= 2 {
            return vec![row(total - 1)];
        }
        let tail = ((budget - 1) / 2).max(1);
        let head = budget - 1 - tail;
        let hidden = total - head - tail;
        let mut rows: Vec<Line> = (0..head).map(row).collect();
        rows.push(Line::styled(
            format!(
                "{:>3} {hidden} more step{}",
                "...",
                if hidden == 1 { "" } else { "s" }
            ),
            LABEL,
        ));
        rows.extend((total - tail..total).map(row));
        rows
    }

    fn row(
        &self,
        i: usize,
        cell: (i64, i64),
        side_dist: (f64, f64),
        side: Option<Side>,
        current: bool,
    ) -> Line<'static> {
        let base = if current {
            VALUE.bg(CURRENT_BG).add_modifier(Modifier::BOLD)
        } else {
            VALUE
        };
        let changed = |axis: Side| {
            if current && side == Some(axis) {
                CHANGED.bg(CURRENT_BG)
            } else {
                base
            }
        };
        let side_span = match side {
            Some(s) => Span::styled(format!("{:>6}", s.as_str()), side_style(s).patch(base)),
            None => Span::styled(format!("{:>6}", "start"), LABEL.patch(base)),
        };
        Line::from(vec![
            Span::styled(format!("{i:>3} {:<9}", cell_text(cell)), base),
            Span::styled(format!("{:>10}", fmt_dist(side_dist.0)), changed(Side::X)),
            Span::styled(format!("{:>10}", fmt_dist(side_dist.1)), changed(Side::Y)),
            side_span,
        ])
    }

    fn hit_lines(&self) -> Vec<Line<'static>> {
        let t = self.ray.trace;
        if !self.ray.hit_reached {
            return vec![Line::from(vec![
                Span::styled("hit       ", LABEL),
                Span::styled(
                    format!("not reached (step {} of {})", self.ray.shown, t.steps.len()),
                    VALUE,
                ),
            ])];
        }
        let h = &t.hit;
        let what = match h.what {
            Cell::Wall(d) => format!("wall {d}"),
            Cell::Void => "void".to_owned(),
            Cell::Floor { .. } => "floor".to_owned(),
            Cell::Door(_) => "door".to_owned(),
        };
        vec![
            Line::from(vec![
                Span::styled("hit       ", LABEL),
                Span::styled(cell_text(h.cell), HIT),
                Span::styled(format!(" {what}"), VALUE),
                Span::styled("  side ", LABEL),
                Span::styled(h.side.as_str(), side_style(h.side)),
            ]),
            Line::from(vec![
                Span::styled("perp      ", LABEL),
                Span::styled(fmt_dist(h.perp_dist), VALUE),
                Span::styled("  wall_x ", LABEL),
                Span::styled(format!("{:.4}", h.wall_x), VALUE),
            ]),
            Line::from(vec![
                Span::styled("texture x ", LABEL),
                Span::styled(format!("{}", texture_x(h, self.tex_width)), VALUE),
                Span::styled(format!(" of {}", self.tex_width), LABEL),
                Span::styled("  line ", LABEL),
                Span::styled(format!("{:.2}", self.line_height), VALUE),
                Span::styled(" px", LABEL),
            ]),
        ]
    }
}

impl Widget for DebugPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let area = area.intersection(buf.area);
        if area.is_empty() {
            return;
        }
        let pane = DebugPane {
            width: usize::from(area.width),
            ..self
        };
        let lines = pane.lines(usize::from(area.height));
        Paragraph::new(lines).render(area, buf);
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
        let cam = Camera::from_angle(Vec2::new(15.5, 5.5), 90.0, 66.0);
        (w, cam)
    }

    #[test]
    fn centre_ray_north_lists_every_step_and_the_hit() {
        let (w, cam) = setup();
        let t = trace_column(&w.map, &cam, 20, 40);
        let pane = DebugPane::new(RevealedTrace::full(&t), &w, &cam, (40, 12));
        let lines = text(&pane.lines(30));
        insta::assert_snapshot!(lines.join("\n"));
    }

    #[test]
    fn a_long_list_keeps_the_start_and_the_hit() {
        let (w, _) = setup();
        let cam = Camera::from_angle(Vec2::new(1.5, 5.5), 0.0, 66.0);
        let t = trace_column(&w.map, &cam, 20, 40);
        assert!(t.steps.len() > 8, "{}", t.steps.len());
        let pane = DebugPane::new(RevealedTrace::full(&t), &w, &cam, (40, 12));
        let lines = text(&pane.lines(13));
        assert_eq!(lines.len(), 13);
        assert!(lines[4].starts_with("  0 (1,5)"), "{lines:#?}");
        assert!(lines.iter().any(|l| l.contains("more steps")));
        let last_step = format!("{:>3}", t.steps.len());
        assert!(lines[9].starts_with(&last_step), "{lines:#?}");
        assert!(lines[10].starts_with("hit"));
    }

    #[test]
    fn while_stepping_the_hit_is_not_shown_yet() {
        let (w, cam) = setup();
        let t = trace_column(&w.map, &cam, 20, 40);
        let pane = DebugPane::new(RevealedTrace::partial(&t, 2), &w, &cam, (40, 12));
        let lines = text(&pane.lines(30));
        assert_eq!(lines.len(), 4 + 3 + 1);
        assert!(lines[6].starts_with("  2 (15,3)"), "{lines:#?}");
        assert!(lines[7].contains("not reached (step 2 of 5)"), "{lines:#?}");
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

    /// The heights corridor seen from its west end in a 40 × 24 view, column 20 traced.
    fn heights_cast() -> (World, Camera, crate::render::cast::Cast) {
        let w = heights_world();
        let cam = Camera::from_angle(Vec2::new(1.5, 1.5), 0.0, 66.0);
        let view = crate::render::view::View::default();
        let proj = crate::render::height_cast::Projection::new(&cam, &view, 40, 24);
        let doors = crate::world::door::DoorState::new(&w.map);
        let cast =
            crate::render::height_cast::cast_heights(&w.map, &doors, &cam, &proj, 40, Some(20));
        (w, cam, cast)
    }

    fn heights_pane_lines(shown: Option<usize>, rows: usize) -> Vec<String> {
        let (w, cam, cast) = heights_cast();
        let t = cast.trace.as_ref().unwrap();
        let ray = match shown {
            Some(n) => RevealedTrace::partial(t, n),
            None => RevealedTrace::full(t),
        };
        let pane = DebugPane::new(ray, &w, &cam, (40, 12)).heights(&cast.heights[20], &w.map);
        text(&pane.lines(rows))
    }

    #[test]
    fn a_compact_pane_keeps_every_height_rows_column_on_screen() {
        let (w, cam, cast) = heights_cast();
        let t = cast.trace.as_ref().unwrap();
        let pane = DebugPane::new(RevealedTrace::full(t), &w, &cam, (40, 12))
            .heights(&cast.heights[20], &w.map);
        let area = Rect::new(0, 0, 28, 40);
        let mut buf = Buffer::empty(area);
        pane.render(area, &mut buf);
        let rows: Vec<String> = (0..40)
            .map(|y| (0..28).map(|x| buf[(x, y)].symbol()).collect::<String>())
            .collect();
        let list = rows
            .iter()
            .skip_while(|r| !r.starts_with("heights"))
            .skip(1)
            .take_while(|r| r.starts_with('('))
            .collect::<Vec<_>>();
        assert!(list.len() >= 3, "{rows:#?}");
        for r in list {
            let last = r.trim_end().rsplit(' ').next().unwrap();
            assert!(
                last.contains("..") && last.split("..").all(|n| n.parse::<usize>().is_ok()),
                "the rows column is cut off: {r:?}"
            );
        }
    }

    #[test]
    fn on_a_heights_map_every_height_change_is_listed_with_its_rows_and_where_it_closed() {
        let lines = heights_pane_lines(None, 40);
        let all = lines.join("\n");
        insta::assert_snapshot!(all);
        assert!(all.contains("height"), "{all}");
        // The start cell's floor and ceiling, the step at x = 3, the lintel at x = 5, the wall.
        for want in [
            "(1,1)",
            "(3,1)     1.50 step   0..0.25   17..22",
            "lintel 0.7..1",
            "wall",
            "heights closed (8,1) 6.50",
            // The closing wall shows only its 0.25..0.7 beside (7,1): 0.45 of the flat 4.74 px.
            "line 2.13 px",
        ] {
            assert!(all.contains(want), "{want:?} missing:\n{all}");
        }
        // Cells with the same span as the one before are not listed again.
        let list = &all[all.find("heights closed").unwrap()..];
        for same in ["(4,1)", "(6,1)", "(7,1)"] {
            assert!(
                !list.contains(same),
                "{same} repeats its neighbour:\n{list}"
            );
        }
    }

    #[test]
    fn the_height_list_follows_the_stepping_and_fits_a_short_pane() {
        // Stepped into (2,1) only: its floor, nothing from the step at x = 3 yet, no closing.
        let lines = heights_pane_lines(Some(1), 40).join("\n");
        assert!(lines.contains("(2,1)     0.50 floor"), "{lines}");
        assert!(
            !lines.contains("0..0.25") && !lines.contains("closed"),
            "{lines}"
        );
        // A short pane keeps the ends of both lists: the last height row is the closing wall.
        let lines = heights_pane_lines(None, 14);
        assert_eq!(lines.len(), 14, "{lines:#?}");
        assert!(lines.iter().any(|l| l.starts_with("hit")), "{lines:#?}");
        assert!(lines.contains(&"heights closed (8,1) 6.50".to_owned()));
        assert!(lines.iter().any(|l| l.contains("more")), "{lines:#?}");
        assert!(lines.last().unwrap().contains(" wall "), "{lines:#?}");
    }

    #[test]
    fn heights_are_printed_short() {
        assert_eq!(fmt_height(0.25), "0.25");
        assert_eq!(fmt_height(1.0), "1");
        assert_eq!(fmt_height(-0.5), "-0.5");
        assert_eq!(fmt_height(-0.0001), "0");
    }

    #[test]
    fn infinite_delta_is_shown_as_infinity() {
        assert_eq!(fmt_dist(1e30), "inf");
        assert_eq!(fmt_dist(1.23456), "1.2346");
    }
}
