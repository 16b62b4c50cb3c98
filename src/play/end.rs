//! What a play session gives back when it ends: why, and its figures, for the transport's
//! goodbye and the server's log line and counters.

use super::pacing::LinkFigures;

/// Why a session ended (for the log, and for how the transport says goodbye).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum End {
    Quit,
    ClientGone,
    Idle,
    Stalled,
    Shutdown,
}

/// A finished session's figures, for the transport's log line and counters.
#[derive(Debug, Clone, Copy, Default)]
pub struct Tally {
    pub frames: u64,
    pub bytes: u64,
    /// Frame ticks that passed without a frame: the session was late, or the link held it.
    pub dropped: u64,
    pub link: LinkFigures,
}
