//! Reading a map file: a regular file only (a FIFO never blocks, `/dev/zero` is never read) and
//! with a byte cap, so a huge file is refused, not swallowed.

use std::path::Path;

use super::parse::MAX_CELLS;
use super::{MapError, MapErrorKind};
use crate::input_file::{read_regular_capped, ReadError};

/// Most bytes a map file may hold: the largest grid ([`MAX_CELLS`] cells, one byte each) twice
/// over, which leaves room for line ends and any header.
pub const MAX_MAP_BYTES: u64 = 2 * MAX_CELLS as u64;

/// Reads a map file, a regular one of at most [`MAX_MAP_BYTES`].
///
/// # Errors
/// The OS's error, a FIFO, device or socket, or a file over the cap, naming the file.
pub fn read_map_file(path: &Path) -> Result<Vec<u8>, MapError> {
    read_regular_capped(path, MAX_MAP_BYTES).map_err(|e| MapError {
        file: path.display().to_string(),
        at: None,
        kind: match e {
            ReadError::TooLarge { cap } => MapErrorKind::FileTooLarge(cap),
            other => MapErrorKind::Io(other.to_string()),
        },
    })
}
