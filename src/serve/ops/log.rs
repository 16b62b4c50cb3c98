//! The server's log on stderr: one line per event, each naming its session; `--quiet`
//! silences it. Text lines by default; `--log-format json` writes each event as one JSON
//! object (`event`: connect, login, refusal, round_end, disconnect, start_failed, or message
//! for the rest),
//! for log shippers. docs/serving.md lists the fields.

use std::fmt::Display;
use std::net::SocketAddr;
use std::str::FromStr;
use std::time::{SystemTime, UNIX_EPOCH};

use serde_json::{json, Value};

use crate::play::pacing::LinkFigures;

/// How log lines are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LogFormat {
    /// `halfcast serve: [session 3 127.0.0.1:5555] connected`.
    #[default]
    Text,
    /// `{"ts":…,"event":"connect","session":3,"peer":"127.0.0.1:5555"}`.
    Json,
}

impl FromStr for LogFormat {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "text" => Ok(Self::Text),
            "json" => Ok(Self::Json),
            _ => Err(format!("unknown log format '{s}' (text or json)")),
        }
    }
}

/// Writes one log line to stderr. A line nobody can read (stderr closed, its reader gone) is
/// dropped: the log must never end a session or the accept loop, as `eprintln!` would by
/// panicking.
fn line(text: std::fmt::Arguments<'_>) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr().lock(), "{text}");
}

/// Where log lines go (stderr unless quiet), and in which form.
#[derive(Debug, Clone, Copy)]
pub struct Log {
    quiet: bool,
    format: LogFormat,
}

impl Log {
    /// A text log that prints unless `quiet`.
    #[must_use]
    pub fn new(quiet: bool) -> Self {
        Self::with_format(quiet, LogFormat::Text)
    }

    /// A log in `format` that prints unless `quiet`.
    #[must_use]
    pub fn with_format(quiet: bool, format: LogFormat) -> Self {
        Self { quiet, format }
    }

    fn json(&self, event: &str, mut fields: Value) {
        let ts = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0.0, |d| d.as_secs_f64());
        let mut obj = json!({ "ts": (ts * 1000.0).round() / 1000.0, "event": event });
        if let (Some(o), Some(f)) = (obj.as_object_mut(), fields.as_object_mut()) {
            o.append(f);
        }
        line(format_args!("{obj}"));
    }

    /// A server-wide line.
    pub fn server(&self, msg: impl Display) {
        if self.quiet {
            return;
        }
        match self.format {
            LogFormat::Text => line(format_args!("halfcast serve: {msg}")),
            LogFormat::Json => self.json("message", json!({ "text": msg.to_string() })),
        }
    }

    /// The server could not start, and why (written even when quiet: it is the last word).
    pub fn failed_to_start(&self, why: impl Display) {
        match self.format {
            LogFormat::Text => line(format_args!("halfcast serve: cannot start: {why}")),
            LogFormat::Json => self.json("start_failed", json!({ "text": why.to_string() })),
        }
    }

    /// A line about session `id` from `peer`.
    pub fn session(&self, id: u64, peer: SocketAddr, msg: impl Display) {
        if self.quiet {
            return;
        }
        match self.format {
            LogFormat::Text => line(format_args!("halfcast serve: [session {id} {peer}] {msg}")),
            LogFormat::Json => self.json(
                "message",
                json!({ "session": id, "peer": peer.to_string(), "text": msg.to_string() }),
            ),
        }
    }

    /// A connection was accepted.
    pub fn connect(&self, id: u64, peer: SocketAddr) {
        match self.format {
            LogFormat::Text => self.session(id, peer, "connected"),
            LogFormat::Json if !self.quiet => self.json(
                "connect",
                json!({ "session": id, "peer": peer.to_string() }),
            ),
            LogFormat::Json => {}
        }
    }

    /// A connection logged in and started to play (or watch) as `name`.
    pub fn login(&self, id: u64, peer: SocketAddr, name: &str, spectator: bool, term: &str) {
        let what = if spectator { "watching" } else { "playing" };
        match self.format {
            LogFormat::Text => {
                self.session(id, peer, format_args!("{what} as {name:?} (TERM={term:?})"))
            }
            LogFormat::Json if !self.quiet => self.json(
                "login",
                json!({ "session": id, "peer": peer.to_string(), "name": name,
                        "as": what, "term": term, "transport": "ssh" }),
            ),
            LogFormat::Json => {}
        }
    }

    /// A browser page's player started playing (or watching) as `name`.
    pub fn login_web(&self, id: u64, peer: SocketAddr, name: &str, spectator: bool) {
        let what = if spectator { "watching" } else { "playing" };
        match self.format {
            LogFormat::Text => {
                self.session(id, peer, format_args!("{what} as {name:?} in a browser"))
            }
            LogFormat::Json if !self.quiet => self.json(
                "login",
                json!({ "session": id, "peer": peer.to_string(), "name": name,
                        "as": what, "transport": "web" }),
            ),
            LogFormat::Json => {}
        }
    }

    /// A connection was turned away for `reason` (a metrics label) saying `why`; `id` when it
    /// had been accepted first.
    pub fn refusal(&self, id: Option<u64>, peer: SocketAddr, reason: &str, why: impl Display) {
        match (self.format, id) {
            (LogFormat::Text, Some(id)) => self.session(id, peer, format_args!("refused: {why}")),
            (LogFormat::Text, None) => self.server(format_args!("refused {peer}: {why}")),
            (LogFormat::Json, _) if !self.quiet => self.json(
                "refusal",
                json!({ "session": id, "peer": peer.to_string(), "reason": reason,
                        "text": why.to_string() }),
            ),
            (LogFormat::Json, _) => {}
        }
    }

    /// Round `round` (its identity, as the leaderboard's `uid` column holds it) ended on a map
    /// (its name and content hash, and the mode), with each player's figures.
    pub fn round_end(
        &self,
        round: &str,
        (map, hash, mode): (&str, &str, &str),
        seconds: f64,
        players: Value,
    ) {
        match self.format {
            LogFormat::Text => self.server(format_args!(
                "round over on {map} ({mode}, {seconds:.1} s, round {round}): {players}"
            )),
            LogFormat::Json if !self.quiet => self.json(
                "round_end",
                json!({ "round": round, "map": map, "map_hash": hash, "mode": mode,
                        "seconds": seconds, "players": players }),
            ),
            LogFormat::Json => {}
        }
    }

    /// A connection closed after `seconds`, with the bytes it read and wrote on the wire, and
    /// why when it was not the client's own doing.
    pub fn disconnect(
        &self,
        id: u64,
        peer: SocketAddr,
        seconds: f64,
        bytes: (u64, u64),
        link: Option<LinkFigures>,
        error: Option<&str>,
    ) {
        match self.format {
            LogFormat::Text => match error {
                None => self.session(id, peer, format_args!("disconnected after {seconds:.1} s")),
                Some(e) => self.session(
                    id,
                    peer,
                    format_args!("disconnected after {seconds:.1} s: {e}"),
                ),
            },
            LogFormat::Json if !self.quiet => self.json(
                "disconnect",
                json!({ "session": id, "peer": peer.to_string(),
                        "seconds": (seconds * 1000.0).round() / 1000.0,
                        "bytes_in": bytes.0, "bytes_out": bytes.1,
                        "link": link.map(|l| json!({
                            "rtt_ms": (l.rtt.as_secs_f64() * 10_000.0).round() / 10.0,
                            "kbit_per_s": l.rate.map(|r| (r * 8.0 / 1000.0).round()),
                            "max_queued_bytes": l.max_queued,
                            "level_steps_down": l.steps_down,
                            "level_steps_up": l.steps_up,
                        })),
                        "error": error }),
            ),
            LogFormat::Json => {}
        }
    }
}
