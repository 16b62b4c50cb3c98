//! The rounds the writer has not yet written, oldest first: each is saved to the disk queue
//! ([`super::queue`]) as it arrives, or, when the disk will not take it either (SQLite and its
//! queue on one full disk), kept in memory only, up to [`MEMORY_ONLY`] rounds; beyond that a
//! round is dropped and counted. `halfcast_leaderboard_pending_rounds` follows its length.

use std::collections::VecDeque;
use std::path::PathBuf;

use super::queue::DiskQueue;
use super::RoundRecord;
use crate::serve::ops::log::Log;
use crate::serve::ops::metrics;

/// Rounds kept in memory alone (their disk refused them) before more are dropped.
pub const MEMORY_ONLY: usize = 1000;

/// A round waiting for the database, and its file in the queue (none: memory only).
#[derive(Debug)]
struct Pending {
    round: RoundRecord,
    file: Option<PathBuf>,
}

/// The writer's backlog.
#[derive(Debug)]
pub struct Backlog {
    queue: DiskQueue,
    rounds: VecDeque<Pending>,
    memory_only: usize,
}

impl Backlog {
    /// A backlog saving to `queue`, starting with the rounds `found` there.
    #[must_use]
    pub fn new(queue: DiskQueue, found: Vec<(RoundRecord, PathBuf)>) -> Self {
        let rounds: VecDeque<Pending> = found
            .into_iter()
            .map(|(round, file)| Pending {
                round,
                file: Some(file),
            })
            .collect();
        metrics::pending_rounds(rounds.len());
        Self {
            queue,
            rounds,
            memory_only: 0,
        }
    }

    /// Takes a finished round: saved to disk, or kept in memory when the disk refuses it (then
    /// logged), or dropped (logged and counted) when memory holds [`MEMORY_ONLY`] already.
    pub fn push(&mut self, round: RoundRecord, log: Log) {
        let file = match self.queue.save(&round) {
            Ok(path) => Some(path),
            Err(e) if self.memory_only < MEMORY_ONLY => {
                self.memory_only += 1;
                log.server(format_args!(
                    "leaderboard: cannot queue a round in {} ({e}); kept in memory ({} of {MEMORY_ONLY})",
                    self.queue.dir().display(),
                    self.memory_only
                ));
                None
            }
            Err(e) => {
                metrics::db_write("dropped");
                log.server(format_args!(
                    "leaderboard: cannot queue a round in {} ({e}) and {MEMORY_ONLY} wait in \
                     memory already: the round is dropped",
                    self.queue.dir().display()
                ));
                return;
            }
        };
        self.rounds.push_back(Pending { round, file });
        metrics::pending_rounds(self.rounds.len());
    }

    /// The oldest round waiting.
    #[must_use]
    pub fn front(&self) -> Option<&RoundRecord> {
        self.rounds.front().map(|p| &p.round)
    }

    /// The oldest round is in the database now: it leaves the backlog and its file goes.
    pub fn written(&mut self) -> Option<RoundRecord> {
        let p = self.rounds.pop_front()?;
        match &p.file {
            Some(path) => DiskQueue::remove(path),
            None => self.memory_only -= 1,
        }
        metrics::pending_rounds(self.rounds.len());
        Some(p.round)
    }

    /// Rounds waiting.
    #[must_use]
    pub fn len(&self) -> usize {
        self.rounds.len()
    }

    /// Whether none waits.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.rounds.is_empty()
    }

    /// The queue's directory, for logs.
    #[must_use]
    pub fn dir(&self) -> &std::path::Path {
        self.queue.dir()
    }
}
