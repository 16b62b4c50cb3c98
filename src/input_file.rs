//! Reading user-named input files with bounded work: only regular files, at most a byte cap.
//!
//! A path can name `/dev/zero` (reads forever), a FIFO (opening it blocks until a writer comes),
//! a terminal or a multi-gigabyte file; reading it would stall or exhaust memory before any
//! parser could refuse it. Every loader of a user file comes through [`read_regular_capped`]
//! (maps, replays and the map a replay names, `diff` frames, textures, sprite sheets, bench
//! frames, the config file, the server's key and password files).
//!
//! The type is checked twice: on the path before opening (so a device is never even opened),
//! and on the opened descriptor (`fstat`), so a path swapped for a FIFO in between is still
//! refused. The open itself uses `O_NONBLOCK`, which makes opening a FIFO return at once instead
//! of waiting for a writer; on a regular file the flag changes nothing.

use std::fmt;
use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

/// Why an input file was not read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ReadError {
    /// The operating system's message (missing file, permission, a directory…) and its kind,
    /// so a caller can treat a missing optional file as absent.
    Io {
        /// What kind of failure (e.g. [`io::ErrorKind::NotFound`]).
        kind: io::ErrorKind,
        /// The message shown.
        message: String,
    },
    /// More bytes than the cap: refused before reading them all.
    TooLarge {
        /// The cap, in bytes.
        cap: u64,
    },
    /// A FIFO, device or socket where only a plain file makes sense.
    NotRegular,
}

impl ReadError {
    fn io(e: &io::Error) -> Self {
        Self::Io {
            kind: e.kind(),
            message: e.to_string(),
        }
    }

    fn directory() -> Self {
        Self::Io {
            kind: io::ErrorKind::IsADirectory,
            message: "is a directory".into(),
        }
    }

    /// Whether the file does not exist (an optional file may then be treated as absent).
    #[must_use]
    pub fn is_not_found(&self) -> bool {
        matches!(self, Self::Io { kind, .. } if *kind == io::ErrorKind::NotFound)
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io { message, .. } => f.write_str(message),
            Self::TooLarge { cap } => write!(f, "file is larger than {cap} bytes (the limit)"),
            Self::NotRegular => f.write_str("not a regular file (a FIFO, device or socket)"),
        }
    }
}

impl std::error::Error for ReadError {}

/// Refuses anything but a regular file, naming a directory as such.
fn check_type(meta: &std::fs::Metadata) -> Result<(), ReadError> {
    if meta.is_file() {
        Ok(())
    } else if meta.is_dir() {
        Err(ReadError::directory())
    } else {
        Err(ReadError::NotRegular)
    }
}

/// Opens `path` for reading without ever blocking in `open()` (a FIFO returns at once) and
/// without making a terminal the controlling one.
#[cfg(unix)]
fn open_nonblocking(path: &Path) -> io::Result<File> {
    use std::os::unix::fs::OpenOptionsExt;
    std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY)
        .open(path)
}

/// Elsewhere opening a file never waits for a writer; the type checks still apply.
#[cfg(not(unix))]
fn open_nonblocking(path: &Path) -> io::Result<File> {
    File::open(path)
}

/// Opens `path` if it is a regular file: checked on the path (a device is never opened) and
/// again on the opened descriptor (a path replaced by a FIFO in between is still refused).
/// Also returns the file's size.
///
/// # Errors
/// The OS's error, "is a directory", or [`ReadError::NotRegular`].
pub fn open_regular(path: &Path) -> Result<(File, u64), ReadError> {
    check_type(&std::fs::metadata(path).map_err(|e| ReadError::io(&e))?)?;
    let file = open_nonblocking(path).map_err(|e| ReadError::io(&e))?;
    let meta = file.metadata().map_err(|e| ReadError::io(&e))?;
    check_type(&meta)?;
    Ok((file, meta.len()))
}

/// Reads `path` whole if it is a regular file of at most `cap` bytes; nothing else is read,
/// and no open or read can block.
///
/// # Errors
/// As [`open_regular`], or [`ReadError::TooLarge`] (from the size, or as soon as byte `cap + 1`
/// arrives if the file grows while it is read).
pub fn read_regular_capped(path: &Path, cap: u64) -> Result<Vec<u8>, ReadError> {
    let (file, len) = open_regular(path)?;
    if len > cap {
        return Err(ReadError::TooLarge { cap });
    }
    let mut bytes = Vec::with_capacity(usize::try_from(len).unwrap_or(0));
    file.take(cap.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| ReadError::io(&e))?;
    if bytes.len() as u64 > cap {
        return Err(ReadError::TooLarge { cap });
    }
    Ok(bytes)
}

/// [`read_regular_capped`] for text: the bytes must be UTF-8.
///
/// # Errors
/// As [`read_regular_capped`], or an `InvalidData` error for bytes that are not UTF-8.
pub fn read_regular_text(path: &Path, cap: u64) -> Result<String, ReadError> {
    String::from_utf8(read_regular_capped(path, cap)?).map_err(|_| ReadError::Io {
        kind: io::ErrorKind::InvalidData,
        message: "not UTF-8 text".into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_files_read_whole_and_large_ones_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("f");
        std::fs::write(&p, b"12345").unwrap();
        assert_eq!(read_regular_capped(&p, 5).unwrap(), b"12345");
        assert_eq!(
            read_regular_capped(&p, 4),
            Err(ReadError::TooLarge { cap: 4 })
        );
        assert_eq!(read_regular_text(&p, 5).unwrap(), "12345");
    }

    #[test]
    fn text_must_be_utf8() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("f");
        std::fs::write(&p, b"\xff\xfe").unwrap();
        assert_eq!(
            read_regular_text(&p, 5).unwrap_err().to_string(),
            "not UTF-8 text"
        );
    }

    #[test]
    fn a_missing_file_says_so() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_regular_capped(&dir.path().join("nope"), 10).unwrap_err();
        assert!(e.is_not_found(), "{e:?}");
        assert!(!ReadError::NotRegular.is_not_found());
    }

    #[cfg(unix)]
    #[test]
    fn a_device_is_not_a_regular_file() {
        for dev in ["/dev/zero", "/dev/null"] {
            if Path::new(dev).exists() {
                assert_eq!(
                    read_regular_capped(Path::new(dev), 1000),
                    Err(ReadError::NotRegular)
                );
            }
        }
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_is_refused_without_waiting_for_a_writer() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("fifo");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|s| s.success()) {
            println!("SKIPPED: mkfifo is not available");
            return;
        }
        // The path check refuses it; the descriptor check is what catches a swap after it.
        assert_eq!(read_regular_capped(&fifo, 10), Err(ReadError::NotRegular));
        let file = open_nonblocking(&fifo).expect("a non-blocking open of a FIFO returns at once");
        assert_eq!(
            check_type(&file.metadata().unwrap()),
            Err(ReadError::NotRegular)
        );
    }

    #[test]
    fn directories_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(
            read_regular_capped(dir.path(), 10).unwrap_err().to_string(),
            "is a directory"
        );
    }
}
