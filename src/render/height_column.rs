//! What one column of a heights map (`Hz` lines) draws, front to back: the floors and ceilings
//! it sees and every vertical face with its rows. The heights caster fills it, the rasterizer
//! paints it, and the JSON and the ray pane print it.

use crate::map::Cell;
use crate::world::ray::Side;

/// What kind of vertical face a column drew (the JSON `kind`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FaceKind {
    /// A cell solid at every height (a wall, the void) or a door panel.
    Wall,
    /// The side of a neighbour's floor that is higher than the ray's cell's.
    Step,
    /// The side of a neighbour's ceiling that is lower than the ray's cell's.
    Lintel,
}

impl FaceKind {
    /// "wall", "step" or "lintel", as the JSON and the debug pane print it.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            FaceKind::Wall => "wall",
            FaceKind::Step => "step",
            FaceKind::Lintel => "lintel",
        }
    }
}

/// One vertical face drawn in a column on an `Hz` map: a JSON `spans` entry, and a row of the
/// debug pane's height list.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceSpan {
    /// The cell whose solid part the face is (the cell the ray was entering, or a door's cell).
    pub cell: (i64, i64),
    /// What that cell is (its wall type or zone picks the paint).
    pub what: Cell,
    /// Which grid line the ray crossed into the face (y-crossed faces are shaded).
    pub side: Side,
    /// Distance along the view direction where the ray meets the face.
    pub perp_dist: f64,
    /// Where along the face the ray meets it, in [0, 1) (texture column), as [`ColumnHit::wall_x`](crate::world::ray::ColumnHit::wall_x).
    pub wall_x: f64,
    /// A full wall, a step below a raised floor, or a lintel above a lowered ceiling.
    pub kind: FaceKind,
    /// The heights the face spans where it borders the ray's cell, low to high: a step from that
    /// cell's floor up to the neighbour's, a lintel from the neighbour's ceiling up to that
    /// cell's, a wall or door that cell's whole open span.
    pub z: (f64, f64),
    /// Pixel rows drawn, [top, bottom): the part of the face inside the column's open window.
    pub rows: (usize, usize),
}

/// A floor or a ceiling drawn in a column: the rows of a cell's horizontal surface that the ray
/// meets before leaving the cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatSpan {
    /// The cell whose floor or ceiling it is.
    pub cell: (i64, i64),
    /// That cell's zone (0 = none), which picks the paint.
    pub zone: u8,
    /// Ceiling (true) or floor (false).
    pub ceiling: bool,
    /// The surface's height.
    pub z: f64,
    /// Distances along the view direction where the ray entered and left the cell.
    pub dist: (f64, f64),
    /// Pixel rows drawn, [top, bottom).
    pub rows: (usize, usize),
}

/// One run of rows of a column's draw list.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Band {
    /// A floor or ceiling seen through the rows.
    Flat(FlatSpan),
    /// A vertical face (wall, step or lintel).
    Face(FaceSpan),
}

impl Band {
    /// The band's pixel rows, [top, bottom).
    #[must_use]
    pub fn rows(&self) -> (usize, usize) {
        match self {
            Band::Flat(f) => f.rows,
            Band::Face(f) => f.rows,
        }
    }
}

/// Where a column's window of open rows closed: the crossing the ray had reached.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindowClosed {
    /// The cell the ray was entering (or the door cell whose panel it met).
    pub cell: (i64, i64),
    /// Distance along the view direction of that crossing.
    pub perp_dist: f64,
}

/// One column's draw list on an `Hz` map, front to back: every pixel row of the column is in
/// exactly one band (every pixel is written once).
#[derive(Debug, Clone, PartialEq)]
pub struct HeightColumn {
    /// The runs of rows, front to back.
    pub bands: Vec<Band>,
    /// Where the column's window of open rows closed (what its `ColumnHit` reports).
    pub closed: WindowClosed,
}

/// One vertical face with the window of open rows (top, bottom) before and after it: how the
/// face narrowed the column, as the ray pane, the trace's data and its side view explain it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceWindow {
    pub face: FaceSpan,
    pub before: (usize, usize),
    pub after: (usize, usize),
}

impl HeightColumn {
    /// The rows a view of `rows` pixel rows (or the column's bands, if they reach further) has
    /// open before the first band.
    #[must_use]
    pub fn first_window(&self, rows: usize) -> (usize, usize) {
        let reach = self.bands.iter().map(|b| b.rows().1).max().unwrap_or(0);
        (0, rows.max(reach))
    }

    /// Each face front to back with the window it left, the window opening as `window`: a band
    /// reaching the window's top raises it, any other lowers its bottom.
    #[must_use]
    pub fn face_windows(&self, window: (usize, usize)) -> Vec<FaceWindow> {
        let (mut top, mut bottom) = window;
        let mut faces = Vec::new();
        for b in &self.bands {
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
        faces
    }

    /// The vertical faces drawn, front to back (the JSON `spans`).
    pub fn faces(&self) -> impl Iterator<Item = &FaceSpan> {
        self.bands.iter().filter_map(|b| match b {
            Band::Face(f) => Some(f),
            Band::Flat(_) => None,
        })
    }
}
