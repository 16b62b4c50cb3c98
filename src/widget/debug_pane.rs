//! The DDA debug pane: one ray's setup, every grid step it took, and where and how it hit.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Widget};

use super::revealed::RevealedTrace;
use crate::camera::Camera;
use crate::cast::{DdaStep, Side};
use crate::map::Cell;
use crate::raster::{heading, texture_x, wall_span};
use crate::world::World;

/// Lines around the step table: column, rayDir, deltaDist, table header; then 3 hit lines.
const FIXED_LINES: usize = 7;

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

fn side_style(side: Side) -> Style {
    Style::new().fg(match side {
        Side::X => SIDE_X,
        Side::Y => SIDE_Y,
    })
}

fn cell_text(c: (i64, i64)) -> String {
    format!("({},{})", c.0, c.1)
}

/// The debugged ray's traversal as text; the last revealed step is highlighted.
#[derive(Debug, Clone, Copy)]
pub struct DebugPane<'a> {
    ray: RevealedTrace<'a>,
    view_width: usize,
    tex_width: usize,
    line_height: f64,
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
        }
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
        out.extend(self.step_rows(rows.saturating_sub(FIXED_LINES)));
        out.extend(self.hit_lines());
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
        Paragraph::new(self.lines(usize::from(area.height))).render(area, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cast::trace_column;
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

    #[test]
    fn infinite_delta_is_shown_as_infinity() {
        assert_eq!(fmt_dist(1e30), "inf");
        assert_eq!(fmt_dist(1.23456), "1.2346");
    }
}
