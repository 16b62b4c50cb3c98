//! The side view of one column on a map with `Hz` heights: distance along the view on the
//! horizontal axis, height up; each cell's floor and ceiling along the ray (solid parts
//! filled), every face the column drew at its distance, and the open window of rows — the
//! wedge of rows from the eye still to be drawn — closing face by face.

use super::drawing::{Anchor, Drawing, Stroke, Tag};
use super::palette::{CAMERA, GRID, TEXT, TEXT_SIZE, WALL, WINDOW, X_SIDE, Y_SIDE};
use crate::map::{Map, Span};
use crate::render::cast::Side;
use crate::render::derivation::{num, Derivation};
use crate::render::height_cast::{FaceSpan, HeightColumn, Projection};

/// Height of the side view in pixels (without its caption).
pub const HEIGHT: f64 = 220.0;

/// The side view's axes: distance along the view across (0 to `t_max`), height up (`z_lo` to
/// `z_hi`), in the box at `origin`.
struct Axes {
    left: f64,
    plot_w: f64,
    top: f64,
    t_max: f64,
    z_lo: f64,
    z_hi: f64,
}

impl Axes {
    /// Axes that hold the eye, the cells along the ray and a little beyond the hit.
    fn new(
        map: &Map,
        d: &Derivation,
        cells: &[((i64, i64), f64)],
        eye: f64,
        box_at: Placed,
    ) -> Self {
        let t_max = d.perp.max(0.5) * 1.1;
        let mut z_lo = eye.min(0.0);
        let mut z_hi = eye.max(1.0);
        for (c, _) in cells {
            if let Some(s) = map.span(c.0, c.1) {
                z_lo = z_lo.min(s.floor);
                z_hi = z_hi.max(s.ceil);
            }
        }
        Self {
            left: box_at.origin.0 + 40.0,
            plot_w: box_at.width - 60.0,
            top: box_at.origin.1,
            t_max,
            z_lo: z_lo - 0.25,
            z_hi: z_hi + 0.25,
        }
    }

    /// The x of distance `t`.
    fn x(&self, t: f64) -> f64 {
        self.left + t.clamp(0.0, self.t_max) / self.t_max * self.plot_w
    }

    /// The y of height `z`.
    fn y(&self, z: f64) -> f64 {
        self.top + (self.z_hi - z.clamp(self.z_lo, self.z_hi)) / (self.z_hi - self.z_lo) * HEIGHT
    }
}

/// Where the side view's box is: its top left corner and its width.
#[derive(Clone, Copy)]
struct Placed {
    origin: (f64, f64),
    width: f64,
}

/// One face the column drew: the distance the open window starts from, the face's distance,
/// the window of rows (top, bottom) after it, and the face.
type Wedge = (f64, f64, usize, usize, FaceSpan);

/// Draws the side view in the box at `origin` of `width` × [`HEIGHT`] pixels.
pub fn draw(
    out: &mut Drawing,
    map: &Map,
    d: &Derivation,
    col: &HeightColumn,
    proj: &Projection,
    origin: (f64, f64),
    width: f64,
) {
    // The cells along the ray with the distances where the ray is in them.
    let mut cells = vec![(d.start_cell, 0.0)];
    cells.extend(d.choices.iter().map(|c| (c.cell, c.crossing())));
    let ax = Axes::new(map, d, &cells, proj.eye, Placed { origin, width });
    let (px, py) = (|t: f64| ax.x(t), |z: f64| ax.y(z));
    out.frame(
        (ax.left, origin.1),
        (ax.plot_w, HEIGHT),
        Stroke::solid(GRID, 1.0),
    );
    // Height marks.
    let mut z = ax.z_lo.ceil();
    while z <= ax.z_hi {
        out.line(
            (ax.left - 4.0, py(z)),
            (ax.left, py(z)),
            Stroke::solid(TEXT, 1.0),
        );
        out.text(
            (ax.left - 6.0, py(z) + TEXT_SIZE / 2.0),
            format!("{}", z + 0.0),
            TEXT_SIZE,
            TEXT,
            Anchor::End,
        );
        z += 1.0;
    }
    // Solid parts of each cell: below its floor, above its ceiling (all of a wall).
    for (k, (c, t0)) in cells.iter().enumerate() {
        let t1 = cells.get(k + 1).map_or(ax.t_max, |n| n.1);
        let (x0, x1) = (px(*t0), px(t1));
        match map.span(c.0, c.1) {
            Some(Span { floor, ceil }) => {
                out.rect(
                    (x0, py(floor)),
                    (x1 - x0, py(ax.z_lo) - py(floor)),
                    WALL,
                    1.0,
                );
                out.rect(
                    (x0, py(ax.z_hi)),
                    (x1 - x0, py(ceil) - py(ax.z_hi)),
                    WALL,
                    1.0,
                );
            }
            None => out.rect((x0, py(ax.z_hi)), (x1 - x0, HEIGHT), WALL, 1.0),
        }
    }
    faces(out, &ax, &wedges(col, proj), proj);
    // The eye.
    out.circle((px(0.0), py(proj.eye)), 5.0, Some(CAMERA), None);
    out.text(
        (ax.left + 4.0, origin.1 - 8.0),
        format!(
            "side view: distance along dir (0 to {}) across, height up; shaded: rows still open",
            num(ax.t_max)
        ),
        TEXT_SIZE,
        TEXT,
        Anchor::Start,
    );
}

/// The window of rows still open after each face the column drew.
fn wedges(col: &HeightColumn, proj: &Projection) -> Vec<Wedge> {
    let mut t_from = 0.0;
    let mut wedges = Vec::new();
    for w in col.face_windows((0, proj.height)) {
        let f = w.face;
        wedges.push((t_from, f.perp_dist, w.after.0, w.after.1, f));
        t_from = f.perp_dist;
    }
    wedges
}

/// Each face at its distance with its label, and before it the wedge of the rows' rays still
/// open from the previous face.
fn faces(out: &mut Drawing, ax: &Axes, wedges: &[Wedge], proj: &Projection) {
    let (px, py) = (|t: f64| ax.x(t), |z: f64| ax.y(z));
    let z_of = |row: f64, t: f64| proj.eye - (row - proj.horizon) * t / proj.focal;
    let mut open = (0usize, proj.height);
    let mut start = 0.0;
    for (k, (_, t, a, b, f)) in wedges.iter().enumerate() {
        // Rows open from the previous face to this one.
        let (ra, rb) = (open.0 as f64, open.1 as f64);
        if ra < rb {
            out.polygon(
                vec![
                    (px(start), py(z_of(ra, start))),
                    (px(*t), py(z_of(ra, *t))),
                    (px(*t), py(z_of(rb, *t))),
                    (px(start), py(z_of(rb, start))),
                ],
                WINDOW,
                0.16,
            );
        }
        let colour = match f.side {
            Side::X => X_SIDE,
            Side::Y => Y_SIDE,
        };
        out.line(
            (px(*t), py(f.z.0)),
            (px(*t), py(f.z.1)),
            Stroke::solid(colour, 4.0),
        );
        let label_y = ax.top + HEIGHT + 14.0 + (k % 2) as f64 * 14.0;
        out.tagged_text(
            (px(*t), label_y),
            format!("{} {}..{}", f.kind.as_str(), f.rows.0, f.rows.1),
            TEXT_SIZE,
            colour,
            Anchor::Middle,
            Tag {
                class: format!("face {}", f.kind.as_str()),
                data: vec![
                    ("rows", format!("{}..{}", f.rows.0, f.rows.1)),
                    ("window", format!("{a}..{b}")),
                ],
            },
        );
        out.line(
            (px(*t), py(ax.z_lo)),
            (px(*t), label_y - TEXT_SIZE - 2.0),
            Stroke::dashed(GRID, 1.0),
        );
        open = (*a, *b);
        start = *t;
    }
}

/// Pixels below the side view's box that its face labels use.
pub const LABELS: f64 = 36.0;
