//! Why a map was refused, with the place in the file that broke the rule.

use std::fmt;

/// A map that breaks a rule: the file, where (1-based line:col, when there is a place) and which rule.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub struct MapError {
    /// The map file as named by the user.
    pub file: String,
    /// 1-based line and column of what broke the rule, when it has a place.
    pub at: Option<(usize, usize)>,
    /// Which rule.
    pub kind: MapErrorKind,
}

impl fmt::Display for MapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.at {
            Some((line, col)) => write!(f, "{}:{line}:{col}: {}", self.file, self.kind),
            None => write!(f, "{}: {}", self.file, self.kind),
        }
    }
}

/// The rule a map broke; the text is what users read, so tests pin it exactly.
// Each variant's `#[error]` text is its documentation (and what the user reads).
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum MapErrorKind {
    #[error("file is not valid UTF-8 text")]
    NotUtf8,
    #[error("unknown identifier '{0}'")]
    UnknownIdentifier(String),
    #[error("no space after identifier '{0}' (write '{0} r,g,b')")]
    NoSpaceAfter(String),
    #[error("duplicate identifier '{id}' (first given at line {first_line})")]
    Duplicate { id: String, first_line: usize },
    #[error("{0} needs exactly one texture path")]
    NeedsOnePath(String),
    #[error("bad colour for {id}: expected r,g,b with integers 0-255, got '{got}'")]
    BadColour { id: String, got: String },
    #[error("bad value for {id}: {why}")]
    BadValue { id: String, why: String },
    #[error("missing identifier '{0}' ({1}) before the map")]
    Missing(&'static str, &'static str),
    #[error("no map grid after the header")]
    NoMap,
    #[error("bad map character '{}'", .0.escape_debug())]
    BadMapChar(char),
    #[error("zone letter '{0}' is used in the map but has no F{0}, C{0}, H{0} or W{0} line")]
    UndefinedZone(char),
    #[error("content after the blank line at {blank_line} that ended the map (the grid must be contiguous and come last)")]
    AfterMap { blank_line: usize },
    #[error("map is not closed: {what} cell at {line}:{col} touches void")]
    NotClosed {
        what: &'static str,
        line: usize,
        col: usize,
    },
    #[error("no player start (N, S, E or W) in the map")]
    NoPlayer,
    #[error("second player start (first at {first_line}:{first_col}); a map has exactly one")]
    SecondPlayer { first_line: usize, first_col: usize },
    #[error("map is too large ({0} cells; the limit is {1})")]
    TooLarge(usize, usize),
    #[error("door at {line}:{col} needs walls on two opposite sides (east and west, or north and south)")]
    DoorNotFramed { line: usize, col: usize },
    #[error("sprite at {0} is not over a floor cell")]
    SpriteOffFloor(String),
    #[error("light at {0} is not over a floor cell")]
    LightOffFloor(String),
    #[error("item at {0} is not over a floor cell")]
    ItemOffFloor(String),
    #[error("creature at {0} is not over a floor cell")]
    CreatureOffFloor(String),
    #[error("exit at {0} is not a floor cell")]
    ExitOffFloor(String),
    #[error("DOORLOCK at {0} is not on a door cell (D)")]
    LockNotOnDoor(String),
    #[error("door at {cell} is already locked (line {first_line})")]
    LockedTwice { cell: String, first_line: usize },
    #[error("DOORLOCK needs the key '{0}' but no ITEM has key={0}")]
    LockWithoutKey(String),
    #[error("cannot read the file: {0}")]
    Io(String),
    #[error("file is larger than {0} bytes (the limit for a map)")]
    FileTooLarge(u64),
    #[error("too many {what}; the limit is {limit}")]
    TooMany { what: &'static str, limit: usize },
    #[error("map is too large for LIGHT ({cells} cells; lights are baked over at most {limit})")]
    TooLargeToLight { cells: usize, limit: usize },
}
