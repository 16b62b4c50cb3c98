//! One column's ray as `halfcast trace` and the browser's `/trace.json`, `/trace.svg` and
//! `/trace.png` ask for it: the pose, view size and column ([`TraceQuery`]), the checks that a
//! ray can start there, and the cast the figure and its data are drawn from ([`TracedRay`]).
//! Both callers go through here, so the page's export is byte for byte what `trace` writes.

pub mod address;
pub mod data;
pub mod values;

use crate::camera::Camera;
use crate::map::{Cell, Map};
use crate::output::figure::{ColumnCast, TraceFigure};
use crate::render::view::{View, STANDING_EYE};
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::World;

/// The view size `trace` draws for when none is given, in cells.
pub const DEFAULT_SIZE: (u16, u16) = (120, 40);

/// Everything that picks one column's ray: pose, field of view, view size, column, and the
/// eye, pitch and doors `trace` also takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraceQuery {
    /// Camera position in cells (`None`: the map's start).
    pub pos: Option<Vec2>,
    /// Facing in degrees, 0 = east, 90 = north (`None`: the map's start).
    pub angle: Option<f64>,
    /// Horizontal field of view in degrees.
    pub fov: f64,
    /// View size in cells (columns, rows).
    pub size: (u16, u16),
    /// The screen column traced, 0-based.
    pub column: usize,
    /// Look up (+) or down (−), in degrees.
    pub pitch: f64,
    /// Eye height in wall heights.
    pub z: f64,
    /// How far every door is open, 0 to 1.
    pub door_open: f64,
}

impl TraceQuery {
    /// Column `column` of the default view, from the map's start, standing, doors shut.
    #[must_use]
    pub fn column(column: usize) -> Self {
        Self {
            pos: None,
            angle: None,
            fov: crate::camera::DEFAULT_FOV_DEG,
            size: DEFAULT_SIZE,
            column,
            pitch: 0.0,
            z: STANDING_EYE,
            door_open: 0.0,
        }
    }

    /// The camera this query casts from in `world` (its start fills what the query leaves out).
    #[must_use]
    pub fn camera(&self, world: &World) -> Camera {
        let start = world.map.start;
        let pos = self.pos.unwrap_or_else(|| start.pos());
        let angle = self.angle.unwrap_or_else(|| start.angle_deg());
        Camera::from_angle(pos, angle, self.fov)
    }

    /// Casts the query's column in `world`, after checking that the column is in the view and
    /// the ray starts in open space (and, on maps with heights, where an eye can be).
    ///
    /// # Errors
    /// What `halfcast trace` prints for a column out of range or a position outside the map,
    /// in a wall or where no eye fits.
    pub fn trace(&self, world: &World) -> Result<TracedRay, String> {
        let map = &world.map;
        let camera = self.camera(world);
        let (cols, rows) = (usize::from(self.size.0), usize::from(self.size.1));
        if self.column >= cols {
            return Err(format!(
                "column {} is out of range: a {cols}-column view has columns 0 to {}",
                self.column,
                cols.saturating_sub(1)
            ));
        }
        let (i, j) = (camera.pos.x.floor() as i64, camera.pos.y.floor() as i64);
        check_start(map, camera.pos, (i, j))?;
        if map.has_heights() {
            crate::game::pose::still_eye(map, camera.pos, self.z)?;
        }
        let mut doors = DoorState::new(map);
        for cell in doors.cells().to_vec() {
            doors.set_open(cell, self.door_open);
        }
        let view = View::new(self.pitch, self.z).on_ground(map.floor_height(i, j));
        let cast = ColumnCast::new(map, &doors, &camera, &view, (cols, rows), self.column);
        Ok(TracedRay {
            camera,
            cast,
            size: (cols, rows),
        })
    }
}

/// Whether a ray may start at `pos` (in cell `(i, j)`): in a floor or door cell.
fn check_start(map: &Map, pos: Vec2, (i, j): (i64, i64)) -> Result<(), String> {
    match map.cell(i, j) {
        Cell::Floor { .. } | Cell::Door(_) => Ok(()),
        Cell::Void => Err(format!(
            "position {},{} is outside the map (cell ({i},{j}))",
            pos.x, pos.y
        )),
        Cell::Wall(_) => Err(format!(
            "position {},{} is inside a wall (cell ({i},{j})): a ray must start in open space",
            pos.x, pos.y
        )),
    }
}

/// One column's ray, cast: what the figure and the page's data are drawn from.
#[derive(Debug, Clone)]
pub struct TracedRay {
    /// The camera it was cast from.
    pub camera: Camera,
    /// The column's trace (and its draw list on maps with heights).
    pub cast: ColumnCast,
    /// The view's size in cells (columns, rows).
    pub size: (usize, usize),
}

impl TracedRay {
    /// The figure of the ray through `map` (the map it was cast in).
    #[must_use]
    pub fn figure<'a>(&'a self, map: &'a Map) -> TraceFigure<'a> {
        self.cast.figure(map, &self.camera, self.size.0)
    }

    /// The figure as an SVG document: what `trace` writes and `/trace.svg` serves.
    #[must_use]
    pub fn svg(&self, map: &Map) -> String {
        self.figure(map).to_svg()
    }

    /// The figure as PNG bytes: what `trace --format png` writes and `/trace.png` serves.
    ///
    /// # Errors
    /// The PNG encoder's message.
    pub fn png(&self, map: &Map) -> Result<Vec<u8>, String> {
        self.figure(map)
            .to_framebuffer()
            .to_png()
            .map_err(|e| e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_column_outside_the_view_and_a_start_in_a_wall_are_refused_as_trace_says() {
        let w = World::default_world();
        let mut q = TraceQuery::column(80);
        q.size = (80, 24);
        assert_eq!(
            q.trace(&w).unwrap_err(),
            "column 80 is out of range: a 80-column view has columns 0 to 79"
        );
        q.column = 40;
        q.pos = Some(Vec2::new(0.5, 0.5));
        assert_eq!(
            q.trace(&w).unwrap_err(),
            "position 0.5,0.5 is inside a wall (cell (0,0)): a ray must start in open space"
        );
        q.pos = Some(Vec2::new(-3.0, 2.0));
        assert!(q.trace(&w).unwrap_err().contains("is outside the map"));
    }

    #[test]
    fn the_traced_ray_is_the_figure_of_the_same_column() {
        let w = World::default_world();
        let mut q = TraceQuery::column(20);
        q.size = (40, 12);
        q.pos = Some(Vec2::new(15.5, 5.5));
        q.angle = Some(90.0);
        let ray = q.trace(&w).unwrap();
        let cam = Camera::from_angle(Vec2::new(15.5, 5.5), 90.0, q.fov);
        let doors = DoorState::new(&w.map);
        let direct = ColumnCast::new(&w.map, &doors, &cam, &View::default(), (40, 12), 20);
        assert_eq!(
            ray.svg(&w.map),
            direct.figure(&w.map, &cam, 40).to_svg(),
            "the same drawing as a cast made by hand"
        );
        assert!(ray.png(&w.map).unwrap().starts_with(b"\x89PNG"));
    }
}
