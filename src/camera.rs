//! The viewer: position, facing and the camera plane that sets the field of view.

use crate::vec2::Vec2;

/// Field of view used when nothing else is asked for, in degrees.
pub const DEFAULT_FOV_DEG: f64 = 66.0;

/// Where the eye is and where it looks; `plane` ⟂ `dir`, |dir| = 1, |plane| = tan(FOV/2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position in map cells (x east, y south).
    pub pos: Vec2,
    /// Unit view direction.
    pub dir: Vec2,
    /// Camera plane, perpendicular to `dir`, |plane| = tan(FOV/2).
    pub plane: Vec2,
}

impl Camera {
    /// Builds the camera from the CLI convention: degrees, 0 = east, 90 = north.
    #[must_use]
    pub fn from_angle(pos: Vec2, angle_deg: f64, fov_deg: f64) -> Self {
        let (cos, sin) = cos_sin_deg(angle_deg);
        Self::from_dir(pos, Vec2::new(cos, -sin), fov_deg)
    }

    /// Builds the camera from a facing vector (normalised here) and a FOV in degrees.
    #[must_use]
    pub fn from_dir(pos: Vec2, dir: Vec2, fov_deg: f64) -> Self {
        let len = dir.length();
        let dir = if len > 0.0 {
            dir * (1.0 / len)
        } else {
            Vec2::new(1.0, 0.0)
        };
        let half = (fov_deg.to_radians() / 2.0).tan();
        Self {
            pos,
            dir,
            plane: dir.right_normal() * half,
        }
    }

    /// The field of view in degrees, 2·atan(|plane|/|dir|).
    #[must_use]
    pub fn fov_deg(&self) -> f64 {
        2.0 * (self.plane.length() / self.dir.length())
            .atan()
            .to_degrees()
    }

    /// The facing in CLI degrees (0 = east, 90 = north), in (−180, 180].
    #[must_use]
    pub fn angle_deg(&self) -> f64 {
        (-self.dir.y).atan2(self.dir.x).to_degrees()
    }

    /// The facing as the status line and `trace`'s figure print it: degrees in [0, 360), so
    /// both name one heading the same way (181.9, never −178.1).
    #[must_use]
    pub fn heading_deg(&self) -> f64 {
        let h = self.angle_deg().rem_euclid(360.0);
        // rem_euclid of a tiny negative angle rounds up to 360.0 itself.
        if h >= 360.0 {
            0.0
        } else {
            h
        }
    }

    /// Turns by `radians` (positive = to the left, toward north from east), keeping |dir| = 1.
    pub fn rotate(&mut self, radians: f64) {
        let fov = self.fov_deg();
        *self = Self::from_dir(self.pos, self.dir.rotated(radians), fov);
    }

    /// The ray direction through screen column `x` of `width`: dir + plane·(2x/w − 1).
    #[must_use]
    pub fn ray_dir(&self, x: usize, width: usize) -> Vec2 {
        let camera_x = 2.0 * x as f64 / width as f64 - 1.0;
        self.dir + self.plane * camera_x
    }

    /// Pixels per world unit at distance 1: W / (2·tan(FOV/2)), used for both axes.
    #[must_use]
    pub fn focal_length(&self, width: usize) -> f64 {
        width as f64 / (2.0 * self.plane.length())
    }
}

/// cos and sin of an angle in degrees, exact at multiples of 90°: there `to_radians` leaves
/// cos(90°) = 6e-17, so a camera facing north would not look straight north and its centre ray
/// would print deltaDistX 2e16 instead of Lode's 1e30 (docs/learning-dda.md).
fn cos_sin_deg(deg: f64) -> (f64, f64) {
    let r = deg.rem_euclid(360.0);
    if r == 0.0 {
        (1.0, 0.0)
    } else if r == 90.0 {
        (0.0, 1.0)
    } else if r == 180.0 {
        (-1.0, 0.0)
    } else if r == 270.0 {
        (0.0, -1.0)
    } else {
        let a = deg.to_radians();
        (a.cos(), a.sin())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angle_90_faces_north_with_plane_to_the_east() {
        let c = Camera::from_angle(Vec2::new(2.5, 2.5), 90.0, 90.0);
        assert!(c.dir.x.abs() < 1e-12 && (c.dir.y + 1.0).abs() < 1e-12);
        assert!((c.plane.x - 1.0).abs() < 1e-12 && c.plane.y.abs() < 1e-12);
    }

    #[test]
    fn right_angles_face_exactly_along_the_axes() {
        for (deg, dir) in [(0.0, (1.0, 0.0)), (90.0, (0.0, -1.0)), (-90.0, (0.0, 1.0))] {
            let c = Camera::from_angle(Vec2::default(), deg, 66.0);
            assert_eq!((c.dir.x, c.dir.y), dir, "{deg}");
        }
        for deg in [180.0, 540.0] {
            assert_eq!(Camera::from_angle(Vec2::default(), deg, 66.0).dir.x, -1.0);
        }
        // Straight north, the centre ray has rayDirX = 0 exactly.
        assert_eq!(
            Camera::from_angle(Vec2::default(), 90.0, 66.0)
                .ray_dir(40, 80)
                .x,
            0.0
        );
    }

    #[test]
    fn the_heading_is_in_0_to_360() {
        let c = Camera::from_angle(Vec2::default(), -178.14, 66.0);
        assert!((c.heading_deg() - 181.86).abs() < 1e-9);
        assert_eq!(
            Camera::from_angle(Vec2::default(), 0.0, 66.0).heading_deg(),
            0.0
        );
    }

    #[test]
    fn default_fov_plane_length_is_tan_33() {
        let c = Camera::from_angle(Vec2::default(), -45.0, DEFAULT_FOV_DEG);
        assert!((c.plane.length() - 33f64.to_radians().tan()).abs() < 1e-12);
        assert!((c.fov_deg() - 66.0).abs() < 1e-9);
        assert!((c.angle_deg() + 45.0).abs() < 1e-9);
    }

    #[test]
    fn rotation_keeps_unit_direction_and_fov() {
        let mut c = Camera::from_angle(Vec2::default(), 10.0, 70.0);
        for _ in 0..1000 {
            c.rotate(0.037);
        }
        assert!((c.dir.length() - 1.0).abs() < 1e-12);
        assert!((c.fov_deg() - 70.0).abs() < 1e-9);
        assert!(c.dir.dot(c.plane).abs() < 1e-12);
    }

    #[test]
    fn centre_column_of_even_width_is_the_view_direction() {
        let c = Camera::from_angle(Vec2::default(), 30.0, 66.0);
        assert_eq!(c.ray_dir(40, 80), c.dir);
    }
}
