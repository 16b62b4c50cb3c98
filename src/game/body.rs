//! The player's body in height — where its feet are and how high its eye — and the one rule for
//! whether it may enter a grid cell. Collision, the SSH world (every player) and replays all ask
//! [`Body::can_enter`], so a step refused in one is refused in all.

use crate::map::{Map, Span};

pub use crate::map::STEP_UP;

/// Room a cell must leave above the eye: ceiling − floor ≥ eye + `HEAD_ROOM` to enter it.
pub const HEAD_ROOM: f64 = 0.1;

/// Slack for rounding, so a step of exactly [`STEP_UP`] (or a jump onto exactly 0.5) counts.
const EPS: f64 = 1e-9;

/// A body at a height: what the rule needs to know about the player.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    /// World height of the feet: the floor stood on plus any jump.
    pub feet: f64,
    /// Eye height above the feet without the jump: 0.5 standing, `CROUCH_EYE` crouching, or
    /// between while getting up or down.
    pub eye: f64,
}

impl Body {
    /// Whether the body fits under `span`'s ceiling where it would stand in it: on the cell's
    /// floor, or higher if its feet are above that floor (falling or jumping in). This is
    /// ceiling − floor ≥ eye + [`HEAD_ROOM`] on the level, and "the ceiling is above your head"
    /// when stepping up or down.
    #[must_use]
    pub fn fits_under(self, span: Span) -> bool {
        span.ceil - self.feet.max(span.floor) >= self.eye + HEAD_ROOM - EPS
    }

    /// Whether `span`'s floor is low enough to step onto: at most [`STEP_UP`] above the feet
    /// (a jump lifts the feet, so it climbs higher); any drop is allowed.
    #[must_use]
    pub fn can_step_onto(self, span: Span) -> bool {
        span.floor <= self.feet + STEP_UP + EPS
    }

    /// Whether the body may move into an open span: it can step onto its floor and fits under
    /// its ceiling.
    #[must_use]
    pub fn can_enter_span(self, span: Span) -> bool {
        self.can_step_onto(span) && self.fits_under(span)
    }

    /// Whether the body may move into cell (`i`, `j`): walls and the void never; a floor or door
    /// cell by its span (whether a door is open enough is the door state's question).
    #[must_use]
    pub fn can_enter(self, map: &Map, i: i64, j: i64) -> bool {
        map.span(i, j).is_some_and(|s| self.can_enter_span(s))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const STANDING: f64 = crate::render::view::STANDING_EYE;

    fn span(floor: f64, ceil: f64) -> Span {
        Span { floor, ceil }
    }

    fn on(feet: f64) -> Body {
        Body {
            feet,
            eye: STANDING,
        }
    }

    #[test]
    fn steps_up_to_a_quarter_are_walked_and_any_drop_is_allowed() {
        assert!(on(0.0).can_enter_span(span(0.25, 2.0)));
        assert!(!on(0.0).can_enter_span(span(0.26, 2.0)));
        assert!(on(1.0).can_enter_span(span(1.25, 2.0)));
        assert!(on(0.1).can_enter_span(span(0.35, 2.0)), "rounding");
        for floor in [-4.0, -1.0, 0.0, 0.99] {
            assert!(on(1.0).can_enter_span(span(floor, 3.0)), "{floor}");
        }
    }

    #[test]
    fn a_lifted_body_climbs_higher() {
        // Feet 0.25 up (a jump's top) climbs a ledge of 0.5 and no more.
        assert!(on(0.25).can_step_onto(span(0.5, 2.0)));
        assert!(!on(0.25).can_step_onto(span(0.51, 2.0)));
    }

    #[test]
    fn a_cell_needs_the_eye_plus_head_room() {
        let low = span(0.0, 0.55);
        assert!(!on(0.0).can_enter_span(low));
        let crouched = Body {
            feet: 0.0,
            eye: 0.3,
        };
        assert!(crouched.can_enter_span(low));
        assert!(on(0.0).can_enter_span(span(0.0, 0.6)), "exactly eye + 0.1");
        assert!(!on(0.0).can_enter_span(span(0.0, 0.599)));
    }

    #[test]
    fn the_ceiling_must_clear_the_head_at_the_height_it_is_entered() {
        // Stepping up under a lintel: the ceiling counts from the new floor.
        assert!(!on(0.0).can_enter_span(span(0.25, 0.8)));
        assert!(on(0.0).can_enter_span(span(0.25, 0.85)));
        // Dropping into a cell whose ceiling is below the head: the lintel is in the way.
        assert!(!on(1.0).can_enter_span(span(0.0, 1.5)));
        assert!(on(1.0).can_enter_span(span(0.0, 1.6)));
    }

    #[test]
    fn walls_and_void_are_never_entered_and_plain_floors_always_are() {
        let map = crate::map::grid_map("111\n1N1\n111\n");
        assert!(on(0.0).can_enter(&map, 1, 1));
        assert!(!on(0.0).can_enter(&map, 0, 1));
        assert!(!on(0.0).can_enter(&map, -5, 1));
        // A jump on a flat map (feet up to 0.25) still fits under the ceiling at 1.
        assert!(on(0.25).can_enter(&map, 1, 1));
    }
}
