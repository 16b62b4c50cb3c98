//! The figure's colours and text sizes, in one place so the top view, the side view and the
//! legend agree (x-crossings orange and y-crossings blue, as in the ray pane).

use crate::color::Rgb;

/// Paper.
pub const BACKGROUND: Rgb = Rgb::new(250, 250, 246);
/// Grid lines.
pub const GRID: Rgb = Rgb::new(196, 198, 206);
/// Wall cells (solid at every height, on the side view too).
pub const WALL: Rgb = Rgb::new(84, 88, 100);
/// Cells the ray passed through.
pub const VISITED: Rgb = Rgb::new(255, 236, 168);
/// The cell that stopped the ray.
pub const HIT_CELL: Rgb = Rgb::new(246, 176, 168);
/// x-crossings (vertical grid lines).
pub const X_SIDE: Rgb = Rgb::new(222, 112, 16);
/// y-crossings (horizontal grid lines).
pub const Y_SIDE: Rgb = Rgb::new(28, 104, 214);
/// The ray.
pub const RAY: Rgb = Rgb::new(118, 48, 160);
/// The eye and `dir`.
pub const CAMERA: Rgb = Rgb::new(24, 24, 28);
/// The camera plane.
pub const PLANE: Rgb = Rgb::new(34, 140, 72);
/// The perpendicular distance and the hit face.
pub const PERP: Rgb = Rgb::new(212, 32, 40);
/// Text.
pub const TEXT: Rgb = Rgb::new(30, 30, 36);
/// The open window of rows on the side view.
pub const WINDOW: Rgb = Rgb::new(118, 48, 160);
/// Cap height of labels, in pixels (the PNG font at twice its size).
pub const TEXT_SIZE: f64 = 10.0;
/// Cap height of grid numbers.
pub const SMALL: f64 = 10.0;
/// Cap height of the title.
pub const TITLE: f64 = 15.0;
