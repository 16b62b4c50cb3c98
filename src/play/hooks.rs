//! What a session tells the server it runs in, and asks of it, without knowing it: frame metrics,
//! a name the world changed, and the leaderboard. The server implements these; a test uses the
//! defaults, which do nothing.

use std::time::Duration;

use crate::game::multi::players::{PlayerId, Snapshot};
use crate::ui::results::Board;

/// The server's side of a session. Every method has a do-nothing default.
pub trait Hooks: Send {
    /// A frame of `bytes` went to the client.
    fn frame_sent(&self, _bytes: usize) {}
    /// Frame ticks that passed without a frame (the session was late).
    fn ticks_skipped(&self, _n: u64) {}
    /// How long a frame waited for the link before it could go.
    fn link_waited(&self, _wait: Duration) {}
    /// The link moved the colour level down (or up).
    fn level_stepped(&self, _down: bool) {}
    /// How long the last frame took to render and to encode.
    fn frame_timed(&self, _render: Duration, _encode: Duration) {}
    /// The world gave the player another name than asked for (it was taken).
    fn renamed(&self, _asked: &str, _given: &str) {}
    /// The player came to map `map` as `name`: their own best there will be wanted.
    fn best_wanted(&self, _map: usize, _name: &str) {}
    /// The leaderboard to show with `snap` for player `me` (the finished round's map while the
    /// results show); `None` when the server keeps none.
    fn board(&self, _snap: &Snapshot, _me: PlayerId) -> Option<Board> {
        None
    }
}

/// A server with no metrics and no leaderboard.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoHooks;

impl Hooks for NoHooks {}
