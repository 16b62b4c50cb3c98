//! The ray pane's lines kept from one frame to the next. A player who stands still, or is
//! between two key taps, has the same centre ray as last frame, and writing its derivation out
//! again (a few dozen formatted numbers, wrapped) was a tenth of an SSH session's frame.

use ratatui::text::Line;

use super::{DebugPane, Heights};
use crate::render::cast::DdaTrace;
use crate::render::derivation::Derivation;

/// The last lines a pane wrote, with everything they were written from; kept by whoever draws
/// every frame (a game loop, an SSH session) and handed to [`DebugPane::lines_kept`].
#[derive(Debug, Default)]
pub struct KeptLines {
    last: Option<(Written, Vec<Line<'static>>)>,
    /// How many times the lines were written out (not reused), for tests.
    writes: usize,
}

impl KeptLines {
    /// How many times the pane's lines were written out rather than reused.
    #[must_use]
    pub fn writes(&self) -> usize {
        self.writes
    }
}

/// Every input of [`DebugPane::lines`], owned: equal inputs write equal lines.
#[derive(Debug, Clone, PartialEq)]
struct Written {
    trace: DdaTrace,
    shown: usize,
    hit_reached: bool,
    derivation: Derivation,
    tex_width: usize,
    focal: f64,
    line_height: f64,
    heights: Option<Heights>,
    view_rows: usize,
    scroll: usize,
    into_setup: usize,
    ascii: bool,
    width: usize,
    rows: usize,
}

impl Written {
    fn of(pane: &DebugPane, rows: usize) -> Self {
        // Every field named, none skipped: a field added to the pane fails to compile here
        // until it is part of what the lines depend on.
        let DebugPane {
            ray,
            derivation,
            tex_width,
            focal,
            line_height,
            heights,
            view_rows,
            scroll,
            into_setup,
            ascii,
            width,
        } = pane;
        Self {
            trace: ray.trace.clone(),
            shown: ray.shown,
            hit_reached: ray.hit_reached,
            derivation: derivation.clone(),
            tex_width: *tex_width,
            focal: *focal,
            line_height: *line_height,
            heights: heights.clone(),
            view_rows: *view_rows,
            scroll: *scroll,
            into_setup: *into_setup,
            ascii: *ascii,
            width: *width,
            rows,
        }
    }

    /// Whether `pane` at `rows` rows is what these lines were written from (compared in place,
    /// without a copy).
    fn is(&self, pane: &DebugPane, rows: usize) -> bool {
        let DebugPane {
            ray,
            derivation,
            tex_width,
            focal,
            line_height,
            heights,
            view_rows,
            scroll,
            into_setup,
            ascii,
            width,
        } = pane;
        self.rows == rows
            && self.shown == ray.shown
            && self.hit_reached == ray.hit_reached
            && self.width == *width
            && self.scroll == *scroll
            && self.into_setup == *into_setup
            && self.ascii == *ascii
            && self.view_rows == *view_rows
            && self.tex_width == *tex_width
            && self.focal == *focal
            && self.line_height == *line_height
            && self.trace == *ray.trace
            && self.derivation == *derivation
            && self.heights == *heights
    }
}

impl DebugPane<'_> {
    /// [`DebugPane::lines`], reusing `kept`'s lines when they were written from the same
    /// inputs (the same ray, steps shown, scroll, width and rows), else writing and keeping them.
    pub fn lines_kept<'k>(&self, rows: usize, kept: &'k mut KeptLines) -> &'k [Line<'static>] {
        let reuse = kept.last.as_ref().is_some_and(|(w, _)| w.is(self, rows));
        if !reuse {
            kept.writes += 1;
            kept.last = Some((Written::of(self, rows), self.lines(rows)));
        }
        kept.last
            .as_ref()
            .map_or(&[], |(_, lines)| lines.as_slice())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::render::cast::trace_column;
    use crate::vec2::Vec2;
    use crate::widget::RevealedTrace;
    use crate::world::World;

    /// A pane of the default map's column 20 of 40, seen from `x`.
    fn pane<'a>(w: &World, cam: &Camera, t: &'a DdaTrace, shown: Option<usize>) -> DebugPane<'a> {
        let ray = shown.map_or(RevealedTrace::full(t), |n| RevealedTrace::partial(t, n));
        DebugPane {
            width: 40,
            ..DebugPane::new(ray, w, cam, (40, 12))
        }
    }

    fn narrow(p: DebugPane<'_>) -> DebugPane<'_> {
        DebugPane { width: 24, ..p }
    }

    #[test]
    fn kept_lines_are_written_again_exactly_when_an_input_changed() {
        let w = World::default_world();
        let cam = Camera::from_angle(Vec2::new(3.5, 3.5), 30.0, 66.0);
        let moved = Camera::from_angle(Vec2::new(3.6, 3.5), 30.0, 66.0);
        let (t, t2) = (
            trace_column(&w.map, &cam, 20, 40),
            trace_column(&w.map, &moved, 20, 40),
        );
        let base = pane(&w, &cam, &t, None);
        // Each step changes one input of the step before (or none, "again"); the count is how
        // many times the lines must have been written by then.
        let wide = |shown: Option<usize>| {
            let ray = shown.map_or(RevealedTrace::full(&t2), |n| RevealedTrace::partial(&t2, n));
            DebugPane {
                width: 40,
                ..DebugPane::new(ray, &w, &moved, (60, 12))
            }
        };
        let steps: Vec<(&str, DebugPane, usize, usize)> = vec![
            ("first", base.clone(), 30, 1),
            ("the same again", base.clone(), 30, 1),
            ("moved", pane(&w, &moved, &t2, None), 30, 2),
            ("a wider view", wide(None), 30, 3),
            ("one step shown", wide(Some(1)), 30, 4),
            ("fewer rows", wide(Some(1)), 8, 5),
            ("narrower", narrow(wide(Some(1))), 8, 6),
            ("scrolled", narrow(wide(Some(1))).scroll(1), 8, 7),
            ("ascii", narrow(wide(Some(1))).scroll(1).ascii(true), 8, 8),
            ("the first", base.clone(), 30, 9),
            ("the first again", base, 30, 9),
        ];
        let mut kept = KeptLines::default();
        let mut before: Option<Vec<Line>> = None;
        for (what, p, rows, writes) in steps {
            let fresh = p.lines(rows);
            let got = p.lines_kept(rows, &mut kept).to_vec();
            assert_eq!(got, fresh, "{what}");
            assert_eq!(kept.writes(), writes, "{what}");
            // A change of input must change the text, or this test could not see stale lines.
            if let Some(b) = before.filter(|_| !what.ends_with("again")) {
                assert_ne!(b, fresh, "{what} writes the same text");
            }
            before = Some(fresh);
        }
    }
}
