//! The derivation's items written as the pane's rows: the setup, each step, the hit.

use ratatui::style::{Modifier, Style};

use super::row::{
    axis, cell_text, fmt_height, pair, side_style, signed, Row, HIT, LABEL, NAME, SIDE_X, VALUE,
    WIDE,
};
use super::DebugPane;
use crate::map::Cell;
use crate::render::cast::Side;
use crate::render::derivation::{compared, num, Choice, PerpFrom, SETUP_PARTS};
use crate::render::raster::texture_x;

/// The rows of each part of the setup (what a scroll into the setup stops at): `cameraX`;
/// `rayDir` (three rows); `deltaDist` and the start cell; X's `step` and `sideDist`; Y's.
pub(super) const SETUP_PART_ROWS: [usize; SETUP_PARTS] = [1, 3, 2, 2, 2];

impl DebugPane<'_> {
    /// The setup: `cameraX`, `rayDir`, `deltaDist` and the start cell, then each axis's `step`
    /// and first `sideDist` (the parts [`SETUP_PART_ROWS`] counts).
    pub(super) fn setup_rows(&self) -> Vec<Row> {
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

    /// Step `c`: folded to one line, or `expanded` with its comparison and the cell it
    /// entered (and the faces there on a heights map); `current` is highlighted.
    pub(super) fn step_rows(&self, c: &Choice, expanded: bool, current: bool) -> Vec<Row> {
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

    /// The hit: what and where, `perp`, the line height and `wall_x` (or not yet).
    pub(super) fn hit_rows(&self) -> Vec<Row> {
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::render::cast::trace_column;
    use crate::vec2::Vec2;
    use crate::widget::revealed::RevealedTrace;
    use crate::world::World;

    #[test]
    fn the_setup_parts_count_every_row_of_the_setup() {
        let w = World::default_world();
        let cam = Camera::from_angle(Vec2::new(15.5, 5.5), 33.0, 66.0);
        let t = trace_column(&w.map, &cam, 7, 40);
        let pane = DebugPane::new(RevealedTrace::full(&t), &w, &cam, (40, 12));
        let rows = pane.setup_rows();
        assert_eq!(SETUP_PART_ROWS.iter().sum::<usize>(), rows.len());
        // Each part starts with the name it is about.
        let firsts = [0, 1, 4, 6, 8].map(|r| rows[r].chunks[0][0].content.to_string());
        assert_eq!(firsts, ["cameraX", "rayDir", "deltaDist", "stepX", "stepY"]);
    }
}
