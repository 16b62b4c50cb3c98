//! The ray debugger's state: paused or not, which column is traced, how far its DDA is shown.

use crate::render::cast::DdaTrace;

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
    }

    /// Reveals one more step; from the hit it starts over at the start cell.
    pub fn step(&mut self, total_steps: usize) {
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
}
