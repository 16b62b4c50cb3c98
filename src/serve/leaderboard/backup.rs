//! `halfcast scores --backup FILE`: a consistent copy of a leaderboard that worlds are writing,
//! made with SQLite's online backup API (no `sqlite3` program, no stopping the worlds). The copy
//! is written beside its final name and renamed into place only once whole and checked, so a
//! timer overwriting yesterday's copy never leaves half a file.

use std::path::{Path, PathBuf};
use std::time::Duration;

use rusqlite::backup::Backup;
use rusqlite::Connection;

use super::store::Store;

/// Copies the leaderboard at `db` to `to` (replacing it); returns the rounds the copy holds.
///
/// # Errors
/// A message naming the file when `db` cannot be read (as `halfcast scores` refuses it), the
/// copy cannot be written, or the copy fails its check.
pub fn backup(db: &Path, to: &Path) -> Result<u64, String> {
    let source = Store::open_read(db)?;
    let partial = partial_path(to);
    let _ = std::fs::remove_file(&partial);
    let copied = copy(source.connection(), &partial);
    if let Err(e) = copied {
        let _ = std::fs::remove_file(&partial);
        return Err(format!("backup to {}: {e}", partial.display()));
    }
    // The copy is read back as `halfcast scores` reads it: schema, integrity, rounds.
    let rounds = Store::open_read(&partial)
        .and_then(|s| s.maps())
        .map(|maps| maps.iter().map(|m| m.3).sum());
    match rounds {
        Ok(n) => std::fs::rename(&partial, to).map(|()| n).map_err(|e| {
            format!(
                "backup: cannot rename {} to {}: {e}",
                partial.display(),
                to.display()
            )
        }),
        Err(e) => {
            let _ = std::fs::remove_file(&partial);
            Err(format!("backup: the copy fails its check: {e}"))
        }
    }
}

/// Every page of `source` into a new file at `to`, then that file made self-contained (a
/// rollback journal instead of the source's WAL: one file to keep, no `-wal` or `-shm`).
fn copy(source: &Connection, to: &Path) -> rusqlite::Result<()> {
    let mut dest = Connection::open(to)?;
    {
        let b = Backup::new(source, &mut dest)?;
        // All pages in one step: a leaderboard is small, and one step reads one snapshot
        // (worlds writing meanwhile do not restart it).
        b.run_to_completion(i32::MAX, Duration::from_millis(50), None)?;
    }
    let _mode: String = dest.query_row("PRAGMA journal_mode=DELETE", [], |r| r.get(0))?;
    Ok(())
}

/// Where the copy is written before it is renamed to `to`: beside it, hidden.
fn partial_path(to: &Path) -> PathBuf {
    let name = to
        .file_name()
        .map_or_else(|| "backup".into(), |n| n.to_string_lossy().into_owned());
    to.with_file_name(format!(".{name}.partial"))
}
