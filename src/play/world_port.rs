//! A session's line to the world it plays in: messages in (join, leave, held keys), the newest
//! snapshot out. The world task that answers it belongs to the server; a session only talks.

use tokio::sync::{mpsc, watch};

use crate::game::multi::players::{PlayerId, SharedSnapshot};
use crate::game::Input;

/// What a session tells the world.
#[derive(Debug, Clone)]
pub enum WorldMsg {
    Join {
        id: PlayerId,
        name: String,
    },
    Leave {
        id: PlayerId,
    },
    /// The keys held now and the commands since the last message (the same `game::Input` the
    /// local TUI steps with), and the player's view width in columns.
    Input {
        id: PlayerId,
        input: Input,
        view_width: usize,
        /// Whether the client's key releases are known (a browser, a kitty-protocol terminal):
        /// then a key pressed and let go between two ticks still moves one tap.
        releases_known: bool,
    },
}

/// A session's line to the world task; cheap to clone.
#[derive(Debug, Clone)]
pub struct WorldHandle {
    tx: mpsc::Sender<WorldMsg>,
    snapshots: watch::Receiver<SharedSnapshot>,
}

impl WorldHandle {
    /// The line over the world task's inbox and its snapshots.
    #[must_use]
    pub fn new(tx: mpsc::Sender<WorldMsg>, snapshots: watch::Receiver<SharedSnapshot>) -> Self {
        Self { tx, snapshots }
    }

    /// Sends a message; waits if the world's inbox is full (it drains it every tick).
    pub async fn send(&self, msg: WorldMsg) {
        // An error means the world task has ended (server shutdown): nothing left to tell.
        let _ = self.tx.send(msg).await;
    }

    /// A receiver that always holds the newest snapshot.
    #[must_use]
    pub fn snapshots(&self) -> watch::Receiver<SharedSnapshot> {
        self.snapshots.clone()
    }
}
