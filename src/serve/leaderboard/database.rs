//! Where a leaderboard lives: a SQLite file (one host's worlds) or a PostgreSQL database
//! (worlds on several hosts), chosen by what `--db` names; the writer thread and `halfcast
//! scores` use either the same way.

use std::path::{Path, PathBuf};

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

/// How to log in to a PostgreSQL `--db`: what the flags add to libpq's conventions.
#[derive(Debug, Clone, Default)]
pub struct Access {
    /// `--db-password-file`.
    pub password_file: Option<PathBuf>,
    /// `--db-insecure-password-file`: use a password file others may read.
    pub insecure_password_file: bool,
}

/// The PostgreSQL URL in `db`, if it is one rather than a file's path.
#[must_use]
pub fn postgres_url(db: &Path) -> Option<&str> {
    db.to_str().filter(|s| pg_store::is_url(s))
}

/// Refuses a `--db` that was meant as a database URL but is not one this build reads
/// (`postgres//host/db`, `postgres:/host/db`, `postgre://…`, `mysql://…`, `host=db dbname=x`),
/// which would otherwise become a SQLite file of that name.
///
/// # Errors
/// What is wrong with it, and the form to use.
pub fn check_form(db: &Path) -> Result<(), String> {
    if postgres_url(db).is_some() {
        return Ok(());
    }
    let text = db.to_string_lossy();
    let lower = text.to_ascii_lowercase();
    let scheme = lower.split_once(':').map(|(s, _)| s).filter(|s| {
        !s.is_empty()
            && s.chars()
                .all(|c| c.is_ascii_alphanumeric() || "+.-".contains(c))
    });
    let url_like = scheme.is_some_and(|s| s.len() > 1) && lower.contains(":/");
    let pg_like = ["postgres", "postgresql", "pg"].iter().any(|p| {
        lower
            .strip_prefix(p)
            .is_some_and(|rest| rest.starts_with(':') || rest.starts_with("//"))
    });
    let keywords = ["host=", "dbname=", "user="]
        .iter()
        .any(|k| lower.starts_with(k) || lower.contains(&format!(" {k}")));
    if url_like || pg_like || keywords {
        return Err(format!(
            "--db {}: neither a SQLite file's path nor a postgres:// URL; a PostgreSQL \
             leaderboard is named postgres://USER@HOST[:PORT]/DATABASE",
            masked(&text)
        ));
    }
    Ok(())
}

/// `db` as logs and errors show it (a URL without its password).
#[must_use]
pub fn shown(db: &Path) -> String {
    match postgres_url(db) {
        Some(url) => pg_store::shown(url),
        None if check_form(db).is_err() => masked(&db.to_string_lossy()),
        None => db.display().to_string(),
    }
}

/// A mistyped URL without what may be its password: the user part's `:secret` before an `@`,
/// a query string, and `password=` settings.
fn masked(text: &str) -> String {
    let text = text.split_once('?').map_or(text, |(u, _)| u);
    let text = match text.rsplit_once('@') {
        Some((before, host)) => {
            let start = before.rfind('/').map_or(0, |i| i + 1);
            let user = &before[start..];
            let user = user.rsplit_once(':').map_or(user, |(u, _)| u);
            format!("{}{user}@{host}", &before[..start])
        }
        None => text.to_owned(),
    };
    text.split(' ')
        .map(|w| {
            if w.to_ascii_lowercase().starts_with("password=") {
                "password=…"
            } else {
                w
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// Checks what can be checked of `db` without a connection: its form ([`check_form`]) and,
/// for PostgreSQL, the password files ([`PgTarget::resolve`]).
///
/// # Errors
/// As [`check_form`] and [`PgTarget::resolve`].
pub fn check(db: &Path, access: &Access) -> Result<(), String> {
    check_form(db)?;
    if let Some(url) = postgres_url(db) {
        PgTarget::resolve(
            url,
            access.password_file.as_deref(),
            access.insecure_password_file,
        )?;
    }
    Ok(())
}

impl Database {
    /// Opens `db` for a server (created or migrated as needed); a PostgreSQL password may come
    /// from `access` ([`PgTarget::resolve`]).
    ///
    /// # Errors
    /// As [`check`] and [`Store::open`] (always [`OpenError::Refused`]) or [`PgStore::open`].
    pub fn open(db: &Path, access: &Access) -> Result<Self, OpenError> {
        check_form(db).map_err(OpenError::Refused)?;
        match postgres_url(db) {
            Some(url) => {
                let file = access.password_file.as_deref();
                let target = PgTarget::resolve(url, file, access.insecure_password_file)
                    .map_err(OpenError::Refused)?;
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
    /// As [`check`], [`Store::open_read`] or [`PgStore::open_read`].
    pub fn open_read(db: &Path, access: &Access) -> Result<Self, String> {
        check_form(db)?;
        match postgres_url(db) {
            Some(url) => {
                let file = access.password_file.as_deref();
                let target = PgTarget::resolve(url, file, access.insecure_password_file)?;
                PgStore::open_read(&target).map(|s| Self::Postgres(Box::new(s)))
            }
            None => Store::open_read(db).map(Self::Sqlite),
        }
    }

    /// Whether the database answers now (a probe while no round waits).
    ///
    /// # Errors
    /// The database's message.
    pub fn ping(&mut self) -> Result<(), String> {
        match self {
            Self::Sqlite(s) => s.ping(),
            Self::Postgres(p) => p.ping(),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mistyped_url_is_refused_not_made_a_file() {
        for bad in [
            "postgres//ann@db.example/halfcast",
            "postgres:/db.example/halfcast",
            "postgresql:db.example",
            "postgre://ann@db.example/halfcast",
            "pg://db.example/halfcast",
            "POSTGRES://db.example/halfcast",
            "mysql://db.example/halfcast",
            "host=db.example dbname=halfcast",
            "user=ann host=db.example",
        ] {
            let e = check_form(Path::new(bad)).unwrap_err();
            assert!(e.contains("postgres://USER@HOST"), "{bad}: {e}");
        }
        for secret in [
            "postgres//ann:secret@db/h",
            "postgres:ann:secret@db/h",
            "pg://db/h?password=secret",
            "host=db password=secret",
        ] {
            let e = check_form(Path::new(secret)).unwrap_err();
            assert!(!e.contains("secret"), "{e}");
        }
        for good in [
            "postgres://ann@db.example/halfcast",
            "postgresql://db.example/halfcast",
            "halfcast.sqlite",
            "/var/lib/halfcast/postgres.sqlite",
            "./pg-board.sqlite",
            "C:board.sqlite",
            "/srv/host=1/board.sqlite",
        ] {
            assert_eq!(check_form(Path::new(good)), Ok(()), "{good}");
        }
    }
}
