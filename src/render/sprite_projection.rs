//! Billboard maths (for the world's sprites, `world::sprite`): where a sprite lands on screen (through the inverse camera matrix), which of
//! its 8 views and animation frames shows, and the far-to-near order they are drawn in.

use crate::camera::Camera;
use crate::render::view::View;
use crate::vec2::Vec2;

/// Sprites nearer than this (in depth along the view) are treated as behind the eye.
pub const NEAR_PLANE: f64 = 0.05;

/// Why a sprite is not drawn at all.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Culled {
    /// At or behind the camera plane.
    Behind,
    /// In front, but entirely outside the screen.
    Offscreen,
}

/// A sprite's place on screen for one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// Depth along the view direction (Lode's transformY), what the depth buffer compares.
    pub depth: f64,
    /// Sideways offset in camera-plane units (Lode's transformX).
    pub lateral: f64,
    /// Left and right edges in columns, unclipped (column x samples the ray at camera x = 2x/W − 1).
    pub left: f64,
    /// Right edge in columns, unclipped.
    pub right: f64,
    /// Top and bottom edges in pixel rows, unclipped.
    pub top: f64,
    /// Bottom edge in pixel rows, unclipped.
    pub bottom: f64,
    /// Columns drawn, clipped to the screen: [first, end).
    pub cols: (usize, usize),
    /// Rows drawn, clipped to the screen: [first, end).
    pub rows: (usize, usize),
}

/// The point `p` in camera space: (lateral, depth) with p − pos = lateral·plane + depth·dir.
#[must_use]
pub fn to_camera_space(camera: &Camera, p: Vec2) -> (f64, f64) {
    let rel = p - camera.pos;
    let (dir, plane) = (camera.dir, camera.plane);
    let inv_det = 1.0 / (plane.x * dir.y - dir.x * plane.y);
    let lateral = inv_det * (dir.y * rel.x - dir.x * rel.y);
    let depth = inv_det * (-plane.y * rel.x + plane.x * rel.y);
    (lateral, depth)
}

/// Projects a sprite of `scale` (width, height in cells) standing at height `offset` onto a
/// `w` × `h`-pixel screen.
///
/// # Errors
/// [`Culled`] when nothing of it can be on screen.
pub fn project(
    camera: &Camera,
    view: &View,
    pos: Vec2,
    scale: (f64, f64),
    offset: f64,
    w: usize,
    h: usize,
) -> Result<Projection, Culled> {
    project_on(camera, view, (pos, scale, offset), (w, h), 1.0)
}

/// [`project`] on a screen of `size` pixels each `pixel_height` times as tall as wide (a glyph
/// sub-grid's): widths use the camera's focal length, heights that over `pixel_height`.
/// `sprite` is (position, scale, base height) as [`project`] takes them.
///
/// # Errors
/// [`Culled`] when nothing of it can be on screen.
pub fn project_on(
    camera: &Camera,
    view: &View,
    sprite: (Vec2, (f64, f64), f64),
    size: (usize, usize),
    pixel_height: f64,
) -> Result<Projection, Culled> {
    let (pos, scale, offset) = sprite;
    let (w, h) = size;
    let (lateral, depth) = to_camera_space(camera, pos);
    if depth.is_nan() || depth <= NEAR_PLANE {
        return Err(Culled::Behind);
    }
    let focal = camera.focal_length(w);
    let centre = w as f64 / 2.0 * (1.0 + lateral / depth);
    let half_w = focal * scale.0 / depth / 2.0;
    let focal = focal / pixel_height;
    let horizon = view.horizon(focal, h);
    let top = view.row_of(offset + scale.1, depth, focal, horizon);
    let bottom = view.row_of(offset, depth, focal, horizon);
    let (left, right) = (centre - half_w, centre + half_w);
    let col = |edge: f64| edge.ceil().clamp(0.0, w as f64) as usize;
    let row = |edge: f64| (edge - 0.5).ceil().clamp(0.0, h as f64) as usize;
    let p = Projection {
        depth,
        lateral,
        left,
        right,
        top,
        bottom,
        cols: (col(left), col(right)),
        rows: (row(top), row(bottom)),
    };
    if p.cols.0 >= p.cols.1 || p.rows.0 >= p.rows.1 {
        return Err(Culled::Offscreen);
    }
    Ok(p)
}

/// Which of 8 views shows: 0 = the sprite's front (viewer in its facing direction), counting
/// counter-clockwise on the map in 45° steps (2 = its left side, 4 = its back, 6 = its right).
#[must_use]
pub fn view_index(sprite: Vec2, facing_deg: f64, viewer: Vec2, views: u8) -> usize {
    if views <= 1 {
        return 0;
    }
    let to = viewer - sprite;
    let seen_from = (-to.y).atan2(to.x).to_degrees();
    let rel = seen_from - facing_deg;
    let n = f64::from(views);
    let k = (rel / (360.0 / n)).round();
    if k.is_finite() {
        k.rem_euclid(n) as usize
    } else {
        0
    }
}

/// The animation frame at `time` seconds: ⌊time · fps⌋ mod frames (time comes from the scene).
#[must_use]
pub fn frame_index(frames: u16, fps: f64, time: f64) -> usize {
    if frames <= 1 || fps.is_nan() || fps <= 0.0 || !time.is_finite() {
        return 0;
    }
    ((time * fps).floor().rem_euclid(f64::from(frames))) as usize
}

/// Indices of the projected sprites from far to near (ties: lower index first), the painter's order.
#[must_use]
pub fn far_to_near(depths: &[(usize, f64)]) -> Vec<usize> {
    let mut order: Vec<(usize, f64)> = depths.to_vec();
    order.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    order.into_iter().map(|(i, _)| i).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> Camera {
        // Looking east from (2, 2) with a 90° FOV: |plane| = 1, focal = W / 2.
        Camera::from_angle(Vec2::new(2.0, 2.0), 0.0, 90.0)
    }

    /// A unit sprite standing at (4, 2), two cells ahead of [`cam`], on an 80×60 screen.
    fn ahead(view: &View) -> Result<Projection, Culled> {
        project(&cam(), view, Vec2::new(4.0, 2.0), (1.0, 1.0), 0.0, 80, 60)
    }

    #[test]
    fn camera_space_of_points_ahead_and_to_the_right() {
        let (l, d) = to_camera_space(&cam(), Vec2::new(5.0, 2.0));
        assert!(l.abs() < 1e-12 && (d - 3.0).abs() < 1e-12);
        // South is the viewer's right when facing east.
        let (l, d) = to_camera_space(&cam(), Vec2::new(4.0, 3.0));
        assert!((l - 1.0).abs() < 1e-12 && (d - 2.0).abs() < 1e-12);
        let (_, d) = to_camera_space(&cam(), Vec2::new(1.0, 2.0));
        assert!(d < 0.0);
    }

    #[test]
    fn a_unit_sprite_two_cells_ahead_is_centred_and_sized_by_the_focal_length() {
        let p = ahead(&View::default()).unwrap();
        // focal = 40 → 20 px wide and tall at depth 2, standing on the floor.
        assert!(
            (p.left - 30.0).abs() < 1e-9 && (p.right - 50.0).abs() < 1e-9,
            "{p:?}"
        );
        assert!(
            (p.top - 20.0).abs() < 1e-9 && (p.bottom - 40.0).abs() < 1e-9,
            "{p:?}"
        );
        assert_eq!((p.cols, p.rows), ((30, 50), (20, 40)));
    }

    #[test]
    fn scale_and_offset_move_the_sprite_like_udiv_vdiv_vmove() {
        let v = View::default();
        let p = project(&cam(), &v, Vec2::new(4.0, 2.0), (0.5, 0.25), 0.75, 80, 60).unwrap();
        assert!((p.right - p.left - 10.0).abs() < 1e-9);
        // Hangs from the ceiling: its top is where the wall top is (row 20).
        assert!(
            (p.top - 20.0).abs() < 1e-9 && (p.bottom - 25.0).abs() < 1e-9,
            "{p:?}"
        );
    }

    #[test]
    fn pitch_and_eye_height_shift_sprites_like_walls() {
        let up = View::new(20.0, 0.5);
        let p = ahead(&up).unwrap();
        let shift = 40.0 * 20f64.to_radians().tan();
        assert!((p.top - 20.0 - shift).abs() < 1e-9, "{p:?}");
        let way_up = View::new(45.0, 0.5);
        let far_below = ahead(&way_up);
        assert_eq!(far_below, Err(Culled::Offscreen));
        let crouch = View::new(0.0, 0.25);
        let p = ahead(&crouch).unwrap();
        assert!(
            (p.top - 15.0).abs() < 1e-9 && (p.bottom - 35.0).abs() < 1e-9,
            "{p:?}"
        );
    }

    #[test]
    fn behind_and_offscreen_are_culled_and_edges_are_clipped() {
        let v = View::default();
        let c = cam();
        assert_eq!(
            project(&c, &v, Vec2::new(1.0, 2.0), (1.0, 1.0), 0.0, 80, 60),
            Err(Culled::Behind)
        );
        assert_eq!(
            project(&c, &v, Vec2::new(2.0, 2.0), (1.0, 1.0), 0.0, 80, 60),
            Err(Culled::Behind)
        );
        // 45° off to the right at depth 2 and beyond the edge.
        assert_eq!(
            project(&c, &v, Vec2::new(4.0, 5.0), (1.0, 1.0), 0.0, 80, 60),
            Err(Culled::Offscreen)
        );
        // Straddling the right edge: clipped to the last column.
        let p = project(&c, &v, Vec2::new(4.0, 4.0), (1.0, 1.0), 0.0, 80, 60).unwrap();
        assert!(p.left < 80.0 && p.right > 80.0);
        assert_eq!(p.cols, (p.left.ceil() as usize, 80));
    }

    #[test]
    fn eight_views_by_angle_between_facing_and_viewer() {
        let s = Vec2::new(5.0, 5.0);
        // Facing east; the viewer walks counter-clockwise around it.
        let at = |deg: f64| {
            let a: f64 = deg.to_radians();
            s + Vec2::new(a.cos(), -a.sin()) * 3.0
        };
        for k in 0..8 {
            assert_eq!(view_index(s, 0.0, at(k as f64 * 45.0), 8), k);
            assert_eq!(view_index(s, 0.0, at(k as f64 * 45.0 + 20.0), 8), k);
            assert_eq!(view_index(s, 90.0, at(90.0 + k as f64 * 45.0 - 20.0), 8), k);
        }
        assert_eq!(view_index(s, 0.0, at(180.0), 1), 0);
    }

    #[test]
    fn frames_follow_time_and_wrap() {
        assert_eq!(frame_index(4, 2.0, 0.0), 0);
        assert_eq!(frame_index(4, 2.0, 0.49), 0);
        assert_eq!(frame_index(4, 2.0, 0.5), 1);
        assert_eq!(frame_index(4, 2.0, 2.1), 0);
        assert_eq!(frame_index(4, 2.0, -0.1), 3);
        assert_eq!(frame_index(4, 0.0, 9.0), 0);
        assert_eq!(frame_index(1, 5.0, 9.0), 0);
        assert_eq!(frame_index(4, 2.0, f64::NAN), 0);
    }

    #[test]
    fn depth_sort_is_far_to_near_and_stable_on_ties() {
        let order = far_to_near(&[(0, 1.0), (1, 5.0), (2, 3.0), (3, 5.0), (4, f64::INFINITY)]);
        assert_eq!(order, [4, 1, 3, 2, 0]);
    }
}
