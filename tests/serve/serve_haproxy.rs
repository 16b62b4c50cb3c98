//! The deployment recipes, tried: a real HAProxy with the shipped config
//! (docs/deploy/haproxy.cfg, its ports moved to free ones) in front of two `halfcast serve
//! --proxy-protocol` processes, and OpenSSH's `ssh` from two source addresses (127.0.0.2 and
//! 127.0.0.3) through it: each plays, and the world's log names the player's own address, not
//! HAProxy's; with one world behind it, the two addresses are limited apart. And the shipped systemd unit passes `systemd-analyze verify`. Each part is
//! skipped with a notice when its tool is not installed.

use crate::serve_process::{free_port, spawn_server, Guard};
use crate::serve_support;

use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use serve_support::openssh::{ssh_available, SshPty};
use serve_support::{header_has, PATIENCE};

fn installed(tool: &str, arg: &str) -> bool {
    Command::new(tool)
        .arg(arg)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

fn deploy(file: &str) -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("docs/deploy")
        .join(file);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// `text` with `from` replaced by `to`, which must be there (the shipped file keeps its shape).
fn moved(text: &str, from: &str, to: &str) -> String {
    assert!(
        text.contains(from),
        "the shipped file no longer has {from:?}"
    );
    text.replace(from, to)
}

/// Reads `rx` until a line satisfies `ok`; that line.
fn line_where(rx: &mpsc::Receiver<String>, ok: impl Fn(&str) -> bool) -> Option<String> {
    let deadline = Instant::now() + PATIENCE;
    while let Some(left) = deadline.checked_duration_since(Instant::now()) {
        match rx.recv_timeout(left.min(Duration::from_millis(100))) {
            Ok(l) if ok(&l) => return Some(l),
            _ => {}
        }
    }
    None
}

/// Runs `ssh` from source address `from` through `port` until it shows the game.
fn play_through(port: u16, from: &str) -> SshPty {
    let ssh = SshPty::spawn(port, &["-b".as_ref(), from.as_ref()], (80, 24));
    let mut screen = vt100::Parser::new(24, 80, 0);
    let deadline = Instant::now() + PATIENCE;
    while !header_has(screen.screen(), "you are ann") {
        let left = deadline
            .checked_duration_since(Instant::now())
            .unwrap_or_else(|| {
                panic!(
                    "ssh from {from} never played:\n{}",
                    screen.screen().contents()
                )
            });
        if let Ok(b) = ssh.rx.recv_timeout(left) {
            screen.process(&b);
        }
    }
    ssh
}

/// HAProxy with the shipped config, listening on a free port, its two worlds at `p1` and
/// `p2`; returns it (stopped when dropped) and its port once it listens.
fn haproxy(dir: &Path, p1: u16, p2: u16) -> (Guard, u16) {
    let front = free_port();
    let cfg = deploy("haproxy.cfg");
    let cfg = moved(&cfg, "bind :22", &format!("bind 127.0.0.1:{front}"));
    let cfg = moved(&cfg, "127.0.0.1:2201", &format!("127.0.0.1:{p1}"));
    let cfg = moved(&cfg, "127.0.0.1:2202", &format!("127.0.0.1:{p2}"));
    let cfg_path = dir.join("haproxy.cfg");
    std::fs::write(&cfg_path, cfg).unwrap();
    let child = Command::new("haproxy")
        .arg("-db")
        .arg("-f")
        .arg(&cfg_path)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("haproxy starts");
    let guard = Guard(child);
    let deadline = Instant::now() + PATIENCE;
    while std::net::TcpStream::connect(("127.0.0.1", front)).is_err() {
        assert!(Instant::now() < deadline, "haproxy never listened");
        std::thread::sleep(Duration::from_millis(50));
    }
    (guard, front)
}

/// Whether HAProxy and OpenSSH's client are both here (a skip notice otherwise).
fn tools() -> bool {
    if !installed("haproxy", "-v") {
        eprintln!("skip: HAProxy is not installed (apt-get install haproxy)");
        return false;
    }
    if !ssh_available() {
        eprintln!("skip: OpenSSH `ssh` is not installed (apt-get install openssh-client)");
        return false;
    }
    true
}

#[test]
fn through_haproxy_two_source_addresses_are_limited_apart() {
    if !tools() {
        return;
    }
    // One world behind both of the config's server lines, so every connection reaches it.
    let dir = tempfile::tempdir().expect("tempdir");
    let (_w, p, _log) = spawn_server(
        dir.path(),
        &["--proxy-protocol", "--db", "none", "--max-per-ip", "1"],
    );
    let (_haproxy, front) = haproxy(dir.path(), p, p);
    let ann = play_through(front, "127.0.0.2");
    // Another address has a place of its own, though HAProxy's address is the same.
    let bob = play_through(front, "127.0.0.3");
    // A second connection from 127.0.0.2 is over --max-per-ip 1, and ssh says so.
    let carol = SshPty::spawn(front, &["-b".as_ref(), "127.0.0.2".as_ref()], (80, 24));
    let mut said = Vec::new();
    let deadline = Instant::now() + PATIENCE;
    let want = b"too many connections from your address";
    while !said.windows(want.len()).any(|w| w == want) {
        let left = deadline
            .checked_duration_since(Instant::now())
            .unwrap_or_else(|| panic!("not refused: {}", String::from_utf8_lossy(&said)));
        match carol.rx.recv_timeout(left) {
            Ok(b) => said.extend_from_slice(&b),
            Err(_) => panic!("not refused: {}", String::from_utf8_lossy(&said)),
        }
    }
    for mut ssh in [ann, bob, carol] {
        let _ = ssh.child.kill();
        let _ = ssh.child.wait();
    }
}

#[test]
fn openssh_through_haproxy_plays_and_the_world_logs_the_players_own_address() {
    if !tools() {
        return;
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let flags = ["--proxy-protocol", "--db", "none", "--max-per-ip", "1"];
    let (w1dir, w2dir) = (dir.path().join("w1"), dir.path().join("w2"));
    std::fs::create_dir_all(&w1dir).unwrap();
    std::fs::create_dir_all(&w2dir).unwrap();
    let (_w1, p1, log1) = spawn_server(&w1dir, &flags);
    let (_w2, p2, log2) = spawn_server(&w2dir, &flags);
    let (_haproxy, front) = haproxy(dir.path(), p1, p2);

    let ann = play_through(front, "127.0.0.2");
    let bob = play_through(front, "127.0.0.3");
    // Each world logs its players under their own addresses (HAProxy's is 127.0.0.1).
    let (tx, logs) = mpsc::channel();
    for rx in [log1, log2] {
        let tx = tx.clone();
        std::thread::spawn(move || {
            while let Ok(l) = rx.recv() {
                if tx.send(l).is_err() {
                    break;
                }
            }
        });
    }
    let mut seen = Vec::new();
    for _ in 0..2 {
        let l =
            line_where(&logs, |l| l.contains("] playing as \"ann")).expect("a world logs a player");
        seen.push(l);
    }
    for from in ["127.0.0.2:", "127.0.0.3:"] {
        assert!(
            seen.iter().any(|l| l.contains(&format!(" {from}"))),
            "no player logged from {from}: {seen:#?}"
        );
    }
    assert!(seen.iter().all(|l| !l.contains(" 127.0.0.1:")), "{seen:#?}");
    for mut ssh in [ann, bob] {
        let _ = ssh.child.kill();
        let _ = ssh.child.wait();
    }
}

#[test]
fn the_shipped_systemd_unit_passes_systemd_analyze_verify() {
    if !installed("systemd-analyze", "--version") {
        eprintln!("skip: systemd-analyze is not installed (apt-get install systemd)");
        return;
    }
    let dir = tempfile::tempdir().expect("tempdir");
    // The unit names /usr/local/bin/halfcast; verify checks that it exists, so point it at
    // the binary under test.
    let unit = moved(
        &deploy("halfcast@.service"),
        "ExecStart=/usr/local/bin/halfcast ",
        &format!("ExecStart={} ", env!("CARGO_BIN_EXE_halfcast")),
    );
    let path = dir.path().join("halfcast@1.service");
    std::fs::write(&path, unit).unwrap();
    let out = Command::new("systemd-analyze")
        .arg("verify")
        .arg(&path)
        .output()
        .expect("systemd-analyze runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    // Unknown or misspelt settings are only warnings: none may appear.
    assert!(
        !err.contains("halfcast@1.service"),
        "systemd-analyze warned:\n{err}"
    );
}
