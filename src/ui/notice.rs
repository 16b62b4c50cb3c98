//! A short note over the status line ("figure written…", "octants hidden…", "this world restarts
//! soon"): what it says and until when. The local game and every play session show notes the
//! same way and for the same time.

use std::time::{Duration, Instant};

/// How long a note shows unless it says otherwise.
pub const NOTICE_FOR: Duration = Duration::from_secs(4);

/// A note and the moment it stops showing.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Notice {
    shown: Option<(String, Instant)>,
}

impl Notice {
    /// Shows `text` from `now` for [`NOTICE_FOR`], replacing any note showing.
    pub fn show(&mut self, text: String, now: Instant) {
        self.show_until(text, now + NOTICE_FOR);
    }

    /// Shows `text` until `until` (a note that stays until the situation changes).
    pub fn show_until(&mut self, text: String, until: Instant) {
        self.shown = Some((text, until));
    }

    /// The note showing at `now`, if any.
    #[must_use]
    pub fn at(&self, now: Instant) -> Option<&str> {
        self.shown
            .as_ref()
            .filter(|(_, until)| now < *until)
            .map(|(t, _)| t.as_str())
    }

    /// Whether a note shows at `now` (a frame must be drawn again when this changes).
    #[must_use]
    pub fn showing(&self, now: Instant) -> bool {
        self.at(now).is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_note_shows_for_its_time_then_goes() {
        let t = Instant::now();
        let mut n = Notice::default();
        assert_eq!(n.at(t), None);
        n.show("hello".into(), t);
        assert_eq!(n.at(t + NOTICE_FOR / 2), Some("hello"));
        assert!(!n.showing(t + NOTICE_FOR));
        n.show_until("stays".into(), t + Duration::from_secs(3600));
        assert_eq!(n.at(t + NOTICE_FOR * 10), Some("stays"));
    }
}
