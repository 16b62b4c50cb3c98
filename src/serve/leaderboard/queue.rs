//! The rounds a world has not yet written to its database, on disk: one file per round in the
//! queue directory (`--queue-dir`; by default `halfcast-queue` beside the host key). A round's
//! file is written whole before the database is tried (a temporary name, fsync, rename, fsync
//! of the directory), so it survives a kill -9 or a power cut at any moment, and removed once
//! the database has the round. A world started with the same directory finds the files and
//! writes them. A round written but not yet removed when the world died is sent again and
//! ignored by the store (its `uid`), so every round is recorded exactly once.
//!
//! Worlds may share a directory: each writes the rounds it finds, and the stores keep each
//! once; one directory per world keeps each world's backlog apart in its metrics.

use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::RoundRecord;
use crate::game::multi::round::PlayerResult;

/// The queue directory's name beside the host key when `--queue-dir` is not given.
pub const DEFAULT_DIR: &str = "halfcast-queue";

/// How a queued round's file name ends.
const SUFFIX: &str = ".round.json";

/// Largest queued-round file read back (a round of 10 000 players is far less).
const MAX_FILE: u64 = 4 * 1024 * 1024;

/// A round as its file holds it.
#[derive(Serialize, Deserialize)]
struct Stored {
    uid: String,
    map_hash: String,
    map_name: String,
    mode: String,
    seconds: f64,
    cleared: bool,
    ended_at: i64,
    players: Vec<StoredPlayer>,
}

/// One player's figures in a [`Stored`] round.
#[derive(Serialize, Deserialize)]
struct StoredPlayer {
    name: String,
    points: i64,
    items: u64,
    it_seconds: f64,
    reached_exit: bool,
}

/// The queue directory of one world.
#[derive(Debug)]
pub struct DiskQueue {
    dir: PathBuf,
}

/// Rounds found in a queue directory at start, oldest first, with the file each came from,
/// and notes about files that could not be read (kept, renamed `.bad`).
pub type Found = (Vec<(RoundRecord, PathBuf)>, Vec<String>);

impl DiskQueue {
    /// Opens (creating, mode 0700) the queue directory `dir`; the rounds already queued there.
    ///
    /// # Errors
    /// The directory cannot be made or read.
    pub fn open(dir: &Path) -> Result<(Self, Found), String> {
        let failed = |e: io::Error| format!("round queue {}: {e}", dir.display());
        create_private_dir(dir).map_err(failed)?;
        let mut rounds = Vec::new();
        let mut notes = Vec::new();
        for entry in fs::read_dir(dir).map_err(failed)? {
            let path = entry.map_err(failed)?.path();
            let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if name.starts_with('.') && name.ends_with(".tmp") {
                // Half written when a world died: its round was never handed on. (A recent one
                // may be another world's, sharing the directory, being written now.)
                if older_than(&path, STALE_TMP) {
                    let _ = fs::remove_file(&path);
                }
            } else if name.ends_with(SUFFIX) {
                match read_round(&path) {
                    Ok(r) => rounds.push((r, path)),
                    Err(e) => {
                        let bad = path.with_extension("bad");
                        let _ = fs::rename(&path, &bad);
                        notes.push(format!(
                            "round queue: {} cannot be read ({e}); kept as {}",
                            path.display(),
                            bad.display()
                        ));
                    }
                }
            }
        }
        rounds.sort_by(|a, b| (a.0.ended_at, &a.0.uid).cmp(&(b.0.ended_at, &b.0.uid)));
        Ok((
            Self {
                dir: dir.to_path_buf(),
            },
            (rounds, notes),
        ))
    }

    /// The directory, for logs.
    #[must_use]
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Writes `round` to its own file, durably; the file's path.
    ///
    /// # Errors
    /// The disk's error (full, read-only, gone).
    pub fn save(&self, round: &RoundRecord) -> io::Result<PathBuf> {
        let name: String = round
            .uid
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let path = self.dir.join(format!("{name}{SUFFIX}"));
        let tmp = self.dir.join(format!(".{name}.tmp"));
        let bytes = serde_json::to_vec(&stored(round)).map_err(io::Error::other)?;
        let written = (|| {
            let mut f = File::create(&tmp)?;
            f.write_all(&bytes)?;
            f.sync_all()?;
            fs::rename(&tmp, &path)?;
            File::open(&self.dir)?.sync_all()
        })();
        if written.is_err() {
            let _ = fs::remove_file(&tmp);
        }
        written.map(|()| path)
    }

    /// Removes a round's file once its database has the round (a file already gone, taken by
    /// another world sharing the directory, is no error).
    pub fn remove(path: &Path) {
        let _ = fs::remove_file(path);
    }
}

/// A temporary file older than this was left by a world that died while writing it.
const STALE_TMP: std::time::Duration = std::time::Duration::from_secs(60);

/// Whether `path` was last changed more than `age` ago.
fn older_than(path: &Path, age: std::time::Duration) -> bool {
    fs::metadata(path)
        .and_then(|m| m.modified())
        .ok()
        .and_then(|t| t.elapsed().ok())
        .is_some_and(|e| e > age)
}

/// Creates `dir` (and its parents) with mode 0700 where it is new.
fn create_private_dir(dir: &Path) -> io::Result<()> {
    let mut b = fs::DirBuilder::new();
    b.recursive(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::DirBuilderExt;
        b.mode(0o700);
    }
    b.create(dir)?;
    // Writable: a queue that cannot take a round would only say so at the first outage.
    // Named for this process: two worlds sharing the directory may start at once.
    let probe = dir.join(format!(".probe-{}.tmp", std::process::id()));
    OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(true)
        .open(&probe)?;
    match fs::remove_file(&probe) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => Err(e),
        _ => Ok(()),
    }
}

fn stored(r: &RoundRecord) -> Stored {
    Stored {
        uid: r.uid.clone(),
        map_hash: r.map_hash.clone(),
        map_name: r.map_name.clone(),
        mode: r.mode.clone(),
        seconds: r.seconds,
        cleared: r.cleared,
        ended_at: r.ended_at,
        players: r
            .players
            .iter()
            .map(|p| StoredPlayer {
                name: p.name.clone(),
                points: p.points,
                items: p.items as u64,
                it_seconds: p.it_seconds,
                reached_exit: p.reached_exit,
            })
            .collect(),
    }
}

fn read_round(path: &Path) -> Result<RoundRecord, String> {
    let bytes =
        crate::input_file::read_regular_capped(path, MAX_FILE).map_err(|e| e.to_string())?;
    let s: Stored = serde_json::from_slice(&bytes).map_err(|e| e.to_string())?;
    Ok(RoundRecord {
        uid: s.uid,
        map_hash: s.map_hash,
        map_name: s.map_name,
        mode: s.mode,
        seconds: s.seconds,
        cleared: s.cleared,
        ended_at: s.ended_at,
        players: s
            .players
            .into_iter()
            .map(|p| PlayerResult {
                name: p.name,
                points: p.points,
                items: usize::try_from(p.items).unwrap_or(usize::MAX),
                it_seconds: p.it_seconds,
                reached_exit: p.reached_exit,
            })
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round(uid: &str, ended_at: i64) -> RoundRecord {
        RoundRecord {
            uid: uid.into(),
            map_hash: "h".into(),
            map_name: "m.cub".into(),
            mode: "coop".into(),
            seconds: 12.5,
            cleared: true,
            ended_at,
            players: vec![PlayerResult {
                name: "ann".into(),
                points: 3,
                items: 2,
                it_seconds: 0.5,
                reached_exit: true,
            }],
        }
    }

    #[test]
    fn saved_rounds_are_found_again_oldest_first_and_removed_once_written() {
        let dir = tempfile::tempdir().unwrap();
        let qdir = dir.path().join("q");
        let (q, (found, _)) = DiskQueue::open(&qdir).unwrap();
        assert!(found.is_empty());
        let late = q.save(&round("b-2", 20)).unwrap();
        q.save(&round("a-1", 10)).unwrap();
        let half = std::fs::File::create(qdir.join(".c-3.tmp")).unwrap();
        let long_ago = std::time::SystemTime::now() - 2 * STALE_TMP;
        half.set_modified(long_ago).unwrap();
        std::fs::write(qdir.join(".e-5.tmp"), b"{being written").unwrap();
        std::fs::write(qdir.join("d-4.round.json"), b"{not json").unwrap();
        let (_, (found, notes)) = DiskQueue::open(&qdir).unwrap();
        let uids: Vec<&str> = found.iter().map(|(r, _)| r.uid.as_str()).collect();
        assert_eq!(uids, ["a-1", "b-2"]);
        assert_eq!(found[0].0, round("a-1", 10));
        assert!(!qdir.join(".c-3.tmp").exists(), "half-written files go");
        assert!(
            qdir.join(".e-5.tmp").exists(),
            "one being written now stays"
        );
        assert!(
            qdir.join("d-4.round.bad").exists() && notes.len() == 1,
            "{notes:?}"
        );
        DiskQueue::remove(&late);
        DiskQueue::remove(&late);
        let (_, (found, _)) = DiskQueue::open(&qdir).unwrap();
        assert_eq!(found.len(), 1);
    }

    #[test]
    fn a_queue_that_cannot_be_made_is_an_error_naming_it() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("file");
        std::fs::write(&file, b"x").unwrap();
        let e = DiskQueue::open(&file.join("q")).unwrap_err();
        assert!(e.contains("round queue") && e.contains("file"), "{e}");
    }
}
