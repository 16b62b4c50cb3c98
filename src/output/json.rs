//! The ray data of a frame as JSON: camera, one hit per column, and the centre ray's trace.

use serde::Serialize;

use crate::camera::Camera;
use crate::cast::{Cast, Side};

/// The JSON document `render --format json` prints (field order as documented).
#[derive(Debug, Serialize)]
pub struct RayReport {
    pub pos: [f64; 2],
    pub dir: [f64; 2],
    pub plane: [f64; 2],
    pub fov: f64,
    pub size: [usize; 2],
    pub centre_column: usize,
    pub columns: Vec<ColumnReport>,
    pub centre_trace: Vec<StepReport>,
}

/// One column's hit.
#[derive(Debug, Serialize)]
pub struct ColumnReport {
    pub cell: [i64; 2],
    pub side: Side,
    pub perp_dist: f64,
    pub wall_x: f64,
}

/// One DDA step of the centre ray.
#[derive(Debug, Serialize)]
pub struct StepReport {
    pub cell: [i64; 2],
    pub side: Side,
    pub side_dist: [f64; 2],
}

impl RayReport {
    /// Builds the report from a cast whose trace is the centre column (`cols / 2`).
    #[must_use]
    pub fn new(camera: &Camera, cast: &Cast, rows: usize) -> Self {
        let cols = cast.columns.len();
        Self {
            pos: [camera.pos.x, camera.pos.y],
            dir: [camera.dir.x, camera.dir.y],
            plane: [camera.plane.x, camera.plane.y],
            fov: camera.fov_deg(),
            size: [cols, rows],
            centre_column: cols / 2,
            columns: cast
                .columns
                .iter()
                .map(|h| ColumnReport {
                    cell: [h.cell.0, h.cell.1],
                    side: h.side,
                    perp_dist: h.perp_dist,
                    wall_x: h.wall_x,
                })
                .collect(),
            centre_trace: cast.trace.as_ref().map_or_else(Vec::new, |t| {
                t.steps
                    .iter()
                    .map(|s| StepReport {
                        cell: [s.cell.0, s.cell.1],
                        side: s.side,
                        side_dist: [s.side_dist.0, s.side_dist.1],
                    })
                    .collect()
            }),
        }
    }

    /// Serialises with full f64 precision (shortest round-trip form).
    #[must_use]
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("plain numbers and strings always serialise")
    }
}
