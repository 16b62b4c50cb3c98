//! What the pane says of a column on a map with heights: each vertical face with the window
//! of rows open before and after it, and where the window closed.

use crate::render::height_cast::{Band, HeightColumn};
pub(super) use crate::render::height_column::FaceWindow;

/// The traced column's draw list on an `Hz` map, as the pane prints it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Heights {
    pub(super) faces: Vec<FaceWindow>,
    pub(super) closed: ((i64, i64), f64),
    /// The closing face's height span (its line is that tall), if a face closed the window.
    pub(super) closing_dz: Option<f64>,
}

impl Heights {
    /// The faces of `col` in a view of `rows` pixel rows, each with the window it left.
    pub(super) fn new(col: &HeightColumn, rows: usize) -> Self {
        let faces = col.face_windows(col.first_window(rows));
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
