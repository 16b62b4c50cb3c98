//! The ray data of a frame as JSON: camera, one hit per column, and the centre ray's trace.

use serde::Serialize;

use crate::camera::Camera;
use crate::render::billboard::SpriteOutcome;
use crate::render::cast::{Cast, Side};
use crate::render::height_cast::{FaceKind, FaceSpan};
use crate::render::sprite_projection::{to_camera_space, Culled};
use crate::world::World;

/// The JSON document `render --format json` prints (field order as documented).
#[derive(Debug, Serialize)]
pub struct RayReport {
    /// Camera position (x, y) in cells.
    pub pos: [f64; 2],
    /// View direction.
    pub dir: [f64; 2],
    /// Camera plane.
    pub plane: [f64; 2],
    /// Horizontal field of view in degrees.
    pub fov: f64,
    /// Frame size in cells (cols, rows).
    pub size: [usize; 2],
    /// The column whose ray `centre_trace` follows (cols / 2).
    pub centre_column: usize,
    /// One ray per column.
    pub columns: Vec<ColumnReport>,
    /// Every cell the centre ray entered, ending with the wall cell.
    pub centre_trace: Vec<StepReport>,
    /// Every sprite's projection, in world order (empty for maps without sprites).
    pub sprites: Vec<SpriteReport>,
}

/// One sprite's projection: where it landed and whether any of it was drawn.
#[derive(Debug, Serialize)]
pub struct SpriteReport {
    /// Index into the map's sprites.
    pub index: usize,
    /// Map position (x, y).
    pub pos: [f64; 2],
    /// Left and right edges in columns, unclipped; `null` when behind the camera.
    pub screen_x: Option<[f64; 2]>,
    /// Columns covered after clipping, [first, end); `null` when culled.
    pub columns: Option<[usize; 2]>,
    /// Depth along the view direction (what the wall depth buffer is compared with);
    /// zero or negative when behind.
    pub distance: f64,
    /// Whether at least one texel reached the screen (false when walls hide it all).
    pub drawn: bool,
    /// `"behind"`, `"offscreen"`, or `null` when projected onto the screen.
    pub culled: Option<Culled>,
}

/// One column's hit (on `Hz` maps, where its window of open rows closed).
#[derive(Debug, Serialize)]
pub struct ColumnReport {
    /// The wall cell hit (x, y).
    pub cell: [i64; 2],
    /// Which grid line was crossed: `x` (a vertical one) or `y`.
    pub side: Side,
    /// Perpendicular distance to the wall (no fisheye).
    pub perp_dist: f64,
    /// Where along the wall face the ray hit, 0–1.
    pub wall_x: f64,
    /// On maps with `Hz` heights, every vertical face drawn in the column, front to back;
    /// absent on flat maps.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spans: Option<Vec<SpanReport>>,
}

/// One vertical face drawn in a column (see [`crate::render::height_cast::FaceSpan`]).
#[derive(Debug, Serialize)]
pub struct SpanReport {
    /// The cell whose solid part the face is.
    pub cell: [i64; 2],
    /// `x` or `y`: which grid line the ray crossed into the face.
    pub side: Side,
    /// Distance along the view direction where the ray meets the face.
    pub perp_dist: f64,
    /// `wall`, `step` or `lintel`.
    pub kind: FaceKind,
    /// The heights the face spans beside the ray's cell, low to high.
    pub z: [f64; 2],
    /// Pixel rows drawn, [top, bottom).
    pub rows: [usize; 2],
}

impl SpanReport {
    fn new(f: &FaceSpan) -> Self {
        Self {
            cell: [f.cell.0, f.cell.1],
            side: f.side,
            perp_dist: f.perp_dist,
            kind: f.kind,
            z: [f.z.0, f.z.1],
            rows: [f.rows.0, f.rows.1],
        }
    }
}

/// One DDA step of the centre ray.
#[derive(Debug, Serialize)]
pub struct StepReport {
    /// The cell entered (x, y).
    pub cell: [i64; 2],
    /// Which grid line was crossed to enter it.
    pub side: Side,
    /// sideDistX/Y after this step.
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
                .enumerate()
                .map(|(x, h)| ColumnReport {
                    cell: [h.cell.0, h.cell.1],
                    side: h.side,
                    perp_dist: h.perp_dist,
                    wall_x: h.wall_x,
                    spans: cast
                        .heights
                        .get(x)
                        .map(|col| col.faces().map(SpanReport::new).collect()),
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
            sprites: Vec::new(),
        }
    }

    /// Adds the sprites of a frame rendered from `world` with `camera`.
    #[must_use]
    pub fn with_sprites(
        mut self,
        world: &World,
        camera: &Camera,
        outcomes: &[SpriteOutcome],
    ) -> Self {
        // Only the world's own sprites are reported (a game's per-frame sprites follow them).
        self.sprites = outcomes
            .iter()
            .filter(|o| o.index < world.sprites.len())
            .map(|o| {
                let pos = world.sprites[o.index].def.pos;
                let (lateral, depth) = to_camera_space(camera, pos);
                let (screen_x, columns, culled) = match o.projection {
                    Ok(p) => (Some([p.left, p.right]), Some([p.cols.0, p.cols.1]), None),
                    Err(Culled::Behind) => (None, None, Some(Culled::Behind)),
                    Err(Culled::Offscreen) => {
                        let w = self.size[0] as f64;
                        let centre = w / 2.0 * (1.0 + lateral / depth);
                        let half = camera.focal_length(self.size[0])
                            * world.sprites[o.index].def.scale.0
                            / depth
                            / 2.0;
                        (
                            Some([centre - half, centre + half]),
                            None,
                            Some(Culled::Offscreen),
                        )
                    }
                };
                SpriteReport {
                    index: o.index,
                    pos: [pos.x, pos.y],
                    screen_x,
                    columns,
                    distance: depth,
                    drawn: o.drawn,
                    culled,
                }
            })
            .collect();
        self
    }

    /// Serialises with full f64 precision (shortest round-trip form).
    #[must_use]
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("plain numbers and strings always serialise")
    }
}
