//! Plain 2-D vector maths shared by the camera, the caster and movement.

use std::ops::{Add, Mul, Sub};

/// A point or direction on the map plane (x east, y south), in cell units.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Vec2 {
    /// East component.
    pub x: f64,
    /// South component.
    pub y: f64,
}

impl Vec2 {
    /// Builds a vector; `const` so tests and defaults can be constants.
    #[must_use]
    pub const fn new(x: f64, y: f64) -> Self {
        Self { x, y }
    }

    /// Euclidean length, used to keep |dir| = 1 and to report |plane|.
    #[must_use]
    pub fn length(self) -> f64 {
        self.x.hypot(self.y)
    }

    /// Rotates counter-clockwise *on screen* (y down) by `radians`, so a
    /// positive angle turns toward north from east, matching the CLI angle.
    #[must_use]
    pub fn rotated(self, radians: f64) -> Self {
        let (s, c) = radians.sin_cos();
        Self::new(self.x * c + self.y * s, -self.x * s + self.y * c)
    }

    /// The perpendicular pointing to the viewer's right (y down): (−y, x).
    #[must_use]
    pub fn right_normal(self) -> Self {
        Self::new(-self.y, self.x)
    }

    /// Dot product, for projections onto the view direction.
    #[must_use]
    pub fn dot(self, o: Self) -> f64 {
        self.x * o.x + self.y * o.y
    }
}

impl Add for Vec2 {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y)
    }
}

impl Sub for Vec2 {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y)
    }
}

impl Mul<f64> for Vec2 {
    type Output = Self;
    fn mul(self, k: f64) -> Self {
        Self::new(self.x * k, self.y * k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotating_east_by_90_degrees_points_north() {
        let v = Vec2::new(1.0, 0.0).rotated(std::f64::consts::FRAC_PI_2);
        assert!((v.x).abs() < 1e-12 && (v.y + 1.0).abs() < 1e-12, "{v:?}");
    }

    #[test]
    fn right_normal_of_east_is_south() {
        assert_eq!(Vec2::new(1.0, 0.0).right_normal(), Vec2::new(-0.0, 1.0));
    }
}
