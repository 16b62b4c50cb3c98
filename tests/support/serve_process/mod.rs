//! `halfcast serve` as a process of its own (what needs the binary: process-wide metrics, the
//! command line's flags, a log read line by line), stopped by the test that started it.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::serve_support::PATIENCE;

/// Kills the server if the test fails before stopping it.
pub struct Guard(pub Child);

impl Drop for Guard {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A port free now on the loopback address (the OS may hand it out again: tests use it at once).
pub fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .expect("a free port")
        .port()
}

/// Starts `cmd` (a proxy in front of the server: HAProxy, Caddy) with its output thrown away,
/// and returns it once something listens on `port` of the loopback address.
pub fn spawn_listening(mut cmd: Command, port: u16) -> Guard {
    let what = cmd.get_program().to_string_lossy().into_owned();
    let child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("{what} starts: {e}"));
    let guard = Guard(child);
    let deadline = Instant::now() + PATIENCE;
    while std::net::TcpStream::connect(("127.0.0.1", port)).is_err() {
        assert!(Instant::now() < deadline, "{what} never listened");
        std::thread::sleep(Duration::from_millis(50));
    }
    guard
}

/// Starts `halfcast serve` on `port` with its host key at `host_key`, `extra` flags and `env`
/// (HALFCAST_PASSWORD unset unless `env` gives it); returns it and its stderr lines as they come.
pub fn spawn(
    port: u16,
    host_key: &std::path::Path,
    extra: &[&str],
    env: &[(&str, &str)],
) -> (Guard, mpsc::Receiver<String>) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args([
            "serve",
            "--listen",
            &format!("127.0.0.1:{port}"),
            "--host-key",
        ])
        .arg(host_key)
        .args(extra)
        .env_remove("HALFCAST_PASSWORD")
        .envs(env.iter().copied())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("halfcast serve starts");
    let stderr = child.stderr.take().expect("stderr");
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    (Guard(child), rx)
}

/// Starts `halfcast serve` with `extra` flags and its host key in `dir`; returns it, its SSH
/// port and its stderr lines once it listens.
pub fn spawn_server(dir: &std::path::Path, extra: &[&str]) -> (Guard, u16, mpsc::Receiver<String>) {
    let port = free_port();
    let (guard, rx) = spawn(port, &dir.join("hk"), extra, &[]);
    let deadline = Instant::now() + PATIENCE;
    loop {
        let line = rx
            .recv_timeout(deadline.saturating_duration_since(Instant::now()))
            .expect("the server said it listens");
        if line.contains("listening on") {
            break;
        }
    }
    (guard, port, rx)
}
