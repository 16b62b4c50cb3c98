//! The leaderboard that outlives the server: every finished round in a SQLite file
//! ([`store`]), written by a thread of its own ([`writer`]) so a slow disk never stalls a
//! frame, and the boards sessions show (the results screen, the `L` key) published from there.
//!
//! Names are the in-game names (SSH user names, made unique); they are bounded when stored
//! ([`bounded_name`]) and escaped wherever printed ([`shown_name`]). [`backup`] copies the file
//! while worlds write it. [`pg_store`] keeps the same board in PostgreSQL for worlds on several
//! hosts ([`pg_config`]: where it is, and the password, as libpq finds them; [`pg_answer`]: a
//! refusal told from an outage); [`database`] opens whichever `--db` names.
//!
//! No round is lost while the database is away: each round has an identity ([`round_id`]) the
//! stores use to ignore a second insert; it goes to a queue on disk ([`queue`]) before the
//! database is tried, and stays in the writer's backlog ([`backlog`]) until the database has it;
//! the writer retries with a growing pause and logs an outage once ([`outage`]).

pub mod backlog;
pub mod backup;
pub mod database;
pub mod open_error;
pub mod outage;
pub mod pg_answer;
pub mod pg_config;
pub mod pg_store;
pub mod pg_text;
pub mod queue;
pub mod round_id;
pub mod store;
pub mod writer;

use std::collections::HashMap;

use serde::Serialize;

use crate::game::multi::round::PlayerResult;

/// How many entries a map's board holds.
pub const TOP: usize = 10;

/// Longest name stored, in characters (the game shows at most 16).
pub const MAX_STORED_NAME: usize = 32;

/// Longest name printed, in characters, before it is cut with `~`.
pub const MAX_SHOWN_NAME: usize = 16;

/// The file name of the default database, beside the host key.
pub const DEFAULT_FILE: &str = "halfcast.sqlite";

/// One finished round as the database records it.
#[derive(Debug, Clone, PartialEq)]
pub struct RoundRecord {
    /// The round's identity, unique across worlds and restarts ([`round_id`]): the stores
    /// write a round once however often it is sent.
    pub uid: String,
    /// The served map's content hash ([`content_hash`] of its file).
    pub map_hash: String,
    /// The map's name.
    pub map_name: String,
    /// "coop" or "tag".
    pub mode: String,
    /// How long the round lasted, in seconds.
    pub seconds: f64,
    /// Whether it ended at the exit with every treasure found.
    pub cleared: bool,
    /// When it ended, in seconds since the Unix epoch.
    pub ended_at: i64,
    /// Everyone's figures.
    pub players: Vec<PlayerResult>,
}

/// One player's result on a board (their best round there).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// The name they played under (bounded, not yet escaped).
    pub name: String,
    /// The round's length, in seconds (printed to the hundredth).
    #[serde(serialize_with = "hundredths")]
    pub seconds: f64,
    /// Their points.
    pub points: i64,
    /// Treasures they picked up.
    pub items: u64,
    /// Seconds as "it" (tag; printed to the hundredth).
    #[serde(serialize_with = "hundredths")]
    pub it_seconds: f64,
    /// Whether that round was a full clear.
    pub cleared: bool,
    /// Whether they reached the exit.
    pub reached_exit: bool,
    /// When the round ended, in seconds since the Unix epoch.
    pub ended_at: i64,
    /// The map's name then.
    #[serde(skip)]
    pub map_name: String,
}

impl Entry {
    /// The figure a board shows for `mode`: "1:23 clear", "120 pts" or "12s it".
    #[must_use]
    pub fn figure(&self, mode: &str) -> String {
        if mode == "tag" {
            format!("{:.0}s it", self.it_seconds)
        } else if self.cleared {
            format!("{} clear", crate::ui::results::clock(self.seconds))
        } else {
            format!("{} pts", self.points)
        }
    }
}

/// A map's board: the top entries and, for players asked about, their own best.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MapBoard {
    /// Best first, at most [`TOP`].
    pub top: Vec<Entry>,
    /// Own bests by name.
    pub bests: HashMap<String, Entry>,
}

/// Every served map's board, keyed by [`board_key`]; `version` counts updates.
#[derive(Debug, Clone, Default)]
pub struct Boards {
    /// Bumped on every change, so a screen redraws.
    pub version: u64,
    /// The boards.
    pub maps: HashMap<String, MapBoard>,
}

/// Seconds as printed: to the hundredth, so a 30 s round reads `30.0`, not the
/// `30.00000000000065` its sum of ticks makes.
#[must_use]
pub fn rounded_seconds(seconds: f64) -> f64 {
    (seconds * 100.0).round() / 100.0
}

fn hundredths<S: serde::Serializer>(seconds: &f64, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(rounded_seconds(*seconds))
}

/// The key of a map's board for one mode.
#[must_use]
pub fn board_key(map_hash: &str, mode: &str) -> String {
    format!("{map_hash}/{mode}")
}

/// A map file's identity on the leaderboard: FNV-1a (64-bit) of its bytes, in hex. Editing a
/// map starts a new board; renaming or moving it does not.
#[must_use]
pub fn content_hash(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// `name` cut to [`MAX_STORED_NAME`] characters, as stored.
#[must_use]
pub fn bounded_name(name: &str) -> String {
    name.chars().take(MAX_STORED_NAME).collect()
}

/// `name` as printed on a terminal: control and other invisible characters as `\u{..}`
/// escapes (so nothing in a name can move the cursor or change colours), cut to
/// [`MAX_SHOWN_NAME`] characters with a `~`.
#[must_use]
pub fn shown_name(name: &str) -> String {
    let out = escaped(name);
    if out.chars().count() > MAX_SHOWN_NAME {
        let cut: String = out.chars().take(MAX_SHOWN_NAME - 1).collect();
        return cut + "~";
    }
    out
}

/// `text` with control and invisible characters as `\u{..}` escapes (map names, which are
/// not cut).
#[must_use]
pub fn escaped(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        if c.is_control() || c.is_whitespace() && c != ' ' || is_invisible(c) {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
    }
    out
}

/// Format characters that draw nothing but reorder or hide text (bidi controls, zero widths).
fn is_invisible(c: char) -> bool {
    matches!(c, '\u{200b}'..='\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2060}'..='\u{2069}' | '\u{feff}')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_escaped_and_bounded() {
        assert_eq!(shown_name("ann"), "ann");
        assert_eq!(shown_name("a\x1b[2Jb"), "a\\u{1b}[2Jb");
        assert_eq!(shown_name("x\u{202e}y"), "x\\u{202e}y");
        assert_eq!(shown_name("abcdefghijklmnopqrstuvwxyz"), "abcdefghijklmno~");
        assert_eq!(bounded_name(&"z".repeat(100)).len(), MAX_STORED_NAME);
    }

    #[test]
    fn seconds_are_printed_to_the_hundredth() {
        let e = Entry {
            name: "ann".into(),
            seconds: 30.000_000_000_000_65,
            points: 1,
            items: 0,
            it_seconds: 12.345_678,
            cleared: false,
            reached_exit: false,
            ended_at: 0,
            map_name: String::new(),
        };
        let v = serde_json::to_value(&e).unwrap();
        assert_eq!(v["seconds"].to_string(), "30.0");
        assert_eq!(v["it_seconds"].to_string(), "12.35");
    }

    #[test]
    fn content_hashes_are_stable() {
        assert_eq!(content_hash(b""), "cbf29ce484222325");
        assert_eq!(content_hash(b"a"), "af63dc4c8601ec8c");
        assert_ne!(content_hash(b"map 1"), content_hash(b"map 2"));
    }
}
