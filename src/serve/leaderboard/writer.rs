//! The leaderboard's own thread: it owns the database connection, writes each finished round,
//! answers "what is this player's best here", and publishes the boards sessions draw through a
//! `watch` channel. The world task and sessions only ever queue a job (never wait on the
//! disk or the network); a full job queue drops the job and counts it.
//!
//! A round goes to the backlog ([`super::backlog`]: on disk first) and then to the database;
//! while the database is away (not there at start, stopped, its disk full) the backlog grows
//! and the thread tries again after a growing pause ([`super::outage`]), writing the backlog
//! in order once it answers. Reads wait out an outage the same way and log it once. While
//! nothing waits, the thread asks the database whether it answers every [`PROBE_EVERY`], so an
//! outage is seen (logged, counted, `halfcast_leaderboard_connected` at 0) when it starts, not
//! when the next round ends, and the "back after" line gives its length.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{sync_channel, Receiver, RecvTimeoutError, SyncSender, TrySendError};
use std::sync::Arc;
use std::time::Instant;

use tokio::sync::watch;

use super::backlog::Backlog;
use super::database::{self, Access, Database, OpenError};
use super::outage::Outage;
use super::queue::DiskQueue;
use super::{board_key, Boards, RoundRecord};
use crate::serve::ops::log::Log;
use crate::serve::ops::metrics;

/// Jobs that may wait for the thread; more are dropped.
const QUEUE: usize = 256;

/// How often the thread asks a database it is not otherwise using whether it answers.
pub const PROBE_EVERY: std::time::Duration = std::time::Duration::from_secs(1);

/// What the thread is asked to do.
#[derive(Debug)]
enum Job {
    Record(RoundRecord),
    Lookup {
        map_hash: String,
        mode: String,
        name: String,
    },
    /// Answers once every job queued before it is done (or tried, while the database is away).
    Flush(std::sync::mpsc::Sender<()>),
}

/// Where the leaderboard is and where its rounds queue: what the thread needs to open it
/// (again).
#[derive(Debug, Clone)]
pub struct Target {
    /// `--db`: a SQLite file or a `postgres://` URL.
    pub db: PathBuf,
    /// `--db-password-file`, `--db-insecure-password-file`.
    pub access: Access,
    /// `--queue-dir`.
    pub queue_dir: PathBuf,
    /// `--db-start-on-error`: a database that refuses at start (a wrong password, no such
    /// database) is waited for as an outage instead of stopping the start.
    pub start_on_error: bool,
}

/// A line to the leaderboard thread; cheap to clone.
#[derive(Debug, Clone)]
pub struct Leaderboard {
    tx: SyncSender<Job>,
    boards: watch::Receiver<Arc<Boards>>,
    log: Log,
}

impl Leaderboard {
    /// Opens the queue and the database at `target`, loads the boards of the `served` maps
    /// (hash, mode), and starts the thread. A database that cannot be reached now is no
    /// error: the world starts, says so, and its rounds queue until the database answers.
    ///
    /// # Errors
    /// When `--db` is malformed or a password file others may read, the queue directory cannot
    /// be made, the database refuses to be used (a wrong password, no such role or database,
    /// not PostgreSQL, newer schema, another program's, damaged; unless
    /// [`Target::start_on_error`]), its boards cannot be read, or the thread cannot start.
    pub fn start(target: Target, served: &[(String, String)], log: Log) -> Result<Self, String> {
        database::check(&target.db, &target.access)?;
        metrics::db_connected(false);
        let (queue, (found, notes)) = DiskQueue::open(&target.queue_dir)?;
        for n in notes {
            log.server(n);
        }
        if !found.is_empty() {
            log.server(format_args!(
                "leaderboard: {} rounds queued in {} by an earlier run; writing them",
                found.len(),
                target.queue_dir.display()
            ));
        }
        let mut writer = Writer {
            db: None,
            served: served.to_vec(),
            backlog: Backlog::new(queue, found),
            writes: Outage::new(),
            reads: Outage::new(),
            next_probe: Instant::now() + PROBE_EVERY,
            boards: watch::channel(Arc::new(Boards::default())).0,
            log,
            target,
        };
        writer.connect(true)?;
        let (tx, rx) = sync_channel(QUEUE);
        let board_rx = writer.boards.subscribe();
        std::thread::Builder::new()
            .name("halfcast-leaderboard".into())
            .spawn(move || writer.run(&rx))
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

    /// Waits (up to `patience`) until every round queued so far is written, or saved in the
    /// queue when the database is away: a server that is shutting down loses no finished round.
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

/// The thread's state.
struct Writer {
    target: Target,
    /// None while the database has not answered yet.
    db: Option<Database>,
    served: Vec<(String, String)>,
    backlog: Backlog,
    writes: Outage,
    reads: Outage,
    /// When to ask the database whether it answers, if nothing else has by then.
    next_probe: Instant,
    boards: watch::Sender<Arc<Boards>>,
    log: Log,
}

impl Writer {
    /// The thread's loop: until every sender is gone, trying the backlog again when it is due.
    fn run(mut self, rx: &Receiver<Job>) {
        self.catch_up();
        loop {
            let now = Instant::now();
            let waiting = !self.backlog.is_empty() || self.db.is_none() || self.writes.is_away();
            let due = if waiting {
                now + self.writes.until_next_try(now)
            } else {
                self.next_probe
            };
            let job = match rx.recv_timeout(due.saturating_duration_since(now)) {
                Ok(job) => Some(job),
                Err(RecvTimeoutError::Timeout) => None,
                Err(RecvTimeoutError::Disconnected) => return,
            };
            // A round's job tries the database itself; any other is no try.
            let tried = matches!(job, Some(Job::Record(_)));
            match job {
                Some(Job::Record(r)) => {
                    self.backlog.push(r, self.log);
                    if self.writes.is_away() {
                        self.log.server(format_args!(
                            "leaderboard: a round is queued; {} waiting in {}",
                            self.backlog.len(),
                            self.backlog.dir().display()
                        ));
                    }
                    self.catch_up();
                }
                Some(Job::Lookup {
                    map_hash,
                    mode,
                    name,
                }) => self.lookup(&map_hash, &mode, name),
                Some(Job::Flush(done)) => {
                    if !self.backlog.is_empty() {
                        self.log.server(format_args!(
                            "leaderboard: {} rounds wait in {}; a world started with it writes them",
                            self.backlog.len(),
                            self.backlog.dir().display()
                        ));
                    }
                    let _ = done.send(());
                }
                None => {}
            }
            if !tried && Instant::now() >= due {
                self.catch_up();
            }
        }
    }

    /// Opens the database if it is not open; false while it is away. At start (`first`), a
    /// refusal is an error; later it is logged as an outage.
    fn connect(&mut self, first: bool) -> Result<bool, String> {
        if self.db.is_some() {
            return Ok(true);
        }
        let t = &self.target;
        let stop_on_refusal = first && !t.start_on_error;
        match Database::open(&t.db, &t.access) {
            Ok(mut db) => {
                let mut boards = Boards::clone(&self.boards.borrow());
                for (hash, mode) in &self.served {
                    match db.board(hash, mode, &[]) {
                        Ok(b) => {
                            metrics::db_read("ok");
                            boards.maps.insert(board_key(hash, mode), b)
                        }
                        Err(e) => {
                            metrics::db_read("error");
                            let e = format!("cannot read the boards: {e}");
                            if stop_on_refusal {
                                return Err(format!("leaderboard: {e}"));
                            }
                            self.write_failed(&e, first.then_some("is away"));
                            return Ok(false);
                        }
                    };
                }
                boards.version += 1;
                self.boards.send_replace(Arc::new(boards));
                self.db = Some(db);
                metrics::db_connected(true);
                Ok(true)
            }
            Err(OpenError::Refused(e)) if stop_on_refusal => Err(format!(
                "{e} (a mistake to fix, not an outage: --db-start-on-error starts anyway)"
            )),
            Err(OpenError::Refused(e)) => {
                self.write_failed(&e, first.then_some("refuses"));
                Ok(false)
            }
            Err(OpenError::Away(e)) => {
                self.write_failed(&e, first.then_some("is away"));
                Ok(false)
            }
        }
    }

    /// Writes the backlog in order, if a try is due, until it is empty or a write fails; with
    /// nothing to write, asks the database whether it answers.
    fn catch_up(&mut self) {
        let now = Instant::now();
        if !self.writes.may_try(now) {
            return;
        }
        self.next_probe = now + PROBE_EVERY;
        if !matches!(self.connect(false), Ok(true)) {
            return;
        }
        if self.backlog.is_empty() {
            if let Some(Err(e)) = self.db.as_mut().map(Database::ping) {
                self.write_failed(&e, None);
                return;
            }
        }
        let mut wrote = 0;
        // The boards to read again afterwards, once each however many rounds a backlog held,
        // with the names that played on them.
        let mut played: Vec<(String, String, Vec<String>)> = Vec::new();
        let mut failed = None;
        while let (Some(r), Some(db)) = (self.backlog.front(), self.db.as_mut()) {
            if let Err(e) = db.record(r) {
                failed = Some(e);
                break;
            }
            metrics::db_write("ok");
            wrote += 1;
            if let Some(r) = self.backlog.written() {
                let names = r.players.into_iter().map(|p| p.name);
                match played
                    .iter_mut()
                    .find(|p| p.0 == r.map_hash && p.1 == r.mode)
                {
                    Some(p) => p.2.extend(names),
                    None => played.push((r.map_hash, r.mode, names.collect())),
                }
            }
        }
        for (map_hash, mode, names) in played {
            self.refresh(&map_hash, &mode, names);
        }
        if let Some(e) = failed {
            self.write_failed(&e, None);
            return;
        }
        metrics::db_connected(true);
        if let Some(away) = self.writes.recovered(Instant::now()) {
            self.log.server(format_args!(
                "leaderboard {}: back after {:.1} s; {wrote} queued rounds written",
                database::shown(&self.target.db),
                away.as_secs_f64()
            ));
        }
    }

    /// A try to write (or to open the database, or a probe) failed: counted, and logged when it
    /// starts an outage; `at_start` says how the database failed the world's start ("is away",
    /// "refuses").
    fn write_failed(&mut self, e: &str, at_start: Option<&str>) {
        metrics::db_write("error");
        metrics::db_connected(false);
        if self.writes.failed(Instant::now()) {
            let shown = database::shown(&self.target.db);
            let dir = self.backlog.dir().display();
            let pending = self.backlog.len();
            if let Some(how) = at_start {
                self.log.server(format_args!(
                    "leaderboard {shown} {how} ({e}); starting anyway: rounds are queued in \
                     {dir} ({pending} now) and written when it answers"
                ));
            } else {
                self.log.server(format_args!(
                    "leaderboard {shown}: cannot write ({e}); rounds are queued in {dir} \
                     ({pending} now) and written when it answers (logged again when it does)"
                ));
            }
        }
    }

    /// Publishes a map's board after rounds were written on it: everyone asked about before
    /// keeps an up-to-date best, and so does everyone who just played (`names`).
    fn refresh(&mut self, map_hash: &str, mode: &str, mut names: Vec<String>) {
        let key = board_key(map_hash, mode);
        names.extend(
            self.boards
                .borrow()
                .maps
                .get(&key)
                .map(|b| b.bests.keys().cloned().collect::<Vec<_>>())
                .unwrap_or_default(),
        );
        names.sort();
        names.dedup();
        let Some(db) = self.db.as_mut() else { return };
        match db.board(map_hash, mode, &names) {
            Ok(b) => {
                self.read_worked(Instant::now());
                publish(&self.boards, key, |m| *m = b);
            }
            Err(e) => self.read_failed("a board", &e),
        }
    }

    /// Looks up `name`'s best, unless reads are waiting out an outage.
    fn lookup(&mut self, map_hash: &str, mode: &str, name: String) {
        let now = Instant::now();
        if !self.reads.may_try(now) {
            return;
        }
        let Some(db) = self.db.as_mut() else { return };
        match db.best(map_hash, mode, &name) {
            Ok(found) => {
                self.read_worked(now);
                if let Some(e) = found {
                    publish(&self.boards, board_key(map_hash, mode), |m| {
                        m.bests.insert(name, e);
                    });
                }
            }
            Err(e) => self.read_failed("a best", &e),
        }
    }

    /// A read worked: counted, and the end of a reads' outage logged.
    fn read_worked(&mut self, now: Instant) {
        metrics::db_read("ok");
        if let Some(away) = self.reads.recovered(now) {
            self.log.server(format_args!(
                "leaderboard: reads work again after {:.1} s",
                away.as_secs_f64()
            ));
        }
    }

    /// A read failed: counted, logged once per outage; reads pause meanwhile.
    fn read_failed(&mut self, what: &str, e: &str) {
        metrics::db_read("error");
        metrics::db_connected(false);
        if self.reads.failed(Instant::now()) {
            self.log.server(format_args!(
                "leaderboard: cannot read {what}: {e} (reads pause and retry; logged again when \
                 they work)"
            ));
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

/// The default queue directory: beside the host key.
#[must_use]
pub fn default_queue_dir(host_key: &Path) -> PathBuf {
    host_key
        .parent()
        .unwrap_or_else(|| Path::new(""))
        .join(super::queue::DEFAULT_DIR)
}

#[cfg(test)]
mod full_disk;
