//! The part of a DDA trace the debugger has revealed so far, shared by the pane and minimap.

use crate::render::cast::{DdaStep, DdaTrace, Side};
use crate::vec2::Vec2;

/// A trace plus how many of its steps are shown; `hit_reached` once all of them are.
#[derive(Debug, Clone, Copy)]
pub struct RevealedTrace<'a> {
    /// The whole trace.
    pub trace: &'a DdaTrace,
    /// Steps revealed so far.
    pub shown: usize,
    /// Whether the hit itself is revealed.
    pub hit_reached: bool,
}

impl<'a> RevealedTrace<'a> {
    /// The whole trace, hit included.
    #[must_use]
    pub fn full(trace: &'a DdaTrace) -> Self {
        Self {
            trace,
            shown: trace.steps.len(),
            hit_reached: true,
        }
    }

    /// Only the first `shown` steps (clamped; all of them means the hit is reached).
    #[must_use]
    pub fn partial(trace: &'a DdaTrace, shown: usize) -> Self {
        let all = trace.steps.len();
        Self {
            trace,
            shown: shown.min(all),
            hit_reached: shown >= all,
        }
    }

    /// The steps revealed so far, in order.
    #[must_use]
    pub fn steps(&self) -> &'a [DdaStep] {
        &self.trace.steps[..self.shown]
    }

    /// The cell the traversal is in now (the start cell before the first step).
    #[must_use]
    pub fn current_cell(&self) -> (i64, i64) {
        self.steps()
            .last()
            .map_or(self.trace.start_cell, |s| s.cell)
    }

    /// How far along the ray (in units of `ray_dir`) the revealed part reaches.
    #[must_use]
    pub fn reach(&self) -> f64 {
        self.steps().last().map_or(0.0, |s| crossing(self.trace, s))
    }

    /// The point on the map where the revealed part of the ray ends.
    #[must_use]
    pub fn end_point(&self, origin: Vec2) -> Vec2 {
        origin + self.trace.ray_dir * self.reach()
    }
}

/// Ray parameter at which `step` crossed its grid line: sideDist − deltaDist of its axis.
#[must_use]
pub fn crossing(trace: &DdaTrace, step: &DdaStep) -> f64 {
    match step.side {
        Side::X => step.side_dist.0 - trace.delta_dist.0,
        Side::Y => step.side_dist.1 - trace.delta_dist.1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::render::cast::trace_column;
    use crate::world::World;

    #[test]
    fn the_last_crossing_is_the_perpendicular_distance() {
        let w = World::default_world();
        let cam = Camera::from_angle(w.map.start.pos(), 70.0, 66.0);
        let t = trace_column(&w.map, &cam, 13, 40);
        let full = RevealedTrace::full(&t);
        assert!((full.reach() - t.hit.perp_dist).abs() < 1e-12);
        assert_eq!(full.current_cell(), t.hit.cell);
        let none = RevealedTrace::partial(&t, 0);
        assert_eq!(none.current_cell(), t.start_cell);
        assert_eq!(none.end_point(cam.pos), cam.pos);
        assert!(!none.hit_reached);
        assert!(RevealedTrace::partial(&t, 999).hit_reached);
    }
}
