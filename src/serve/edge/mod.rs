//! The one way in, for every transport. A transport (`ssh/`, `web/`) accepts its connections,
//! learns what its client is (a terminal's name and colours, a page's size) and hands this room
//! its input, a [`crate::play::sink::FrameSink`] and a goodbye; everything else about a player's
//! connection is written here once:
//!
//! - [`admission`]: the limits, a refusal (its log line, metric and counter), the connection's
//!   number, unique across transports.
//! - [`name`]: the name a player is shown to others by.
//! - [`arrival`]: a player in the world and counted live until its place is given back, however
//!   its session ends (a panic included).
//! - [`run`]: the session in a task of its own, a panic there caught and counted, the transport's
//!   goodbye, the end's figures and log line.
//! - [`hooks`]: the server's side of a running session (frame metrics, renames, the leaderboard)
//!   and the world's draining as a note.
//!
//! A new way to connect is its accept loop, its sink and its goodbye; see
//! docs/architecture.md, "Where do I change…".

pub mod admission;
pub mod arrival;
pub mod hooks;
pub mod name;
pub mod run;

#[cfg(test)]
mod run_tests;

/// Which transport carries a session, as logs and metrics name it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Via {
    /// An SSH client, with the terminal name its pty request gave.
    Ssh { term: String },
    /// A browser page over a WebSocket.
    Web,
}

impl Via {
    /// The `transport` label of metrics and JSON log lines.
    #[must_use]
    pub fn label(&self) -> &'static str {
        match self {
            Via::Ssh { .. } => "ssh",
            Via::Web => "web",
        }
    }
}
