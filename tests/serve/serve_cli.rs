//! The `halfcast serve` command as a user runs it: flags, exit codes, the host key kept across
//! restarts, and a clean stop on SIGTERM. The server process is always stopped by the test.

use crate::serve_support;

use std::process::Command;
use std::sync::mpsc;
use std::time::Duration;

use crate::serve_process::{free_port, spawn as spawn_with, Guard};
use serve_support::{header_has, Client};

fn halfcast() -> Command {
    Command::new(env!("CARGO_BIN_EXE_halfcast"))
}

/// Starts the server and returns it with its stderr lines (as they come).
fn spawn(port: u16, host_key: &std::path::Path) -> (Guard, mpsc::Receiver<String>) {
    spawn_with(port, host_key, &[], &[])
}

/// Collects lines until one contains `needle` (or the server's stderr ends / patience runs out).
fn wait_line(rx: &mpsc::Receiver<String>, needle: &str, seen: &mut Vec<String>) -> bool {
    let deadline = std::time::Instant::now() + serve_support::PATIENCE;
    while let Some(left) = deadline.checked_duration_since(std::time::Instant::now()) {
        match rx.recv_timeout(left) {
            Ok(l) => {
                let hit = l.contains(needle);
                seen.push(l);
                if hit {
                    return true;
                }
            }
            Err(_) => return false,
        }
    }
    false
}

#[test]
fn bad_serve_flags_exit_2_with_a_message() {
    let dir = tempfile::tempdir().expect("tempdir");
    let garbage_key = dir.path().join("garbage");
    std::fs::write(&garbage_key, "not a key").expect("write");
    let open_key = dir.path().join("open_key");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let private = std::fs::Permissions::from_mode(0o600);
        std::fs::set_permissions(&garbage_key, private).expect("chmod");
        // A real key, but readable by everyone: sshd refuses such a key, and so do we.
        std::fs::write(
            &open_key,
            russh::keys::PrivateKey::from(
                russh::keys::ssh_key::private::Ed25519Keypair::from_seed(&[3; 32]),
            )
            .to_openssh(russh::keys::ssh_key::LineEnding::LF)
            .expect("encode")
            .as_bytes(),
        )
        .expect("write key");
        std::fs::set_permissions(&open_key, std::fs::Permissions::from_mode(0o644)).expect("chmod");
    }
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec!["--password".into(), String::new()],
            "must not be empty",
        ),
        (
            vec!["--authorized-keys".into(), "/no/such/file".into()],
            "authorized keys /no/such/file",
        ),
        (
            vec!["--host-key".into(), garbage_key.display().to_string()],
            "not an OpenSSH private key",
        ),
        (vec!["--max-sessions".into(), "0".into()], "max-sessions"),
        (
            vec!["--max-startups".into(), "60:30:10".into()],
            "--max-startups \"60:30:10\": full must not be below start",
        ),
        (vec!["--login-grace".into(), "0".into()], "login-grace"),
        (
            vec!["--password-file".into(), "/no/such/pw".into()],
            "password file /no/such/pw",
        ),
        (vec!["--listen".into(), "nowhere".into()], "listen"),
        (
            vec![
                "--password".into(),
                "x".into(),
                "--authorized-keys".into(),
                "k".into(),
            ],
            "cannot be used with",
        ),
    ];
    #[cfg(unix)]
    let cases = {
        let mut cases = cases;
        cases.push((
            vec!["--host-key".into(), open_key.display().to_string()],
            "is readable by others (mode 644); run chmod 600",
        ));
        cases
    };
    for (args, msg) in cases {
        let mut cmd = halfcast();
        cmd.arg("serve");
        if !args.iter().any(|a| a == "--listen") {
            cmd.args(["--listen", "127.0.0.1:0"]);
        }
        if !args.iter().any(|a| a == "--host-key") {
            cmd.arg("--host-key").arg(dir.path().join("hk"));
        }
        let out = cmd.args(&args).output().expect("run");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(msg), "{args:?}: {err}");
    }
}

#[test]
fn serves_a_frame_keeps_its_host_key_and_stops_on_sigterm() {
    let dir = tempfile::tempdir().expect("tempdir");
    let key = dir.path().join("host_ed25519");
    let mut fingerprints = Vec::new();
    for round in 0..2 {
        let port = free_port();
        let (mut child, rx) = spawn(port, &key);
        let mut seen = Vec::new();
        assert!(wait_line(&rx, "listening on", &mut seen), "{seen:?}");
        let fp = seen
            .iter()
            .find(|l| l.contains("host key ssh-ed25519 SHA256:"))
            .cloned()
            .expect("fingerprint logged");
        fingerprints.push(fp);
        assert_eq!(
            seen.iter().any(|l| l.contains("generated a new host key")),
            round == 0
        );
        let rt = tokio::runtime::Runtime::new().expect("runtime");
        rt.block_on(async {
            let addr = format!("127.0.0.1:{port}").parse().expect("addr");
            let mut c = Client::connect(addr, "ann", 50, 14, "xterm-256color").await;
            assert!(c.until(|s| header_has(s, "you are ann")).await);
        });
        assert!(
            wait_line(&rx, "[session 1 127.0.0.1:", &mut seen),
            "{seen:?}"
        );
        let pid = child.0.id().to_string();
        let killed = Command::new("kill").args(["-TERM", &pid]).status();
        if killed.is_err() {
            eprintln!("skip: no `kill` command to send SIGTERM");
            return;
        }
        let mut status = None;
        for _ in 0..200 {
            if let Some(s) = child.0.try_wait().expect("wait") {
                status = Some(s);
                break;
            }
            std::thread::sleep(Duration::from_millis(25));
        }
        let status = status.expect("the server exits after SIGTERM");
        assert!(status.success(), "{status:?}");
        assert!(
            wait_line(&rx, "served 1 connections", &mut seen)
                || seen.iter().any(|l| l.contains("served")),
            "{seen:?}"
        );
    }
    assert_eq!(
        fingerprints[0], fingerprints[1],
        "same host key after a restart"
    );
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(&key).expect("key").permissions().mode() & 0o777;
        assert_eq!(mode, 0o600);
    }
}

#[test]
fn a_server_whose_log_nobody_reads_goes_on_serving() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (_server, port, rx) = crate::serve_process::spawn_server(dir.path(), &["--db", "none"]);
    // The reader of the server's stderr stops at the next line (the first connection's), and
    // the pipe closes: every later line fails to write.
    drop(rx);
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    rt.block_on(async {
        let addr = format!("127.0.0.1:{port}").parse().expect("addr");
        for name in ["ann", "bob", "cat"] {
            let mut c = Client::connect(addr, name, 50, 14, "xterm-256color").await;
            assert!(
                c.until(|s| header_has(s, &format!("you are {name}"))).await,
                "{name} plays with the log's pipe closed"
            );
        }
    });
}

/// Waits for the server to listen.
fn listening(rx: &mpsc::Receiver<String>) {
    let mut seen = Vec::new();
    assert!(wait_line(rx, "listening on", &mut seen), "{seen:?}");
}

/// Logs in with `password` (true if accepted).
fn password_accepted(port: u16, password: &str) -> bool {
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    rt.block_on(async {
        let addr = format!("127.0.0.1:{port}").parse().expect("addr");
        let mut h = serve_support::connect_raw(addr, None)
            .await
            .expect("connect");
        h.authenticate_password("ann", password)
            .await
            .expect("auth")
            .success()
    })
}

#[test]
fn the_password_comes_from_a_file_or_the_environment_and_the_command_line_warns() {
    let dir = tempfile::tempdir().expect("tempdir");
    let key = dir.path().join("hk");
    let pw = dir.path().join("pw");
    std::fs::write(&pw, "from-file\n").expect("write");
    let pw_arg = pw.display().to_string();

    let port = free_port();
    let (_child, rx) = spawn_with(port, &key, &["--password-file", &pw_arg], &[]);
    listening(&rx);
    assert!(password_accepted(port, "from-file"));
    assert!(!password_accepted(port, "from-file\n"));

    let port = free_port();
    let (_child, rx) = spawn_with(port, &key, &[], &[("HALFCAST_PASSWORD", "from-env")]);
    listening(&rx);
    assert!(password_accepted(port, "from-env"));
    assert!(!password_accepted(port, "from-file"));

    let port = free_port();
    let (_child, rx) = spawn_with(port, &key, &["--password", "on-the-line"], &[]);
    let mut seen = Vec::new();
    assert!(
        wait_line(
            &rx,
            "warning: --password is visible to every local user",
            &mut seen
        ),
        "{seen:?}"
    );
    listening(&rx);
    assert!(password_accepted(port, "on-the-line"));

    let out = halfcast()
        .args(["serve", "--listen", "127.0.0.1:0", "--host-key"])
        .arg(&key)
        .args(["--authorized-keys", "/no/such/keys"])
        .env("HALFCAST_PASSWORD", "x")
        .output()
        .expect("run");
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("choose one way to log in"));
}
