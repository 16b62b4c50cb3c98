//! The ray debugger's state: paused or not, which column is traced, how far its DDA is shown.

use crate::render::cast::DdaTrace;
use crate::render::derivation::SETUP_PARTS;

/// How much of the debugged ray's traversal is revealed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Cursor {
    /// The whole traversal, up to and including the hit.
    #[default]
    AtHit,
    /// Only the first `n` steps (0 = still in the start cell).
    Steps(usize),
}

/// Paused-world ray inspection: the column is `None` for the centre ray.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Debugger {
    /// Whether the world is paused for inspection.
    pub paused: bool,
    /// The debugged column (`None` = the centre ray).
    pub column: Option<usize>,
    /// How far the DDA has been stepped.
    pub cursor: Cursor,
    /// How many steps the ray pane is scrolled back from the newest (0 = it follows).
    pub scroll: usize,
    /// Once scrolled back to the setup, how many of its parts further back (0 = its end, up to
    /// `SETUP_PARTS - 1` = `cameraX`): a setup taller than the pane is read a part at a time.
    pub into_setup: usize,
}

impl Debugger {
    /// The traced column in a view `width` columns wide (the centre unless one was picked).
    #[must_use]
    pub fn column_in(&self, width: usize) -> usize {
        let centre = width / 2;
        self.column.unwrap_or(centre).min(width.saturating_sub(1))
    }

    /// How many of `trace`'s steps to show, and whether the hit is reached.
    #[must_use]
    pub fn revealed(&self, trace: &DdaTrace) -> (usize, bool) {
        let all = trace.steps.len();
        match self.cursor {
            Cursor::AtHit => (all, true),
            Cursor::Steps(n) if n >= all => (all, true),
            Cursor::Steps(n) => (n, false),
        }
    }

    /// Freezes the world (showing the full ray) or returns to play on the centre ray.
    pub fn toggle_pause(&mut self) {
        *self = Self {
            paused: !self.paused,
            column: if self.paused { None } else { self.column },
            cursor: Cursor::AtHit,
            scroll: 0,
            into_setup: 0,
        };
    }

    /// Moves the traced column by `by`, clamped to a `width`-column view.
    pub fn move_column(&mut self, by: i32, width: usize) {
        if width == 0 {
            return;
        }
        let now = self.column_in(width) as i64;
        let max = width as i64 - 1;
        self.column = Some((now + i64::from(by)).clamp(0, max) as usize);
        self.follow();
    }

    /// Scrolls the ray pane `by` steps back (negative: forward again), within what is shown of
    /// a trace of `total_steps` steps (the setup, each step shown, and the hit once reached);
    /// past the setup's end, on into the setup a part at a time, to `cameraX`.
    pub fn scroll_by(&mut self, by: i32, total_steps: usize) {
        let (shown, hit) = self.revealed_count(total_steps);
        let max = shown + usize::from(hit);
        let back = (self.scroll + self.into_setup) as i64 + i64::from(by);
        let back = back.clamp(0, (max + SETUP_PARTS - 1) as i64) as usize;
        self.scroll = back.min(max);
        self.into_setup = back - self.scroll;
    }

    /// The ray pane follows the newest step again.
    pub fn follow(&mut self) {
        self.scroll = 0;
        self.into_setup = 0;
    }

    fn revealed_count(&self, all: usize) -> (usize, bool) {
        match self.cursor {
            Cursor::AtHit => (all, true),
            Cursor::Steps(n) if n >= all => (all, true),
            Cursor::Steps(n) => (n, false),
        }
    }

    /// Reveals one more step; from the hit it starts over at the start cell.
    pub fn step(&mut self, total_steps: usize) {
        self.follow();
        self.cursor = match self.cursor {
            Cursor::AtHit => Cursor::Steps(0),
            Cursor::Steps(n) if n + 1 >= total_steps => Cursor::AtHit,
            Cursor::Steps(n) => Cursor::Steps(n + 1),
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_by_default_and_clamped_when_the_view_shrinks() {
        let mut d = Debugger::default();
        assert_eq!(d.column_in(80), 40);
        assert_eq!(d.column_in(0), 0);
        d.move_column(-100, 80);
        assert_eq!(d.column_in(80), 0);
        d.move_column(500, 80);
        assert_eq!(d.column_in(80), 79);
        assert_eq!(d.column_in(10), 9);
    }

    #[test]
    fn stepping_walks_from_the_start_to_the_hit_and_wraps() {
        let mut d = Debugger::default();
        d.toggle_pause();
        assert!(d.paused);
        d.step(3);
        assert_eq!(d.cursor, Cursor::Steps(0));
        d.step(3);
        d.step(3);
        assert_eq!(d.cursor, Cursor::Steps(2));
        d.step(3);
        assert_eq!(d.cursor, Cursor::AtHit);
        d.move_column(5, 80);
        d.toggle_pause();
        assert_eq!(d, Debugger::default());
    }

    #[test]
    fn scrolling_stays_within_what_is_shown_and_a_step_follows_again() {
        let mut d = Debugger::default();
        d.toggle_pause();
        // At the hit of a 4-step trace: the hit, 4 steps and the setup can be focused.
        d.scroll_by(3, 4);
        assert_eq!(d.scroll, 3);
        d.scroll_by(100, 4);
        assert_eq!(d.scroll, 5);
        d.scroll_by(-100, 4);
        assert_eq!(d.scroll, 0);
        d.step(4);
        d.step(4);
        d.scroll_by(5, 4);
        assert_eq!((d.cursor, d.scroll), (Cursor::Steps(1), 1));
        d.step(4);
        assert_eq!(d.scroll, 0);
    }
}
