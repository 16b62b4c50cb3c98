//! Output files that appear whole or not at all.
//!
//! A regular-file target is written as a hidden `.NAME.halfcast-PID.part` file beside it and
//! renamed over it only when complete; on any failure (a write error, a limit reached) the part
//! file is removed and an existing target is left as it was. A target that is not a regular file
//! (`/dev/stdout`, a FIFO, `/dev/null`) is written in place, as a stream: it cannot be renamed
//! over, and whoever reads it sees the stream end where the error happened.

use std::fs::{File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

/// An output file being written; [`OutputFile::commit`] makes it appear, dropping it without
/// committing removes what was written.
pub(crate) struct OutputFile {
    out: BufWriter<File>,
    /// The part file and the final path, for a regular-file target.
    rename: Option<(PathBuf, PathBuf)>,
}

/// Distinguishes the part files of one process.
static NEXT_PART: AtomicU32 = AtomicU32::new(0);

impl OutputFile {
    /// Starts writing `target`: a part file beside it, or the target itself if it exists and is
    /// not a regular file. A symlink is followed, so the part file lands beside the real file.
    ///
    /// # Errors
    /// The part file (or the stream) cannot be created.
    pub(crate) fn create(target: &Path) -> io::Result<Self> {
        match std::fs::metadata(target) {
            Ok(m) if !m.is_file() && !m.is_dir() => {
                let file = OpenOptions::new().write(true).open(target)?;
                return Ok(Self {
                    out: BufWriter::new(file),
                    rename: None,
                });
            }
            _ => {}
        }
        let real = std::fs::canonicalize(target).unwrap_or_else(|_| target.to_path_buf());
        let name = real
            .file_name()
            .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
        let part_name = format!(
            ".{name}.halfcast-{}-{}.part",
            std::process::id(),
            NEXT_PART.fetch_add(1, Ordering::Relaxed)
        );
        let part = real.with_file_name(part_name);
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&part)?;
        Ok(Self {
            out: BufWriter::new(file),
            rename: Some((part, real)),
        })
    }

    /// Flushes and moves the finished file into place.
    ///
    /// # Errors
    /// The last write or the rename failed (the part file is then removed).
    pub(crate) fn commit(mut self) -> io::Result<()> {
        self.out.flush()?;
        if let Some((part, real)) = self.rename.take() {
            if let Err(e) = std::fs::rename(&part, real) {
                let _ = std::fs::remove_file(&part);
                return Err(e);
            }
        }
        Ok(())
    }
}

impl Write for OutputFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.out.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

impl Drop for OutputFile {
    fn drop(&mut self) {
        if let Some((part, _)) = self.rename.take() {
            let _ = std::fs::remove_file(part);
        }
    }
}

/// Writes `bytes` as the whole of `target` (nothing appears if the write fails).
///
/// # Errors
/// As [`OutputFile::create`] and [`OutputFile::commit`].
pub(crate) fn write_whole(target: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut f = OutputFile::create(target)?;
    f.write_all(bytes)?;
    f.commit()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn the_file_appears_only_when_committed() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.cast");
        let mut f = OutputFile::create(&target).unwrap();
        f.write_all(b"hello").unwrap();
        f.flush().unwrap();
        assert!(!target.exists());
        assert_eq!(names(dir.path()).len(), 1, "only the part file");
        f.commit().unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"hello");
        assert_eq!(names(dir.path()), ["out.cast"]);
    }

    #[test]
    fn a_dropped_file_leaves_nothing_and_the_old_target_intact() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.cast");
        std::fs::write(&target, b"old").unwrap();
        let mut f = OutputFile::create(&target).unwrap();
        f.write_all(b"half of a new one").unwrap();
        drop(f);
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        assert_eq!(names(dir.path()), ["out.cast"]);
    }

    #[cfg(unix)]
    #[test]
    fn a_device_is_written_in_place() {
        let null = Path::new("/dev/null");
        if null.exists() {
            write_whole(null, b"gone").unwrap();
            assert!(null.exists());
        }
    }
}
