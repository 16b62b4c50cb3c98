//! Whether this world takes new players: what `/healthz` answers a load balancer, so it sends
//! players to a world that will keep them (not one draining for a restart, nor a full one).

use std::sync::atomic::{AtomicBool, Ordering};

use crate::serve::limits::Limiter;

/// A world's readiness as a balancer's health check sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Health {
    /// New players are welcome.
    Accepting,
    /// The world is draining before it stops (SIGTERM): send new players elsewhere.
    Draining,
    /// Every session place is taken: a newcomer would only be told "server full".
    Full,
}

impl Health {
    /// The HTTP status `/healthz` answers with: 200 when accepting, 503 otherwise.
    #[must_use]
    pub fn status(self) -> u16 {
        match self {
            Health::Accepting => 200,
            Health::Draining | Health::Full => 503,
        }
    }

    /// The word in the answer's body (and the check counter's `answer` label).
    #[must_use]
    pub fn word(self) -> &'static str {
        match self {
            Health::Accepting => "accepting",
            Health::Draining => "draining",
            Health::Full => "full",
        }
    }
}

/// What decides a world's [`Health`]: the drain flag and the session places left.
#[derive(Debug)]
pub struct Readiness {
    draining: AtomicBool,
    limiter: Limiter,
}

impl Readiness {
    /// Accepting until [`Readiness::drain`], full while `limiter` has no place left.
    #[must_use]
    pub fn new(limiter: Limiter) -> Self {
        Self {
            draining: AtomicBool::new(false),
            limiter,
        }
    }

    /// From now on the world is draining (for good: a drained world only stops).
    pub fn drain(&self) {
        self.draining.store(true, Ordering::Relaxed);
    }

    /// The world's health now.
    #[must_use]
    pub fn health(&self) -> Health {
        if self.draining.load(Ordering::Relaxed) {
            Health::Draining
        } else if self.limiter.has_room().is_err() {
            Health::Full
        } else {
            Health::Accepting
        }
    }
}
