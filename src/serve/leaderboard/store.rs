//! The leaderboard's SQLite file: its schema and migrations, opening it without harming it, one
//! finished round written in one transaction, and the rankings read back.
//!
//! Several worlds on one host share one file (`--db` the same path): it is in WAL mode, so
//! reading never waits for a write, and a writer waits up to [`BUSY`] for another's
//! transaction instead of failing with "database is locked". Every write and every migration
//! step takes the write lock first (`BEGIN IMMEDIATE`), and a migration re-reads the version
//! under that lock, so two worlds starting at once migrate the file once.
//!
//! The schema's version is SQLite's `user_version`; `MIGRATIONS` holds the steps from an
//! empty file, one per version. A file of a newer version is refused (a newer halfcast wrote
//! it), and so is one SQLite cannot read (corrupt, not a database) or cannot lock: those are
//! start-up errors, and the file is not written to.

use std::path::Path;
use std::time::Duration;

use rusqlite::{params, Connection, OpenFlags, OptionalExtension, TransactionBehavior};

use super::{bounded_name, Entry, MapBoard, RoundRecord};

/// The schema version this build writes and reads.
pub const SCHEMA_VERSION: i64 = 3;

/// The steps from version N-1 to N, index N-1; each runs in one transaction with the version
/// bump.
const MIGRATIONS: &[&str] = &[
    // 1: rounds and each player's figures in them.
    "CREATE TABLE rounds (
        id INTEGER PRIMARY KEY,
        map_hash TEXT NOT NULL,
        map_name TEXT NOT NULL,
        mode TEXT NOT NULL,
        seconds REAL NOT NULL,
        cleared INTEGER NOT NULL,
        ended_at INTEGER NOT NULL
    );
    CREATE TABLE results (
        round_id INTEGER NOT NULL REFERENCES rounds(id),
        name TEXT NOT NULL,
        points INTEGER NOT NULL,
        items INTEGER NOT NULL,
        it_seconds REAL NOT NULL,
        reached_exit INTEGER NOT NULL
    );
    CREATE INDEX rounds_by_map ON rounds(map_hash, mode);",
    // 2: a player's own best is looked up by name.
    "CREATE INDEX results_by_name ON results(name, round_id);",
    // 3: a round's identity, so a round written again (from a world's queue, after an outage
    // or a kill -9) is ignored; rounds written before it have none.
    "ALTER TABLE rounds ADD COLUMN uid TEXT;
    CREATE UNIQUE INDEX rounds_by_uid ON rounds(uid);",
];

/// How long to wait for another process's lock before giving up: other worlds sharing the
/// file hold it for one round's transaction (milliseconds), and the writer runs on a thread of
/// its own, so a wait delays the board, never a frame.
pub const BUSY: Duration = Duration::from_secs(10);

/// An open leaderboard file at the current schema.
#[derive(Debug)]
pub struct Store {
    conn: Connection,
}

/// What a failed open says, naming the file.
fn failed(path: &Path, what: &str, e: impl std::fmt::Display) -> String {
    format!("leaderboard {}: {what}: {e}", path.display())
}

impl Store {
    /// Opens `path` for the server: created (empty, at the current schema) if absent, else
    /// checked and migrated forward.
    ///
    /// # Errors
    /// A newer schema, a file SQLite cannot read or lock, or one that fails its integrity
    /// check; the file is then left as it was.
    pub fn open(path: &Path) -> Result<Self, String> {
        let fresh = !path.exists();
        let flags = if fresh {
            OpenFlags::SQLITE_OPEN_READ_WRITE | OpenFlags::SQLITE_OPEN_CREATE
        } else {
            OpenFlags::SQLITE_OPEN_READ_WRITE
        };
        let conn = Connection::open_with_flags(path, flags | OpenFlags::SQLITE_OPEN_NO_MUTEX)
            .map_err(|e| failed(path, "cannot open", e))?;
        conn.busy_timeout(BUSY)
            .map_err(|e| failed(path, "cannot open", e))?;
        let mut store = Self { conn };
        let version = store.check(path)?;
        // Whether we can write at all (another process may hold the lock): an empty write
        // transaction changes nothing in the file.
        store
            .conn
            .execute_batch("BEGIN IMMEDIATE; COMMIT;")
            .map_err(|e| failed(path, "cannot lock for writing", e))?;
        // WAL: other worlds read while one writes (the mode is kept in the file).
        let mode: String = store
            .conn
            .query_row("PRAGMA journal_mode=WAL", [], |r| r.get(0))
            .map_err(|e| failed(path, "cannot turn on WAL", e))?;
        if !mode.eq_ignore_ascii_case("wal") {
            return Err(failed(
                path,
                "cannot turn on WAL",
                format!("journal mode {mode}"),
            ));
        }
        store.migrate(path, version)?;
        Ok(store)
    }

    /// Opens an existing `path` read-only (`halfcast scores`).
    ///
    /// # Errors
    /// As [`Store::open`], and when the file does not exist.
    pub fn open_read(path: &Path) -> Result<Self, String> {
        if !path.exists() {
            return Err(failed(path, "cannot open", "no such file"));
        }
        let conn = Connection::open_with_flags(
            path,
            OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX,
        )
        .map_err(|e| failed(path, "cannot open", e))?;
        conn.busy_timeout(BUSY)
            .map_err(|e| failed(path, "cannot open", e))?;
        let store = Self { conn };
        let version = store.check(path)?;
        if version < SCHEMA_VERSION {
            return Err(failed(
                path,
                "old schema",
                format!("version {version}; `halfcast serve --db` upgrades it to {SCHEMA_VERSION}"),
            ));
        }
        Ok(store)
    }

    /// Whether the file answers a query now.
    ///
    /// # Errors
    /// SQLite's message.
    pub fn ping(&self) -> Result<(), String> {
        self.conn
            .query_row("SELECT 1", [], |_| Ok(()))
            .map_err(|e| e.to_string())
    }

    /// Reads the schema version and checks the file's integrity; refuses newer versions.
    fn check(&self, path: &Path) -> Result<i64, String> {
        // The version and the tables in one statement (one snapshot): another world may
        // migrate the file between two.
        let (version, tables): (i64, i64) = self
            .conn
            .query_row(
                "SELECT (SELECT user_version FROM pragma_user_version),
                        (SELECT COUNT(*) FROM sqlite_master)",
                [],
                |r| Ok((r.get(0)?, r.get(1)?)),
            )
            .map_err(|e| failed(path, "cannot read", e))?;
        let ok: String = self
            .conn
            .query_row("PRAGMA quick_check", [], |r| r.get(0))
            .map_err(|e| failed(path, "cannot read", e))?;
        if ok != "ok" {
            return Err(failed(path, "damaged", ok));
        }
        if version == 0 {
            // Version 0 is a new, empty file; one with tables of its own is someone else's.
            if tables > 0 {
                return Err(failed(
                    path,
                    "not a halfcast leaderboard",
                    "it has tables but no schema version",
                ));
            }
        }
        if version > SCHEMA_VERSION {
            return Err(failed(
                path,
                "written by a newer halfcast",
                format!(
                    "schema version {version}, this build knows up to {SCHEMA_VERSION}; \
                     upgrade halfcast or use another --db"
                ),
            ));
        }
        Ok(version)
    }

    /// Runs the migrations after `from`, each in its own transaction with its version bump.
    fn migrate(&mut self, path: &Path, from: i64) -> Result<(), String> {
        for (i, step) in MIGRATIONS.iter().enumerate().skip(from.max(0) as usize) {
            let to = i as i64 + 1;
            let tx = self
                .conn
                .transaction_with_behavior(TransactionBehavior::Immediate)
                .map_err(|e| failed(path, "cannot migrate", e))?;
            // Another world sharing the file may have taken this step since we looked.
            let now: i64 = tx
                .query_row("PRAGMA user_version", [], |r| r.get(0))
                .map_err(|e| failed(path, "cannot migrate", e))?;
            if now >= to {
                continue;
            }
            tx.execute_batch(step)
                .and_then(|()| tx.pragma_update(None, "user_version", to))
                .and_then(|()| tx.commit())
                .map_err(|e| failed(path, &format!("cannot migrate to version {to}"), e))?;
        }
        Ok(())
    }

    /// The open connection, for a backup of it ([`super::backup`]).
    pub(super) fn connection(&self) -> &Connection {
        &self.conn
    }

    /// The schema version of the open file.
    ///
    /// # Errors
    /// When SQLite fails to answer.
    pub fn version(&self) -> Result<i64, String> {
        self.conn
            .query_row("PRAGMA user_version", [], |r| r.get(0))
            .map_err(|e| e.to_string())
    }

    /// Writes one finished round and its players, all or nothing; a round whose `uid` is
    /// already there is left as it is (written once, however often it is sent).
    ///
    /// # Errors
    /// SQLite's message (disk full, I/O error, locked too long).
    pub fn record(&mut self, r: &RoundRecord) -> Result<(), String> {
        let tx = self
            .conn
            .transaction_with_behavior(TransactionBehavior::Immediate)
            .map_err(|e| e.to_string())?;
        let added = tx
            .execute(
                "INSERT INTO rounds (uid, map_hash, map_name, mode, seconds, cleared, ended_at)
                 VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7) ON CONFLICT (uid) DO NOTHING",
                params![r.uid, r.map_hash, r.map_name, r.mode, r.seconds, r.cleared, r.ended_at],
            )
            .map_err(|e| e.to_string())?;
        if added == 0 {
            return Ok(());
        }
        let round = tx.last_insert_rowid();
        for p in &r.players {
            tx.execute(
                "INSERT INTO results (round_id, name, points, items, it_seconds, reached_exit)
                 VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
                params![
                    round,
                    bounded_name(&p.name),
                    p.points,
                    p.items as i64,
                    p.it_seconds,
                    p.reached_exit
                ],
            )
            .map_err(|e| e.to_string())?;
        }
        tx.commit().map_err(|e| e.to_string())
    }

    /// Every (map hash, mode) with rounds recorded: its latest name and its number of rounds,
    /// by name.
    ///
    /// # Errors
    /// SQLite's message.
    pub fn maps(&self) -> Result<Vec<(String, String, String, u64)>, String> {
        let mut st = self
            .conn
            .prepare(
                "SELECT map_hash, mode, COUNT(*),
                        (SELECT map_name FROM rounds r2 WHERE r2.map_hash = r.map_hash
                         ORDER BY id DESC LIMIT 1)
                 FROM rounds r GROUP BY map_hash, mode ORDER BY 4, 2",
            )
            .map_err(|e| e.to_string())?;
        let rows = st
            .query_map([], |r| {
                Ok((
                    r.get::<_, String>(0)?,
                    r.get::<_, String>(3)?,
                    r.get::<_, String>(1)?,
                    r.get::<_, i64>(2)? as u64,
                ))
            })
            .map_err(|e| e.to_string())?;
        rows.collect::<Result<_, _>>().map_err(|e| e.to_string())
    }

    /// The map's board for `mode`: each player's best entry, best first, at most `n`.
    ///
    /// # Errors
    /// SQLite's message.
    pub fn top(&self, map_hash: &str, mode: &str, n: usize) -> Result<Vec<Entry>, String> {
        let sql = format!(
            "SELECT * FROM (
                SELECT p.name, r.seconds, p.points, p.items, p.it_seconds, r.cleared,
                       p.reached_exit, r.ended_at, r.map_name, r.id AS id,
                       ROW_NUMBER() OVER (PARTITION BY p.name ORDER BY {order}) AS k
                FROM results p JOIN rounds r ON r.id = p.round_id
                WHERE r.map_hash = ?1 AND r.mode = ?2
             ) WHERE k = 1 ORDER BY {order} LIMIT ?3",
            order = ranking(mode)
        );
        let mut st = self.conn.prepare(&sql).map_err(|e| e.to_string())?;
        let rows = st
            .query_map(params![map_hash, mode, n as i64], entry)
            .map_err(|e| e.to_string())?;
        rows.collect::<Result<_, _>>().map_err(|e| e.to_string())
    }

    /// `name`'s best entry on the map for `mode`, if they have one.
    ///
    /// # Errors
    /// SQLite's message.
    pub fn best(&self, map_hash: &str, mode: &str, name: &str) -> Result<Option<Entry>, String> {
        let sql = format!(
            "SELECT p.name, r.seconds, p.points, p.items, p.it_seconds, r.cleared,
                    p.reached_exit, r.ended_at, r.map_name
             FROM results p JOIN rounds r ON r.id = p.round_id
             WHERE r.map_hash = ?1 AND r.mode = ?2 AND p.name = ?3
             ORDER BY {} LIMIT 1",
            ranking(mode)
        );
        self.conn
            .query_row(&sql, params![map_hash, mode, bounded_name(name)], entry)
            .optional()
            .map_err(|e| e.to_string())
    }

    /// The board of one map for `mode`, with `names`' own bests.
    ///
    /// # Errors
    /// SQLite's message.
    pub fn board(&self, map_hash: &str, mode: &str, names: &[String]) -> Result<MapBoard, String> {
        let mut board = MapBoard {
            top: self.top(map_hash, mode, super::TOP)?,
            ..MapBoard::default()
        };
        for n in names {
            if let Some(e) = self.best(map_hash, mode, n)? {
                board.bests.insert(n.clone(), e);
            }
        }
        Ok(board)
    }
}

/// The ORDER BY of a mode's ranking (best first; earlier rounds win ties): coop ranks full
/// clears by time, then everything else by points; tag ranks by the least time as "it".
/// Its column names are each in one table only, so it reads the same on the join and on a
/// select from it.
pub(super) fn ranking(mode: &str) -> &'static str {
    if mode == "tag" {
        "it_seconds ASC, id ASC"
    } else {
        "cleared DESC, CASE WHEN cleared THEN seconds ELSE 0 END ASC, points DESC, \
         seconds ASC, id ASC"
    }
}

fn entry(r: &rusqlite::Row<'_>) -> rusqlite::Result<Entry> {
    Ok(Entry {
        name: r.get(0)?,
        seconds: r.get(1)?,
        points: r.get(2)?,
        items: r.get::<_, i64>(3)?.max(0) as u64,
        it_seconds: r.get(4)?,
        cleared: r.get(5)?,
        reached_exit: r.get(6)?,
        ended_at: r.get(7)?,
        map_name: r.get(8)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::multi::round::PlayerResult;

    static NEXT_UID: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

    fn round(hash: &str, seconds: f64, cleared: bool, players: &[(&str, i64, f64)]) -> RoundRecord {
        RoundRecord {
            uid: format!(
                "test-{}",
                NEXT_UID.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
            ),
            map_hash: hash.into(),
            map_name: "m.cub".into(),
            mode: if players.iter().any(|p| p.2 > 0.0) {
                "tag".into()
            } else {
                "coop".into()
            },
            seconds,
            cleared,
            ended_at: 1,
            players: players
                .iter()
                .map(|&(name, points, it)| PlayerResult {
                    name: name.into(),
                    points,
                    items: 0,
                    it_seconds: it,
                    reached_exit: cleared,
                })
                .collect(),
        }
    }

    #[test]
    fn coop_ranks_full_clears_by_time_then_points_one_row_per_player() {
        let dir = tempfile::tempdir().unwrap();
        let mut s = Store::open(&dir.path().join("lb.sqlite")).unwrap();
        s.record(&round("h", 90.0, false, &[("ann", 500, 0.0)]))
            .unwrap();
        s.record(&round(
            "h",
            60.0,
            true,
            &[("bob", 10, 0.0), ("ann", 20, 0.0)],
        ))
        .unwrap();
        s.record(&round("h", 40.0, true, &[("cat", 5, 0.0)]))
            .unwrap();
        s.record(&round("h", 50.0, false, &[("dan", 900, 0.0)]))
            .unwrap();
        s.record(&round("other", 1.0, true, &[("eve", 1, 0.0)]))
            .unwrap();
        let top = s.top("h", "coop", 10).unwrap();
        let names: Vec<&str> = top.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(names, ["cat", "ann", "bob", "dan"]);
        assert_eq!(s.best("h", "coop", "ann").unwrap().unwrap().seconds, 60.0);
        assert!(s.best("h", "coop", "eve").unwrap().is_none());
        assert_eq!(s.top("h", "coop", 2).unwrap().len(), 2);
    }

    #[test]
    fn tag_ranks_the_least_time_as_it() {
        let dir = tempfile::tempdir().unwrap();
        let mut s = Store::open(&dir.path().join("lb.sqlite")).unwrap();
        s.record(&round(
            "h",
            180.0,
            false,
            &[("ann", 0, 30.0), ("bob", 0, 10.0)],
        ))
        .unwrap();
        let names: Vec<String> = s
            .top("h", "tag", 10)
            .unwrap()
            .into_iter()
            .map(|e| e.name)
            .collect();
        assert_eq!(names, ["bob", "ann"]);
    }

    #[test]
    fn an_old_schema_is_migrated_and_a_newer_one_refused_untouched() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("lb.sqlite");
        {
            let c = Connection::open(&path).unwrap();
            c.execute_batch(MIGRATIONS[0]).unwrap();
            c.pragma_update(None, "user_version", 1).unwrap();
        }
        assert_eq!(
            Store::open(&path).unwrap().version().unwrap(),
            SCHEMA_VERSION
        );
        {
            let c = Connection::open(&path).unwrap();
            c.pragma_update(None, "user_version", 99).unwrap();
        }
        let before = std::fs::read(&path).unwrap();
        let e = Store::open(&path).unwrap_err();
        assert!(e.contains("written by a newer halfcast"), "{e}");
        assert!(
            std::fs::read(&path).unwrap() == before,
            "the file was changed"
        );
        // Another program's database is not taken over either.
        let other = dir.path().join("other.sqlite");
        Connection::open(&other)
            .unwrap()
            .execute_batch("CREATE TABLE notes (x)")
            .unwrap();
        let theirs = std::fs::read(&other).unwrap();
        let e = Store::open(&other).unwrap_err();
        assert!(e.contains("not a halfcast leaderboard"), "{e}");
        assert!(
            std::fs::read(&other).unwrap() == theirs,
            "the file was changed"
        );
        let e = Store::open(&path).unwrap_err();
        assert!(e.contains("schema version 99"), "{e}");
        assert!(
            std::fs::read(&path).unwrap() == before,
            "the file was changed"
        );
    }

    #[test]
    fn two_worlds_on_one_file_start_together_and_lose_no_round_writing_at_once() {
        const EACH: usize = 200;
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("shared.sqlite");
        // Both open a file that does not exist yet, at the same moment: one migrates it.
        let barrier = std::sync::Arc::new(std::sync::Barrier::new(2));
        let writers: Vec<_> = ["ann", "bob"]
            .into_iter()
            .map(|who| {
                let (path, barrier) = (path.clone(), std::sync::Arc::clone(&barrier));
                std::thread::spawn(move || {
                    barrier.wait();
                    let mut s = Store::open(&path).expect("opens beside the other world");
                    for i in 0..EACH {
                        s.record(&round("h", 30.0 + i as f64, false, &[(who, i as i64, 0.0)]))
                            .unwrap_or_else(|e| panic!("{who}'s round {i}: {e}"));
                        // And reads, as a world's board does after each round.
                        s.top("h", "coop", TOP_FOR_TEST)
                            .expect("reads while the other writes");
                    }
                })
            })
            .collect();
        for w in writers {
            w.join().expect("a writer failed");
        }
        let s = Store::open_read(&path).unwrap();
        assert_eq!(s.version().unwrap(), SCHEMA_VERSION);
        let maps = s.maps().unwrap();
        assert_eq!(maps.len(), 1, "{maps:?}");
        assert_eq!(
            maps[0].3,
            2 * EACH as u64,
            "every round of both worlds is there"
        );
        let mode: String = s
            .conn
            .query_row("PRAGMA journal_mode", [], |r| r.get(0))
            .unwrap();
        assert_eq!(mode, "wal");
    }

    #[test]
    fn a_round_sent_twice_is_written_once_and_old_rounds_keep_after_the_migration() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("lb.sqlite");
        {
            // A version-2 file with one round in it (no identity).
            let c = Connection::open(&path).unwrap();
            c.execute_batch(MIGRATIONS[0]).unwrap();
            c.execute_batch(MIGRATIONS[1]).unwrap();
            c.pragma_update(None, "user_version", 2).unwrap();
            c.execute_batch(
                "INSERT INTO rounds (map_hash, map_name, mode, seconds, cleared, ended_at)
                 VALUES ('h', 'm.cub', 'coop', 9.0, 0, 1);
                 INSERT INTO results VALUES (1, 'old', 3, 0, 0.0, 0);",
            )
            .unwrap();
        }
        let mut s = Store::open(&path).unwrap();
        let r = round("h", 30.0, false, &[("ann", 7, 0.0), ("bob", 5, 0.0)]);
        s.record(&r).unwrap();
        s.record(&r).unwrap();
        let mut again = round("h", 31.0, false, &[("cat", 1, 0.0)]);
        again.uid.clone_from(&r.uid);
        s.record(&again).unwrap();
        let count = |sql: &str| -> i64 { s.conn.query_row(sql, [], |row| row.get(0)).unwrap() };
        assert_eq!(
            count("SELECT COUNT(*) FROM rounds"),
            2,
            "the old round and ann's"
        );
        assert_eq!(count("SELECT COUNT(*) FROM results"), 3);
        assert_eq!(s.maps().unwrap()[0].3, 2);
    }

    const TOP_FOR_TEST: usize = 10;
}
