//! Server-wide counters, for the load test and the shutdown summary (atomics; no locks).

use std::sync::atomic::{AtomicU64, Ordering};

/// Totals over all sessions since the server started.
#[derive(Debug, Default)]
pub struct ServeStats {
    pub connections: AtomicU64,
    pub refused: AtomicU64,
    pub sessions_live: AtomicU64,
    pub frames_sent: AtomicU64,
    pub bytes_sent: AtomicU64,
    /// Frame ticks skipped because a session was still sending the previous frame.
    pub frames_dropped: AtomicU64,
    /// Sessions that panicked (each ended that session only).
    pub sessions_failed: AtomicU64,
}

/// A plain copy of [`ServeStats`] at one moment.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StatsSnapshot {
    pub connections: u64,
    pub refused: u64,
    pub sessions_live: u64,
    pub frames_sent: u64,
    pub bytes_sent: u64,
    pub frames_dropped: u64,
    pub sessions_failed: u64,
}

impl ServeStats {
    /// Adds `n` to a counter.
    pub fn add(counter: &AtomicU64, n: u64) {
        counter.fetch_add(n, Ordering::Relaxed);
    }

    /// Reads all counters.
    #[must_use]
    pub fn snapshot(&self) -> StatsSnapshot {
        let r = |c: &AtomicU64| c.load(Ordering::Relaxed);
        StatsSnapshot {
            connections: r(&self.connections),
            refused: r(&self.refused),
            sessions_live: r(&self.sessions_live),
            frames_sent: r(&self.frames_sent),
            bytes_sent: r(&self.bytes_sent),
            frames_dropped: r(&self.frames_dropped),
            sessions_failed: r(&self.sessions_failed),
        }
    }
}
