//! `halfcast scores --json --db DB` as the leaderboard tests read it: run, checked to succeed,
//! parsed.

use std::ffi::OsStr;
use std::process::Command;

/// The JSON `halfcast scores --json --db db` prints (SQLite file or `postgres://…` URL); panics
/// with its stderr when it fails.
pub fn scores_json(db: impl AsRef<OsStr>) -> serde_json::Value {
    let out = Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(["scores", "--json", "--db"])
        .arg(db)
        .output()
        .expect("halfcast scores runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON")
}
