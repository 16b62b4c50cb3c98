//! Where a leaderboard lives: a SQLite file (one host's worlds) or a PostgreSQL database
//! (worlds on several hosts), chosen by what `--db` names; the writer thread and `halfcast
//! scores` use either the same way.

use std::path::Path;

pub use super::open_error::OpenError;
use super::pg_config::PgTarget;
use super::pg_store::{self, PgStore};
use super::store::Store;
use super::{Entry, MapBoard, RoundRecord};

/// An open leaderboard.
#[derive(Debug)]
pub enum Database {
    /// A SQLite file.
    Sqlite(Store),
    /// A PostgreSQL database.
    Postgres(Box<PgStore>),
}

/// The PostgreSQL URL in `db`, if it is one rather than a file's path.
#[must_use]
pub fn postgres_url(db: &Path) -> Option<&str> {
    db.to_str().filter(|s| pg_store::is_url(s))
}

/// `db` as logs and errors show it (a URL without its password).
#[must_use]
pub fn shown(db: &Path) -> String {
    postgres_url(db).map_or_else(|| db.display().to_string(), pg_store::shown)
}

impl Database {
    /// Opens `db` for a server (created or migrated as needed); a PostgreSQL password may come
    /// from `password_file` ([`PgTarget::resolve`]).
    ///
    /// # Errors
    /// As [`Store::open`] (always [`OpenError::Refused`]) or [`PgStore::open`].
    pub fn open(db: &Path, password_file: Option<&Path>) -> Result<Self, OpenError> {
        match postgres_url(db) {
            Some(url) => {
                let target = PgTarget::resolve(url, password_file).map_err(OpenError::Refused)?;
                PgStore::open(&target).map(|s| Self::Postgres(Box::new(s)))
            }
            None => Store::open(db)
                .map(Self::Sqlite)
                .map_err(OpenError::Refused),
        }
    }

    /// Opens `db` to read it (`halfcast scores`).
    ///
    /// # Errors
    /// As [`Store::open_read`] or [`PgStore::open_read`].
    pub fn open_read(db: &Path) -> Result<Self, String> {
        match postgres_url(db) {
            Some(url) => PgStore::open_read(&PgTarget::resolve(url, None)?)
                .map(|s| Self::Postgres(Box::new(s))),
            None => Store::open_read(db).map(Self::Sqlite),
        }
    }

    /// Writes one finished round, all or nothing.
    ///
    /// # Errors
    /// The database's message.
    pub fn record(&mut self, r: &RoundRecord) -> Result<(), String> {
        match self {
            Self::Sqlite(s) => s.record(r),
            Self::Postgres(p) => p.record(r),
        }
    }

    /// Every (map hash, name, mode, rounds) with rounds recorded.
    ///
    /// # Errors
    /// The database's message.
    pub fn maps(&mut self) -> Result<Vec<(String, String, String, u64)>, String> {
        match self {
            Self::Sqlite(s) => s.maps(),
            Self::Postgres(p) => p.maps(),
        }
    }

    /// A map's board for `mode`, best first, at most `n`.
    ///
    /// # Errors
    /// The database's message.
    pub fn top(&mut self, map_hash: &str, mode: &str, n: usize) -> Result<Vec<Entry>, String> {
        match self {
            Self::Sqlite(s) => s.top(map_hash, mode, n),
            Self::Postgres(p) => p.top(map_hash, mode, n),
        }
    }

    /// `name`'s best entry on a map for `mode`.
    ///
    /// # Errors
    /// The database's message.
    pub fn best(
        &mut self,
        map_hash: &str,
        mode: &str,
        name: &str,
    ) -> Result<Option<Entry>, String> {
        match self {
            Self::Sqlite(s) => s.best(map_hash, mode, name),
            Self::Postgres(p) => p.best(map_hash, mode, name),
        }
    }

    /// A map's board with `names`' own bests.
    ///
    /// # Errors
    /// The database's message.
    pub fn board(
        &mut self,
        map_hash: &str,
        mode: &str,
        names: &[String],
    ) -> Result<MapBoard, String> {
        match self {
            Self::Sqlite(s) => s.board(map_hash, mode, names),
            Self::Postgres(p) => p.board(map_hash, mode, names),
        }
    }
}
