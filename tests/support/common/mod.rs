//! Helpers shared by the integration tests: running the binary and finding ../shared.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The project root (where Cargo.toml is), so fixture paths in messages are stable.
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Runs the halfcast binary with `args` from the project root, no stdin.
pub fn halfcast(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(args)
        .current_dir(root())
        .stdin(std::process::Stdio::null())
        .output()
        .expect("run halfcast")
}

/// [`halfcast`], asserting it succeeded (the failure message shows its stderr).
pub fn halfcast_ok(args: &[&str]) -> Output {
    let out = halfcast(args);
    assert_eq!(
        out.status.code(),
        Some(0),
        "halfcast {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// `../shared` beside the project, or `None` after printing a skip notice.
pub fn shared_dir(what: &str) -> Option<PathBuf> {
    let dir = root().join("../shared");
    if dir.is_dir() {
        Some(dir)
    } else {
        println!("SKIPPED {what}: ../shared is not beside the project");
        None
    }
}

/// Runs `halfcast replay FIXTURE --format cast [extra…]` into a temporary file and returns the
/// asciicast text (panics with stderr if the command fails).
pub fn replay_cast(fixture: &str, extra: &[&str]) -> String {
    let dir = tempfile::tempdir().expect("temp dir");
    let cast = dir.path().join("run.cast");
    let mut args = vec!["replay", fixture];
    args.extend_from_slice(extra);
    args.extend([
        "--format",
        "cast",
        "--out",
        cast.to_str().expect("utf-8 path"),
    ]);
    let out = halfcast(&args);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::read_to_string(&cast).expect("read the cast")
}
