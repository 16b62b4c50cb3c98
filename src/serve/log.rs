//! The server's log: one line per event on stderr, each naming its session; `--quiet` silences it.

use std::fmt::Display;
use std::net::SocketAddr;

/// Where log lines go (stderr unless quiet).
#[derive(Debug, Clone, Copy)]
pub struct Log {
    quiet: bool,
}

impl Log {
    /// A log that prints unless `quiet`.
    #[must_use]
    pub fn new(quiet: bool) -> Self {
        Self { quiet }
    }

    /// A server-wide line.
    pub fn server(&self, msg: impl Display) {
        if !self.quiet {
            eprintln!("halfcast serve: {msg}");
        }
    }

    /// A line about session `id` from `peer`.
    pub fn session(&self, id: u64, peer: SocketAddr, msg: impl Display) {
        if !self.quiet {
            eprintln!("halfcast serve: [session {id} {peer}] {msg}");
        }
    }
}
