//! Under tmux (3.3 answers neither XTGETTCAP nor DECRQSS, only DA1), with
//! `TERM=xterm-256color` and no `COLORTERM`, the game still starts at once, at 256 colours by
//! the `TERM` rule, and says so. Skipped with a notice when tmux is not installed.

use std::process::{Command, Output};
use std::thread;
use std::time::{Duration, Instant};

/// A hang guard only (the test never asserts on speed).
const PATIENCE: Duration = Duration::from_secs(60);

struct Tmux(String);

impl Tmux {
    fn run(&self, args: &[&str]) -> Output {
        Command::new("tmux")
            .args(["-L", &self.0, "-f", "/dev/null"])
            .args(args)
            .env_remove("TMUX")
            .output()
            .expect("run tmux")
    }

    fn status(&self) -> String {
        let out = self.run(&["capture-pane", "-t", "t", "-p"]);
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .rev()
            .find(|l| !l.trim().is_empty())
            .unwrap_or_default()
            .to_owned()
    }

    fn wait_status(&self, needle: &str) {
        let start = Instant::now();
        loop {
            let s = self.status();
            if s.contains(needle) {
                return;
            }
            assert!(start.elapsed() < PATIENCE, "no {needle:?} in: {s}");
            thread::sleep(Duration::from_millis(50));
        }
    }
}

impl Drop for Tmux {
    fn drop(&mut self) {
        let _ = self.run(&["kill-server"]);
    }
}

#[test]
fn under_tmux_xterm_256color_gets_256_by_the_term_rule() {
    if Command::new("tmux").arg("-V").output().is_err() {
        eprintln!("skipping: tmux is not installed");
        return;
    }
    let tmux = Tmux(format!("halfcast-colour-{}", std::process::id()));
    let bin = env!("CARGO_BIN_EXE_halfcast");
    let started = tmux.run(&[
        "new-session",
        "-d",
        "-s",
        "t",
        "-x",
        "140",
        "-y",
        "30",
        "env",
        "-u",
        "COLORTERM",
        "-u",
        "NO_COLOR",
        "TERM=xterm-256color",
        bin,
        "--fps",
        "30",
    ]);
    assert!(started.status.success(), "{started:?}");
    tmux.wait_status(" 256 (TERM)");
    let _ = tmux.run(&["send-keys", "-t", "t", "o"]);
    tmux.wait_status(" 16 (O key)");
    let _ = tmux.run(&["send-keys", "-t", "t", "q"]);
}
