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
    /// Height of the floor the eye stands on (`Hz` maps; 0 on flat ones), so the eye is at
    /// `ground + eye_z`; play eases it when stepping up or down, a still frame takes the cell's floor.
    pub ground: f64,
}

impl Default for View {
    /// Level gaze at standing height: exactly the picture without pitch or jump.
    fn default() -> Self {
        Self {
            pitch_deg: 0.0,
            eye_z: STANDING_EYE,
            ground: 0.0,
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
            ground: 0.0,
        }
    }

    /// This view standing on a floor at height `ground` (NaN counts as 0; kept within the
    /// heights a map may give).
    #[must_use]
    pub fn on_ground(mut self, ground: f64) -> Self {
        self.ground = if ground.is_nan() {
            0.0
        } else {
            ground.clamp(crate::map::Span::MIN_FLOOR, crate::map::Span::MAX_CEIL)
        };
        self
    }

    /// The eye's height in the world: the floor it stands on plus its height above that floor.
    #[must_use]
    #[inline]
    pub fn eye(&self) -> f64 {
        self.ground + self.eye_z
    }

    /// The clamped copy of this view (fields are public, so callers may have set anything).
    #[must_use]
    pub fn clamped(self) -> Self {
        Self::new(self.pitch_deg, self.eye_z).on_ground(self.ground)
    }

    /// The horizon's pixel row (may be off-screen): h/2 + focal·tan(pitch), kept within ±h of centre.
    #[must_use]
    pub fn horizon(&self, focal: f64, screen_h: usize) -> f64 {
        let h = screen_h as f64;
        let shift = focal * self.clamped().pitch_deg.to_radians().tan();
        h / 2.0 + shift.clamp(-h, h)
    }

    /// Screen row of a point at world height `z` (0 = a flat floor, 1 = its ceiling) and depth
    /// `depth`.
    #[must_use]
    #[inline]
    pub fn row_of(&self, z: f64, depth: f64, focal: f64, horizon: f64) -> f64 {
        horizon - (z - self.eye()) * focal / depth
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

    #[test]
    fn standing_on_a_raised_floor_lifts_the_eye() {
        let v = View::default().on_ground(1.5);
        assert_eq!(v.eye(), 2.0);
        assert_eq!(v.row_of(1.5, 1.0, 40.0, 30.0), 50.0);
        assert_eq!(v.clamped(), v);
        assert_eq!(View::default().on_ground(f64::NAN).ground, 0.0);
        assert_eq!(View::default().on_ground(99.0).ground, 8.0);
    }
}
