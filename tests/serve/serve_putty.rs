//! A real PuTTY (Debian's `putty`, on an Xvfb display) joins `halfcast serve` with its defaults
//! (`TERM=xterm`, answerback `PuTTY`) and is shown 24-bit colour as `truecolor (PuTTY)`, read
//! from PuTTY's own session log. Skipped without `putty` or `Xvfb`; `.ci/run` installs them.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use russh::keys::HashAlg;

use crate::serve_support;

/// Whether `name` is an executable on `PATH`.
fn on_path(name: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|paths| std::env::split_paths(&paths).any(|dir| dir.join(name).is_file()))
}

/// A child process killed when dropped.
struct Killed(Child);

impl Drop for Killed {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Starts Xvfb on a free display; returns it and the display's name (`:N`).
fn xvfb() -> Option<(Killed, String)> {
    let mut child = Command::new("Xvfb")
        .args([
            "-displayfd",
            "1",
            "-screen",
            "0",
            "800x600x24",
            "-nolisten",
            "tcp",
        ])
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .ok()?;
    let out = child.stdout.take()?;
    let child = Killed(child);
    let mut line = String::new();
    BufReader::new(out).read_line(&mut line).ok()?;
    let n = line.trim();
    (!n.is_empty()).then(|| (child, format!(":{n}")))
}

/// The SHA-256 fingerprint of the host key at `path`, as PuTTY's `-hostkey` takes it.
fn fingerprint(path: &Path) -> String {
    let key = russh::keys::load_secret_key(path, None).expect("host key");
    key.public_key().fingerprint(HashAlg::Sha256).to_string()
}

#[test]
fn putty_with_its_defaults_is_shown_truecolor_putty() {
    if !on_path("putty") || !on_path("Xvfb") {
        println!("SKIPPED: PuTTY or Xvfb is not installed (apt-get install putty xvfb)");
        return;
    }
    let Some((_x, display)) = xvfb() else {
        println!("SKIPPED: Xvfb would not start");
        return;
    };
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    let (srv, dir) = rt.block_on(serve_support::server(|_| {}));
    let log = dir.path().join("putty.log");
    let port = srv.local_addr().port().to_string();
    let hostkey = fingerprint(&dir.path().join("hk"));
    let _putty = Killed(
        Command::new("putty")
            .env("DISPLAY", &display)
            // PuTTY keeps its settings and random seed in $HOME/.putty: not the tester's.
            .env("HOME", dir.path())
            .args(["-ssh", "-P", &port, "-hostkey", &hostkey, "-sessionlog"])
            .arg(&log)
            .arg("ann@127.0.0.1")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("start putty"),
    );
    let deadline = Instant::now() + serve_support::PATIENCE;
    let mut shown = Vec::new();
    while Instant::now() < deadline {
        shown = std::fs::read(&log).unwrap_or_default();
        if String::from_utf8_lossy(&shown).contains("| truecolor (PuTTY) |") {
            break;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    let text = String::from_utf8_lossy(&shown);
    assert!(
        text.contains("| truecolor (PuTTY) |"),
        "PuTTY's session shows no `truecolor (PuTTY)`: {}",
        text.chars().take(2000).collect::<String>()
    );
    // The session still runs (an answerback typed as keys could have quit it).
    assert_eq!(
        srv.live(),
        (0, 1),
        "the session ended (logging in, playing)"
    );
    rt.block_on(srv.shutdown());
}
