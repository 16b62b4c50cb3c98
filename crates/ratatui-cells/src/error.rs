//! The one error type: why text or bytes did not read as a frame.

use std::fmt;

/// Why text or bytes did not read as a frame: a malformed cells text (naming its line), a
/// ratatui form that does not parse, a size over [`crate::limits::MAX_FRAME`], bytes that are
/// not UTF-8. Its `Display` is the whole message, for a person.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Error {
    message: String,
}

impl Error {
    /// An error saying `message`.
    pub(crate) fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Error {}
