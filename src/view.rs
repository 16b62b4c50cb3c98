//! Vertical look: pitch (the horizon shifted, Permadi's look up/down) and eye height (crouch/jump).
//!
//! These are the classic raycaster tricks, not a true 3-D rotation: walls stay vertical, the whole
//! picture slides up or down, and the eye can rise or sink between floor (0) and ceiling (1).

/// Steepest pitch accepted, in degrees either way.
pub const MAX_PITCH_DEG: f64 = 45.0;

/// Lowest and highest eye heights (in wall heights), so the eye never leaves the room.
pub const EYE_RANGE: (f64, f64) = (0.05, 0.95);

/// Standing eye height: half a wall, the only height the engine core had before.
pub const STANDING_EYE: f64 = 0.5;

/// How the eye looks vertically; the horizontal pose stays in [`crate::Camera`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Degrees, positive = look up (the horizon moves down the screen); clamped to ±[`MAX_PITCH_DEG`].
    pub pitch_deg: f64,
    /// Eye height above the floor in wall heights (0.5 = standing); clamped to [`EYE_RANGE`].
    pub eye_z: f64,
}

impl Default for View {
    /// Level gaze at standing height: exactly the picture without pitch or jump.
    fn default() -> Self {
        Self {
            pitch_deg: 0.0,
            eye_z: STANDING_EYE,
        }
    }
}

impl View {
    /// A view with both values clamped into their ranges (NaN becomes the default).
    #[must_use]
    pub fn new(pitch_deg: f64, eye_z: f64) -> Self {
        let pitch = if pitch_deg.is_nan() { 0.0 } else { pitch_deg };
        let eye = if eye_z.is_nan() { STANDING_EYE } else { eye_z };
        Self {
            pitch_deg: pitch.clamp(-MAX_PITCH_DEG, MAX_PITCH_DEG),
            eye_z: eye.clamp(EYE_RANGE.0, EYE_RANGE.1),
        }
    }

    /// The clamped copy of this view (fields are public, so callers may have set anything).
    #[must_use]
    pub fn clamped(self) -> Self {
        Self::new(self.pitch_deg, self.eye_z)
    }

    /// The horizon's pixel row (may be off-screen): h/2 + focal·tan(pitch), kept within ±h of centre.
    #[must_use]
    pub fn horizon(&self, focal: f64, screen_h: usize) -> f64 {
        let h = screen_h as f64;
        let shift = focal * self.clamped().pitch_deg.to_radians().tan();
        h / 2.0 + shift.clamp(-h, h)
    }

    /// Screen row of a point at height `z` (0 = floor, 1 = ceiling) and depth `depth`.
    #[must_use]
    #[inline]
    pub fn row_of(&self, z: f64, depth: f64, focal: f64, horizon: f64) -> f64 {
        horizon - (z - self.eye_z) * focal / depth
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_view_puts_the_horizon_in_the_middle() {
        assert_eq!(View::default().horizon(50.0, 60), 30.0);
    }

    #[test]
    fn looking_up_moves_the_horizon_down() {
        let v = View::new(45.0, 0.5);
        assert!((v.horizon(20.0, 60) - 50.0).abs() < 1e-9);
        assert!(View::new(-10.0, 0.5).horizon(20.0, 60) < 30.0);
    }

    #[test]
    fn values_are_clamped() {
        let v = View::new(300.0, 7.0);
        assert_eq!((v.pitch_deg, v.eye_z), (MAX_PITCH_DEG, EYE_RANGE.1));
        let v = View::new(f64::NAN, f64::NAN);
        assert_eq!(v, View::default());
        assert_eq!(View::new(-60.0, 1.0).horizon(1000.0, 40), -20.0);
    }

    #[test]
    fn floor_and_ceiling_rows_at_distance_one() {
        let v = View::default();
        assert_eq!(v.row_of(0.0, 1.0, 40.0, 30.0), 50.0);
        assert_eq!(v.row_of(1.0, 1.0, 40.0, 30.0), 10.0);
        let crouch = View::new(0.0, 0.25);
        assert_eq!(crouch.row_of(0.0, 1.0, 40.0, 30.0), 40.0);
    }
}
