//! A private tmux server for one test: start a session, send keys, read the pane back with
//! `capture-pane`. A test asks for one with [`Tmux::new`], which prints a skip notice and gives
//! `None` when tmux is not installed.

use std::process::{Command, Output};
use std::thread;
use std::time::{Duration, Instant};

/// A hang guard only (the test never asserts on speed).
pub const PATIENCE: Duration = Duration::from_secs(60);

/// One tmux server on its own socket; killed when dropped. Its session is named `t`.
pub struct Tmux {
    socket: String,
}

impl Tmux {
    /// A private tmux server for one test (named `halfcast-NAME-PID`), or `None` with a skip
    /// notice when tmux is not installed.
    pub fn new(name: &str) -> Option<Self> {
        if Command::new("tmux").arg("-V").output().is_err() {
            eprintln!("skipping: tmux is not installed");
            return None;
        }
        Some(Self {
            socket: format!("halfcast-{name}-{}", std::process::id()),
        })
    }

    /// Runs a tmux command against this server.
    pub fn run(&self, args: &[&str]) -> Output {
        Command::new("tmux")
            .args(["-L", &self.socket, "-f", "/dev/null"])
            .args(args)
            .env_remove("TMUX")
            .output()
            .expect("run tmux")
    }

    /// Starts the session `t`, detached, `cols`×`rows`, with `env` (`NAME=value`) set in it,
    /// running `command`; asserts tmux accepted it.
    pub fn start(&self, (cols, rows): (u16, u16), env: &[&str], command: &[&str]) {
        let (cols, rows) = (cols.to_string(), rows.to_string());
        let mut args = vec!["new-session", "-d"];
        for e in env {
            args.extend(["-e", e]);
        }
        args.extend(["-s", "t", "-x", &cols, "-y", &rows]);
        args.extend(command);
        let started = self.run(&args);
        assert!(started.status.success(), "{started:?}");
    }

    /// A tmux command's standard output.
    pub fn text(&self, args: &[&str]) -> String {
        String::from_utf8_lossy(&self.run(args).stdout).into_owned()
    }

    /// The pane's text (with its SGR colours when `colours`).
    pub fn capture(&self, colours: bool) -> String {
        if colours {
            self.text(&["capture-pane", "-t", "t", "-p", "-e"])
        } else {
            self.text(&["capture-pane", "-t", "t", "-p"])
        }
    }

    /// Captures the pane until `ok` holds for it (a hang guard of [`PATIENCE`]).
    pub fn wait_for(&self, what: &str, ok: impl Fn(&str) -> bool) -> String {
        let start = Instant::now();
        loop {
            let screen = self.capture(false);
            if ok(&screen) {
                return screen;
            }
            assert!(
                start.elapsed() < PATIENCE,
                "gave up waiting for {what}:\n{screen}"
            );
            thread::sleep(Duration::from_millis(50));
        }
    }
}

impl Drop for Tmux {
    fn drop(&mut self) {
        let _ = self.run(&["kill-server"]);
    }
}
