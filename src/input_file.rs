//! Reading user-named input files with bounded work: at most a byte cap, and for files that are
//! only ever regular files on disk (textures) nothing else is even opened.
//!
//! A path can name `/dev/zero` (reads forever), a FIFO (opening it blocks until a writer comes)
//! or a multi-gigabyte file; reading it whole would stall or exhaust memory before any parser
//! could refuse it. Every loader of a user file comes through here.

use std::fmt;
use std::io::Read;
use std::path::Path;

/// Why an input file was not read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ReadError {
    /// The operating system's message (missing file, permission, a directory…).
    Io(String),
    /// More bytes than the cap: refused before reading them all.
    TooLarge {
        /// The cap, in bytes.
        cap: u64,
    },
    /// A FIFO, device or socket where only a plain file makes sense.
    NotRegular,
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io(e) => f.write_str(e),
            Self::TooLarge { cap } => write!(f, "file is larger than {cap} bytes (the limit)"),
            Self::NotRegular => f.write_str("not a regular file (a FIFO, device or socket)"),
        }
    }
}

impl std::error::Error for ReadError {}

/// Reads `path` whole if it holds at most `cap` bytes; pipes work (they end), `/dev/zero` stops
/// at the cap.
///
/// # Errors
/// The OS's error, or [`ReadError::TooLarge`] as soon as byte `cap + 1` arrives.
pub fn read_capped(path: &Path, cap: u64) -> Result<Vec<u8>, ReadError> {
    let file = std::fs::File::open(path).map_err(|e| ReadError::Io(e.to_string()))?;
    let mut bytes = Vec::new();
    file.take(cap.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| ReadError::Io(e.to_string()))?;
    if bytes.len() as u64 > cap {
        return Err(ReadError::TooLarge { cap });
    }
    Ok(bytes)
}

/// [`read_capped`] for a path that must be a regular file: the type is checked before opening,
/// so a FIFO never blocks and a device is never read.
///
/// # Errors
/// As [`read_capped`], or [`ReadError::NotRegular`].
pub fn read_regular_capped(path: &Path, cap: u64) -> Result<Vec<u8>, ReadError> {
    let meta = std::fs::metadata(path).map_err(|e| ReadError::Io(e.to_string()))?;
    if !meta.is_file() {
        return Err(if meta.is_dir() {
            ReadError::Io("is a directory".into())
        } else {
            ReadError::NotRegular
        });
    }
    if meta.len() > cap {
        return Err(ReadError::TooLarge { cap });
    }
    read_capped(path, cap)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_files_read_whole_and_large_ones_stop_at_the_cap() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("f");
        std::fs::write(&p, b"12345").unwrap();
        assert_eq!(read_capped(&p, 5).unwrap(), b"12345");
        assert_eq!(read_capped(&p, 4), Err(ReadError::TooLarge { cap: 4 }));
        assert_eq!(
            read_regular_capped(&p, 4),
            Err(ReadError::TooLarge { cap: 4 })
        );
    }

    #[cfg(unix)]
    #[test]
    fn an_endless_device_stops_at_the_cap_and_is_not_a_regular_file() {
        let zero = Path::new("/dev/zero");
        if !zero.exists() {
            return;
        }
        assert_eq!(
            read_capped(zero, 1000),
            Err(ReadError::TooLarge { cap: 1000 })
        );
        assert_eq!(read_regular_capped(zero, 1000), Err(ReadError::NotRegular));
    }

    #[test]
    fn directories_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(
            read_regular_capped(dir.path(), 10),
            Err(ReadError::Io("is a directory".into()))
        );
    }
}
