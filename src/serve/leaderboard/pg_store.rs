//! The leaderboard in PostgreSQL (`--db postgres://…`): the same schema and rankings as the
//! SQLite file ([`super::store`]), for worlds on several hosts that share one board.
//!
//! The blocking client runs on the leaderboard's own thread only, so a slow or unreachable
//! server delays the board, never a frame. A server that is down (at start-up or later) fails
//! the writes meanwhile; the writer keeps the rounds in its queue ([`super::queue`]) and tries
//! again, connecting anew. Each round carries its identity (`uid`, unique), so one written twice
//! is stored once. No TLS: reach the server over a network you trust (loopback, a private
//! network, or a tunnel). Where it is and the password: [`super::pg_config`].

use postgres::{Client, Config, NoTls, Row};

use super::open_error::OpenError;
use super::pg_config::PgTarget;
pub use super::pg_text::{causes, shown};
use super::store::SCHEMA_VERSION;
use super::{bounded_name, Entry, MapBoard, RoundRecord};

/// The steps from version N-1 to N, index N-1, in PostgreSQL's dialect of
/// [`super::store`]'s migrations.
const MIGRATIONS: &[&str] = &[
    "CREATE TABLE rounds (
        id BIGSERIAL PRIMARY KEY,
        map_hash TEXT NOT NULL,
        map_name TEXT NOT NULL,
        mode TEXT NOT NULL,
        seconds DOUBLE PRECISION NOT NULL,
        cleared BOOLEAN NOT NULL,
        ended_at BIGINT NOT NULL
    );
    CREATE TABLE results (
        round_id BIGINT NOT NULL REFERENCES rounds(id),
        name TEXT NOT NULL,
        points BIGINT NOT NULL,
        items BIGINT NOT NULL,
        it_seconds DOUBLE PRECISION NOT NULL,
        reached_exit BOOLEAN NOT NULL
    );
    CREATE INDEX rounds_by_map ON rounds(map_hash, mode);",
    "CREATE INDEX results_by_name ON results(name, round_id);",
    "ALTER TABLE rounds ADD COLUMN uid TEXT;
    CREATE UNIQUE INDEX rounds_by_uid ON rounds(uid);",
];

/// The advisory lock worlds take while they migrate, so two starting at once migrate once.
const MIGRATION_LOCK: i64 = 0x6861_6c66_6361_7374; // "halfcast"

/// How long a ping waits for the server's answer.
const PING_PATIENCE: std::time::Duration = std::time::Duration::from_secs(5);

/// Whether `db` (what `--db` was given) names a PostgreSQL database rather than a file.
#[must_use]
pub fn is_url(db: &str) -> bool {
    db.starts_with("postgres://") || db.starts_with("postgresql://")
}

/// A connection to a PostgreSQL leaderboard at the current schema.
pub struct PgStore {
    config: Config,
    url: String,
    client: Client,
}

impl std::fmt::Debug for PgStore {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PgStore").field("url", &self.url).finish()
    }
}

/// What a failed start says, naming the database (without its password).
fn failed(url: &str, what: &str, e: impl std::fmt::Display) -> String {
    format!("leaderboard {url}: {what}: {e}")
}

impl PgStore {
    /// Connects to `target` for the server: the schema created or migrated forward.
    ///
    /// # Errors
    /// [`OpenError::Away`] when the server cannot be reached now (or the connection is lost
    /// while migrating); [`OpenError::Refused`] when it refuses the login or the database
    /// ([`super::pg_answer`]), the database holds a newer schema or another program's `rounds`
    /// table, or a migration fails.
    pub fn open(target: &PgTarget) -> Result<Self, OpenError> {
        let mut store = Self::connect(target)?;
        match store.migrate() {
            Ok(()) => Ok(store),
            Err(e) if store.client.is_closed() => Err(OpenError::Away(e)),
            Err(e) => Err(OpenError::Refused(e)),
        }
    }

    /// Connects to `target` to read it (`halfcast scores`).
    ///
    /// # Errors
    /// As [`PgStore::open`], and when the schema is older than this build's.
    pub fn open_read(target: &PgTarget) -> Result<Self, String> {
        let mut store = Self::connect(target).map_err(|e| e.to_string())?;
        let version = store.version()?;
        if version != SCHEMA_VERSION {
            return Err(failed(
                &store.url,
                "schema version",
                format!(
                    "{version}; this build reads {SCHEMA_VERSION} (`halfcast serve --db` migrates)"
                ),
            ));
        }
        Ok(store)
    }

    fn connect(target: &PgTarget) -> Result<Self, OpenError> {
        let cannot = |c: String| failed(&target.shown, "cannot connect", c);
        super::pg_answer::speaks_postgres(&target.config).map_err(|e| match e {
            OpenError::Away(c) => OpenError::Away(cannot(c)),
            OpenError::Refused(c) => OpenError::Refused(cannot(c)),
        })?;
        let client = target
            .config
            .connect(NoTls)
            .map_err(|e| super::pg_answer::classify(&e, cannot))?;
        Ok(Self {
            config: target.config.clone(),
            url: target.shown.clone(),
            client,
        })
    }

    /// Connects again if the connection was lost (the server restarted or was away).
    fn alive(&mut self) -> Result<(), String> {
        if self.client.is_closed() {
            self.client = self
                .config
                .connect(NoTls)
                .map_err(|e| format!("PostgreSQL {} is unreachable: {}", self.url, causes(&e)))?;
        }
        Ok(())
    }

    /// Whether the server answers now (connecting again if the connection was lost).
    ///
    /// # Errors
    /// That it is unreachable, or its message.
    pub fn ping(&mut self) -> Result<(), String> {
        self.alive()?;
        self.client
            .is_valid(PING_PATIENCE)
            .map_err(|e| format!("PostgreSQL {} does not answer: {}", self.url, causes(&e)))
    }

    /// Runs the migrations this database lacks, under an advisory lock.
    fn migrate(&mut self) -> Result<(), String> {
        let url = self.url.clone();
        let mut tx = self
            .client
            .transaction()
            .map_err(|e| failed(&url, "cannot migrate", causes(&e)))?;
        tx.execute("SELECT pg_advisory_xact_lock($1)", &[&MIGRATION_LOCK])
            .map_err(|e| failed(&url, "cannot lock for migrating", causes(&e)))?;
        tx.batch_execute("CREATE TABLE IF NOT EXISTS halfcast_schema (version INTEGER NOT NULL)")
            .map_err(|e| failed(&url, "cannot migrate", causes(&e)))?;
        let version: i64 = tx
            .query_opt("SELECT version FROM halfcast_schema", &[])
            .map_err(|e| failed(&url, "cannot read", causes(&e)))?
            .map_or(0, |r| i64::from(r.get::<_, i32>(0)));
        if version > SCHEMA_VERSION {
            return Err(failed(
                &url,
                "written by a newer halfcast",
                format!(
                    "schema version {version}, this build knows up to {SCHEMA_VERSION}; \
                     upgrade halfcast or use another --db"
                ),
            ));
        }
        if version == 0 {
            let theirs: bool = tx
                .query_one("SELECT to_regclass('rounds') IS NOT NULL", &[])
                .map_err(|e| failed(&url, "cannot read", causes(&e)))?
                .get(0);
            if theirs {
                return Err(failed(
                    &url,
                    "not a halfcast leaderboard",
                    "it has a rounds table but no schema version",
                ));
            }
            tx.execute("INSERT INTO halfcast_schema (version) VALUES (0)", &[])
                .map_err(|e| failed(&url, "cannot migrate", causes(&e)))?;
        }
        for (i, step) in MIGRATIONS.iter().enumerate().skip(version as usize) {
            let to = i as i32 + 1;
            tx.batch_execute(step)
                .and_then(|()| {
                    tx.execute("UPDATE halfcast_schema SET version = $1", &[&to])
                        .map(|_| ())
                })
                .map_err(|e| {
                    failed(&url, &format!("cannot migrate to version {to}"), causes(&e))
                })?;
        }
        tx.commit()
            .map_err(|e| failed(&url, "cannot migrate", causes(&e)))
    }

    /// The schema version of the database (0 before the first migration).
    ///
    /// # Errors
    /// When the server fails to answer.
    pub fn version(&mut self) -> Result<i64, String> {
        self.alive()?;
        let exists: bool = self
            .client
            .query_one("SELECT to_regclass('halfcast_schema') IS NOT NULL", &[])
            .map_err(|e| causes(&e))?
            .get(0);
        if !exists {
            return Ok(0);
        }
        let row = self
            .client
            .query_opt("SELECT version FROM halfcast_schema", &[])
            .map_err(|e| causes(&e))?;
        Ok(row.map_or(0, |r| i64::from(r.get::<_, i32>(0))))
    }

    /// Writes one finished round and its players, all or nothing; a connection found lost on
    /// the way (the server restarted) is made again and the round written once more.
    ///
    /// # Errors
    /// The server's message, or that it is unreachable.
    pub fn record(&mut self, r: &RoundRecord) -> Result<(), String> {
        self.alive()?;
        match self.write(r) {
            Err(_) if self.client.is_closed() => {
                self.alive()?;
                self.write(r)
            }
            done => done,
        }
    }

    fn write(&mut self, r: &RoundRecord) -> Result<(), String> {
        let mut tx = self.client.transaction().map_err(|e| causes(&e))?;
        // A round already there (sent again from the queue) adds nothing.
        let Some(row) = tx
            .query_opt(
                "INSERT INTO rounds (uid, map_hash, map_name, mode, seconds, cleared, ended_at)
                 VALUES ($1, $2, $3, $4, $5, $6, $7) ON CONFLICT (uid) DO NOTHING RETURNING id",
                &[
                    &r.uid,
                    &r.map_hash,
                    &r.map_name,
                    &r.mode,
                    &r.seconds,
                    &r.cleared,
                    &r.ended_at,
                ],
            )
            .map_err(|e| causes(&e))?
        else {
            return tx.commit().map_err(|e| causes(&e));
        };
        let round: i64 = row.get(0);
        for p in &r.players {
            tx.execute(
                "INSERT INTO results (round_id, name, points, items, it_seconds, reached_exit)
                 VALUES ($1, $2, $3, $4, $5, $6)",
                &[
                    &round,
                    &bounded_name(&p.name),
                    &p.points,
                    &(p.items as i64),
                    &p.it_seconds,
                    &p.reached_exit,
                ],
            )
            .map_err(|e| causes(&e))?;
        }
        tx.commit().map_err(|e| causes(&e))
    }

    /// As [`super::store::Store::maps`].
    ///
    /// # Errors
    /// The server's message.
    pub fn maps(&mut self) -> Result<Vec<(String, String, String, u64)>, String> {
        self.alive()?;
        let rows = self
            .client
            .query(
                "SELECT map_hash, mode, COUNT(*),
                        (SELECT map_name FROM rounds r2 WHERE r2.map_hash = r.map_hash
                         ORDER BY id DESC LIMIT 1)
                 FROM rounds r GROUP BY map_hash, mode ORDER BY 4, 2",
                &[],
            )
            .map_err(|e| causes(&e))?;
        Ok(rows
            .iter()
            .map(|r| {
                (
                    r.get::<_, String>(0),
                    r.get::<_, String>(3),
                    r.get::<_, String>(1),
                    r.get::<_, i64>(2).max(0) as u64,
                )
            })
            .collect())
    }

    /// As [`super::store::Store::top`].
    ///
    /// # Errors
    /// The server's message.
    pub fn top(&mut self, map_hash: &str, mode: &str, n: usize) -> Result<Vec<Entry>, String> {
        self.alive()?;
        let sql = format!(
            "SELECT * FROM (
                SELECT p.name, r.seconds, p.points, p.items, p.it_seconds, r.cleared,
                       p.reached_exit, r.ended_at, r.map_name, r.id AS id,
                       ROW_NUMBER() OVER (PARTITION BY p.name ORDER BY {order}) AS k
                FROM results p JOIN rounds r ON r.id = p.round_id
                WHERE r.map_hash = $1 AND r.mode = $2
             ) AS best WHERE k = 1 ORDER BY {order} LIMIT $3",
            order = super::store::ranking(mode)
        );
        let rows = self
            .client
            .query(&sql, &[&map_hash, &mode, &(n as i64)])
            .map_err(|e| causes(&e))?;
        Ok(rows.iter().map(entry).collect())
    }

    /// As [`super::store::Store::best`].
    ///
    /// # Errors
    /// The server's message.
    pub fn best(
        &mut self,
        map_hash: &str,
        mode: &str,
        name: &str,
    ) -> Result<Option<Entry>, String> {
        self.alive()?;
        let sql = format!(
            "SELECT p.name, r.seconds, p.points, p.items, p.it_seconds, r.cleared,
                    p.reached_exit, r.ended_at, r.map_name
             FROM results p JOIN rounds r ON r.id = p.round_id
             WHERE r.map_hash = $1 AND r.mode = $2 AND p.name = $3
             ORDER BY {} LIMIT 1",
            super::store::ranking(mode)
        );
        let row = self
            .client
            .query_opt(&sql, &[&map_hash, &mode, &bounded_name(name)])
            .map_err(|e| causes(&e))?;
        Ok(row.as_ref().map(entry))
    }

    /// As [`super::store::Store::board`].
    ///
    /// # Errors
    /// The server's message.
    pub fn board(
        &mut self,
        map_hash: &str,
        mode: &str,
        names: &[String],
    ) -> Result<MapBoard, String> {
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

fn entry(r: &Row) -> Entry {
    Entry {
        name: r.get(0),
        seconds: r.get(1),
        points: r.get(2),
        items: r.get::<_, i64>(3).max(0) as u64,
        it_seconds: r.get(4),
        cleared: r.get(5),
        reached_exit: r.get(6),
        ended_at: r.get(7),
        map_name: r.get(8),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn urls_are_told_from_files_and_shown_without_their_password() {
        assert!(is_url("postgres://u:p@h/db") && is_url("postgresql://h/db"));
        assert!(!is_url("halfcast.sqlite") && !is_url("/var/lib/postgres.sqlite"));
        assert_eq!(
            shown("postgres://ann:secret@db.example/halfcast"),
            "postgres://ann@db.example/halfcast"
        );
        assert_eq!(
            shown("postgres://db.example/halfcast"),
            "postgres://db.example/halfcast"
        );
        assert_eq!(
            shown("postgres://h/db?password=x&user=y"),
            "postgres://h/db"
        );
    }
}
