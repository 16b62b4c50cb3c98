//! Why a leaderboard could not be opened: away for now (a world starts anyway and queues) or
//! refused for good (a start-up error). Both stores say it the same way.

/// Why a leaderboard could not be opened.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum OpenError {
    /// It cannot be reached now (PostgreSQL down or unreachable): a world starts anyway,
    /// queues its rounds, and tries again.
    Away(String),
    /// It answered and must not be used (newer schema, another program's, damaged, a bad
    /// password file): a start-up error.
    Refused(String),
}

impl std::fmt::Display for OpenError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Away(m) | Self::Refused(m) => f.write_str(m),
        }
    }
}
