//! The browser checks' common ground: whether Debian's Chromium and Playwright for Python are
//! here, and running one of `tests/serve/browser/*.py` to its last line of JSON.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

/// Where Debian's `chromium` package puts the browser.
pub const CHROMIUM: &str = "/usr/bin/chromium";

/// Whether Chromium and Playwright for Python are installed; prints the skip notice when not.
pub fn ready() -> bool {
    let here = Path::new(CHROMIUM).exists()
        && Command::new("python3")
            .args(["-c", "import playwright"])
            .output()
            .is_ok_and(|o| o.status.success());
    if !here {
        eprintln!("skip: no {CHROMIUM} or no Python playwright (apt-get install chromium; pip install playwright)");
    }
    here
}

/// `tests/serve/browser/NAME`.
pub fn script(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/serve/browser")
        .join(name)
}

/// Starts `browser/NAME ARGS…` with its output piped, for a test that acts while it runs.
pub fn start(name: &str, args: &[&std::ffi::OsStr]) -> Child {
    Command::new("python3")
        .arg(script(name))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("python3 runs")
}

/// Waits for a check started by [`start`]: its last line's JSON, or the test fails with all it
/// printed.
pub fn finish(name: &str, child: Child) -> serde_json::Value {
    let done = child.wait_with_output().expect("its output");
    let stdout = String::from_utf8_lossy(&done.stdout);
    assert!(
        done.status.success(),
        "{name} failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&done.stderr)
    );
    serde_json::from_str(stdout.lines().last().unwrap_or("")).expect("JSON")
}

/// Runs `browser/NAME ARGS…` to its end: its last line's JSON.
pub fn run(name: &str, args: &[&std::ffi::OsStr]) -> serde_json::Value {
    finish(name, start(name, args))
}
