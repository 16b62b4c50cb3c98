//! The leaderboard's own thread: it owns the SQLite connection, writes each finished round,
//! answers "what is this player's best here", and publishes the boards sessions draw through a
//! `watch` channel. The world task and sessions only ever queue a job (never wait on the
//! disk); a full queue drops the job and counts it.

use std::sync::mpsc::{sync_channel, Receiver, SyncSender, TrySendError};
use std::sync::Arc;

use tokio::sync::watch;

use super::database::Database;
use super::{board_key, Boards, RoundRecord};
use crate::serve::ops::log::Log;
use crate::serve::ops::metrics;

/// Jobs that may wait for the thread; more are dropped.
const QUEUE: usize = 256;

/// What the thread is asked to do.
#[derive(Debug)]
enum Job {
    Record(RoundRecord),
    Lookup {
        map_hash: String,
        mode: String,
        name: String,
    },
    /// Answers once every job queued before it is done.
    Flush(std::sync::mpsc::Sender<()>),
}

/// A line to the leaderboard thread; cheap to clone.
#[derive(Debug, Clone)]
pub struct Leaderboard {
    tx: SyncSender<Job>,
    boards: watch::Receiver<Arc<Boards>>,
    log: Log,
}

impl Leaderboard {
    /// Loads the boards of the `served` maps (hash, mode) from `store`, then starts the thread.
    ///
    /// # Errors
    /// When the boards cannot be read, or the thread cannot start.
    pub fn start(
        mut store: Database,
        served: &[(String, String)],
        log: Log,
    ) -> Result<Self, String> {
        let mut boards = Boards::default();
        for (hash, mode) in served {
            let b = store
                .board(hash, mode, &[])
                .map_err(|e| format!("leaderboard: cannot read the boards: {e}"))?;
            boards.maps.insert(board_key(hash, mode), b);
        }
        let (tx, rx) = sync_channel(QUEUE);
        let (board_tx, board_rx) = watch::channel(Arc::new(boards));
        std::thread::Builder::new()
            .name("halfcast-leaderboard".into())
            .spawn(move || run(store, &rx, &board_tx, log))
            .map_err(|e| format!("leaderboard: cannot start its thread: {e}"))?;
        Ok(Self {
            tx,
            boards: board_rx,
            log,
        })
    }

    /// Queues a finished round for writing (dropped, counted and logged if the queue is full).
    pub fn record(&self, round: RoundRecord) {
        if let Err(TrySendError::Full(_)) = self.tx.try_send(Job::Record(round)) {
            metrics::db_write("dropped");
            self.log
                .server("leaderboard: write queue full, a round was not recorded");
        }
    }

    /// Asks for `name`'s own best on a map (published with the boards when found).
    pub fn lookup(&self, map_hash: &str, mode: &str, name: &str) {
        let _ = self.tx.try_send(Job::Lookup {
            map_hash: map_hash.to_owned(),
            mode: mode.to_owned(),
            name: name.to_owned(),
        });
    }

    /// Waits (up to `patience`) until every round queued so far is written: a server that is
    /// shutting down loses no finished round.
    pub async fn flush(&self, patience: std::time::Duration) {
        let (tx, rx) = std::sync::mpsc::channel();
        let queue = self.tx.clone();
        let _ = tokio::task::spawn_blocking(move || {
            if queue.send(Job::Flush(tx)).is_ok() {
                let _ = rx.recv_timeout(patience);
            }
        })
        .await;
    }

    /// The boards as they are now, and as they change.
    #[must_use]
    pub fn boards(&self) -> watch::Receiver<Arc<Boards>> {
        self.boards.clone()
    }
}

/// The thread's loop: until every sender is gone.
fn run(mut store: Database, rx: &Receiver<Job>, boards: &watch::Sender<Arc<Boards>>, log: Log) {
    while let Ok(job) = rx.recv() {
        match job {
            Job::Record(r) => {
                let names: Vec<String> = r.players.iter().map(|p| p.name.clone()).collect();
                match store.record(&r) {
                    Ok(()) => metrics::db_write("ok"),
                    Err(e) => {
                        metrics::db_write("error");
                        log.server(format_args!("leaderboard: cannot record a round: {e}"));
                        continue;
                    }
                }
                // Everyone asked about before keeps an up-to-date best, and so does everyone
                // who just played.
                let key = board_key(&r.map_hash, &r.mode);
                let mut asked: Vec<String> = boards
                    .borrow()
                    .maps
                    .get(&key)
                    .map(|b| b.bests.keys().cloned().collect())
                    .unwrap_or_default();
                asked.extend(names);
                asked.sort();
                asked.dedup();
                match store.board(&r.map_hash, &r.mode, &asked) {
                    Ok(b) => publish(boards, key, |m| *m = b),
                    Err(e) => log.server(format_args!("leaderboard: cannot read a board: {e}")),
                }
            }
            Job::Lookup {
                map_hash,
                mode,
                name,
            } => match store.best(&map_hash, &mode, &name) {
                Ok(Some(e)) => publish(boards, board_key(&map_hash, &mode), |m| {
                    m.bests.insert(name, e);
                }),
                Ok(None) => {}
                Err(e) => log.server(format_args!("leaderboard: cannot read a best: {e}")),
            },
            Job::Flush(done) => {
                let _ = done.send(());
            }
        }
    }
}

/// Changes one map's board and publishes the boards with a new version.
fn publish(
    boards: &watch::Sender<Arc<Boards>>,
    key: String,
    change: impl FnOnce(&mut super::MapBoard),
) {
    let mut next = Boards::clone(&boards.borrow());
    change(next.maps.entry(key).or_default());
    next.version += 1;
    boards.send_replace(Arc::new(next));
}
