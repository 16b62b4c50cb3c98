//! The deployment recipes, tried: a real HAProxy with the shipped snippet
//! (docs/deploy/haproxy-halfcast.cfg, its ports moved to free ones) in front of two `halfcast
//! serve --proxy-protocol` processes, and OpenSSH's `ssh` from two source addresses (127.0.0.2 and
//! 127.0.0.3) through it: each plays, and the world's log names the player's own address, not
//! HAProxy's; with one world behind it, the two addresses are limited apart. And the shipped
//! systemd unit passes `systemd-analyze verify`. Each part is skipped with a notice when its
//! tool is not installed. The fleet's behaviour over time (one host key, restarts, health
//! checks) is in serve_fleet.rs, with the helpers here.

use crate::serve_process::{free_port, spawn_listening, spawn_server, Guard};
use crate::serve_support;

use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use serve_support::openssh::{ssh_available, SshPty};
use serve_support::{header_has, PATIENCE};

pub(crate) fn installed(tool: &str, arg: &str) -> bool {
    Command::new(tool)
        .arg(arg)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

pub(crate) fn deploy(file: &str) -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("docs/deploy")
        .join(file);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// `text` with `from` replaced by `to`, which must be there (the shipped file keeps its shape).
pub(crate) fn moved(text: &str, from: &str, to: &str) -> String {
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

/// A world behind the balancer: its SSH port and its metrics (and health) port.
#[derive(Debug, Clone, Copy)]
pub(crate) struct World {
    pub(crate) ssh: u16,
    pub(crate) metrics: u16,
}

/// Starts `halfcast serve --proxy-protocol --metrics` with `extra` flags and its host key at
/// `dir/hk`.
pub(crate) fn world(dir: &Path, extra: &[&str]) -> (Guard, World, mpsc::Receiver<String>) {
    let metrics = free_port();
    let m = metrics.to_string();
    let mut flags = vec!["--proxy-protocol", "--metrics", &m];
    flags.extend_from_slice(extra);
    let (guard, ssh, log) = spawn_server(dir, &flags);
    (guard, World { ssh, metrics }, log)
}

/// The test's HAProxy configuration: a `global` and a distribution's `defaults` (in `mode
/// http`, as Debian ships it) of our own, a frontend on `probe` that turns every connection
/// away (it answers once HAProxy listens, and sends no world a connection), then the shipped
/// snippet as it is, with its bind port and its two worlds' ports moved to free ones.
fn config(front: u16, probe: u16, w1: World, w2: World) -> String {
    let snippet = deploy("haproxy-halfcast.cfg");
    let snippet = moved(&snippet, "bind :22\n", &format!("bind :{front}\n"));
    let snippet = moved(
        &snippet,
        "bind :::22 v6only",
        &format!("bind :::{front} v6only"),
    );
    let snippet = moved(
        &snippet,
        "127.0.0.1:2201 port 9101",
        &format!("127.0.0.1:{} port {}", w1.ssh, w1.metrics),
    );
    let snippet = moved(
        &snippet,
        "127.0.0.1:2202 port 9102",
        &format!("127.0.0.1:{} port {}", w2.ssh, w2.metrics),
    );
    format!(
        "global\n    maxconn 1024\n\ndefaults\n    mode http\n    timeout connect 5s\n    \
         timeout client 50s\n    timeout server 50s\n\nfrontend probe\n    mode tcp\n    \
         bind 127.0.0.1:{probe}\n    tcp-request connection reject\n\n{snippet}"
    )
}

/// HAProxy with the shipped snippet in front of worlds `w1` and `w2`, listening on a free
/// port; returns it (stopped when dropped) and its port once it listens.
pub(crate) fn haproxy(dir: &Path, w1: World, w2: World) -> (Guard, u16) {
    let (front, probe) = (free_port(), free_port());
    let cfg_path = dir.join("haproxy.cfg");
    std::fs::write(&cfg_path, config(front, probe, w1, w2)).unwrap();
    let mut haproxy = Command::new("haproxy");
    haproxy.arg("-db").arg("-f").arg(&cfg_path);
    // HAProxy binds every listener before it serves any: once the probe answers, so does
    // the front.
    (spawn_listening(haproxy, probe), front)
}

/// Whether HAProxy and OpenSSH's client are both here (a skip notice otherwise).
pub(crate) fn tools() -> bool {
    if !installed("haproxy", "-v") {
        eprintln!("SKIPPED: HAProxy is not installed (apt-get install haproxy)");
        return false;
    }
    if !ssh_available() {
        eprintln!("SKIPPED: OpenSSH `ssh` is not installed (apt-get install openssh-client)");
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
    let (_w, w, _log) = world(dir.path(), &["--db", "none", "--max-per-ip", "1"]);
    let (_haproxy, front) = haproxy(dir.path(), w, w);
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
    let flags = ["--db", "none", "--max-per-ip", "1"];
    let (w1dir, w2dir) = (dir.path().join("w1"), dir.path().join("w2"));
    std::fs::create_dir_all(&w1dir).unwrap();
    std::fs::create_dir_all(&w2dir).unwrap();
    let (_w1, w1, log1) = world(&w1dir, &flags);
    let (_w2, w2, log2) = world(&w2dir, &flags);
    let (_haproxy, front) = haproxy(dir.path(), w1, w2);

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
fn the_shipped_systemd_units_pass_systemd_analyze_verify() {
    if !installed("systemd-analyze", "--version") {
        eprintln!("SKIPPED: systemd-analyze is not installed (apt-get install systemd)");
        return;
    }
    let dir = tempfile::tempdir().expect("tempdir");
    // The units name /usr/local/bin/halfcast; verify checks that it exists, so point them at
    // the binary under test.
    let exe = |unit: &str| {
        moved(
            &deploy(unit),
            "ExecStart=/usr/local/bin/halfcast ",
            &format!("ExecStart={} ", env!("CARGO_BIN_EXE_halfcast")),
        )
    };
    let files = [
        ("halfcast@1.service", exe("halfcast@.service")),
        ("halfcast-backup.service", exe("halfcast-backup.service")),
        ("halfcast-backup.timer", deploy("halfcast-backup.timer")),
    ];
    for (name, text) in &files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    for (name, _) in &files {
        let out = Command::new("systemd-analyze")
            .arg("verify")
            .arg(dir.path().join(name))
            .output()
            .expect("systemd-analyze runs");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{name}: {err}");
        // Unknown or misspelt settings are only warnings: none may appear.
        assert!(
            !err.contains("halfcast"),
            "systemd-analyze warned about {name}:\n{err}"
        );
    }
}
