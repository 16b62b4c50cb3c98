//! The floor under the player and the eye's smooth way onto it: collision stands on the exact
//! floor at once, the eye eases to it over [`STEP_EASE`] seconds (a step up or down would
//! otherwise jolt the whole picture by a quarter wall in one frame).

/// How long the eye takes to follow the floor after a step up or down, in seconds.
pub const STEP_EASE: f64 = 0.15;

/// The floor the body stands on and where the eye's ground is on its way there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footing {
    /// The floor height of the player's cell: where the feet are for the movement rules.
    pub floor: f64,
    /// The eye's ground when the floor last changed.
    from: f64,
    /// Seconds since the floor last changed (at least [`STEP_EASE`] once settled).
    since: f64,
}

impl Footing {
    /// Standing still on `floor`: the eye's ground is exactly the floor.
    #[must_use]
    pub fn on(floor: f64) -> Self {
        Self {
            floor,
            from: floor,
            since: STEP_EASE,
        }
    }

    /// The ground the eye stands on now (the view's `ground`): from where it was toward the
    /// floor, smoothstep over [`STEP_EASE`]; exactly the floor once settled.
    #[must_use]
    pub fn shown(&self) -> f64 {
        if self.since >= STEP_EASE {
            return self.floor;
        }
        let t = (self.since / STEP_EASE).clamp(0.0, 1.0);
        self.from + (self.floor - self.from) * t * t * (3.0 - 2.0 * t)
    }

    /// Whether the eye has reached the floor.
    #[must_use]
    pub fn settled(&self) -> bool {
        self.since >= STEP_EASE
    }

    /// The player now stands on `floor`. The eye's ground starts from where it is shown now
    /// plus `lift` (what a jump that ended on a higher floor gives back, so the eye does not
    /// dip) and eases to the new floor.
    pub fn move_to(&mut self, floor: f64, lift: f64) {
        if floor == self.floor {
            return;
        }
        self.from = self.shown() + lift;
        self.floor = floor;
        self.since = 0.0;
    }

    /// Lets `dt` seconds pass (frames of 1/fps that add up to [`STEP_EASE`] settle exactly,
    /// whatever the rounding of their sum).
    pub fn advance(&mut self, dt: f64) {
        let since = self.since + dt;
        self.since = if since >= STEP_EASE - 1e-9 {
            STEP_EASE
        } else {
            since
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_eye_eases_onto_a_new_floor_and_then_stands_exactly_on_it() {
        let mut f = Footing::on(0.0);
        assert_eq!(f.shown(), 0.0);
        f.move_to(0.25, 0.0);
        assert_eq!(f.floor, 0.25);
        assert_eq!(f.shown(), 0.0, "no jolt at the moment of the step");
        let mut last = 0.0;
        for _ in 0..4 {
            f.advance(STEP_EASE / 5.0);
            let now = f.shown();
            assert!(now > last && now < 0.25, "{now}");
            last = now;
        }
        f.advance(STEP_EASE / 5.0);
        assert!(f.settled());
        assert_eq!(f.shown(), 0.25);
    }

    #[test]
    fn a_new_step_mid_way_starts_from_where_the_eye_is() {
        let mut f = Footing::on(0.0);
        f.move_to(0.25, 0.0);
        f.advance(STEP_EASE / 2.0);
        let mid = f.shown();
        assert!(
            (mid - 0.125).abs() < 1e-12,
            "smoothstep is half way at half time: {mid}"
        );
        f.move_to(0.5, 0.0);
        assert_eq!(f.shown(), mid);
        f.advance(1.0);
        assert_eq!(f.shown(), 0.5);
        // Down again, with a lift given back by a landing jump.
        f.move_to(0.0, 0.1);
        assert!((f.shown() - 0.6).abs() < 1e-12);
    }
}
