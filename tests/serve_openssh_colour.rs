//! OpenSSH's own `ssh` with `TERM=xterm-256color` (it does not forward `COLORTERM`): the server
//! asks the client's terminal for 24-bit colour over the channel, or takes `COLORTERM` from
//! `ssh -o SetEnv=…`. Skipped with a notice where `ssh` is not installed.

mod serve_support;

use std::io::{Read, Write};
use std::sync::mpsc;
use std::time::Instant;

use portable_pty::{native_pty_system, CommandBuilder, PtySize};
use serve_support::{header_has, row_text, server, PATIENCE};

/// The query's first bytes (XTGETTCAP `RGB`).
const QUERY_START: &[u8] = b"\x1bP+q524742\x1b\\";

fn ssh_available() -> bool {
    std::process::Command::new("ssh")
        .arg("-V")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Runs `ssh EXTRA… ann@server` in an 80×24 pty playing a terminal that answers the colour
/// query with `answer`; returns the header once it shows `want` (or what it showed instead),
/// and whether the query was seen.
fn header_via_openssh(extra: &[&str], answer: &[u8], want: &str) -> (String, bool) {
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    let (srv, _dir) = rt.block_on(server(|_| {}));
    let port = srv.local_addr().port().to_string();
    let pty = native_pty_system()
        .openpty(PtySize {
            rows: 24,
            cols: 80,
            pixel_width: 0,
            pixel_height: 0,
        })
        .expect("pty");
    let mut cmd = CommandBuilder::new("ssh");
    cmd.args(["-tt", "-F", "/dev/null", "-p", &port]);
    cmd.args([
        "-o",
        "StrictHostKeyChecking=no",
        "-o",
        "UserKnownHostsFile=/dev/null",
    ]);
    cmd.args([
        "-o",
        "BatchMode=yes",
        "-o",
        "ConnectTimeout=10",
        "-o",
        "LogLevel=ERROR",
    ]);
    cmd.args(extra);
    cmd.arg("ann@127.0.0.1");
    cmd.env("TERM", "xterm-256color");
    cmd.env_remove("COLORTERM");
    let mut child = pty.slave.spawn_command(cmd).expect("spawn ssh");
    drop(pty.slave);
    let mut reader = pty.master.try_clone_reader().expect("reader");
    let mut writer = pty.master.take_writer().expect("writer");
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut buf = [0u8; 8192];
        while let Ok(n) = reader.read(&mut buf) {
            if n == 0 || tx.send(buf[..n].to_vec()).is_err() {
                break;
            }
        }
    });
    let mut screen = vt100::Parser::new(24, 80, 0);
    let mut seen = Vec::new();
    let mut queried = false;
    let deadline = Instant::now() + PATIENCE;
    while !header_has(screen.screen(), want) {
        let Some(left) = deadline.checked_duration_since(Instant::now()) else {
            break;
        };
        let Ok(b) = rx.recv_timeout(left) else {
            break;
        };
        seen.extend_from_slice(&b);
        screen.process(&b);
        if !queried && seen.windows(QUERY_START.len()).any(|w| w == QUERY_START) {
            queried = true;
            writer.write_all(answer).expect("answer");
        }
    }
    let header = row_text(screen.screen(), 0);
    writer.write_all(b"\x03").expect("quit");
    let _ = child.kill();
    let _ = child.wait();
    rt.block_on(srv.shutdown());
    (header, queried)
}

#[test]
fn a_terminal_answering_rgb_through_openssh_gets_truecolor() {
    if !ssh_available() {
        eprintln!("skip: OpenSSH `ssh` is not installed (apt-get install openssh-client)");
        return;
    }
    let want = "truecolor (terminal said so)";
    let (h, queried) = header_via_openssh(&[], b"\x1bP1+r524742\x1b\\\x1b[?62;22c", want);
    assert!(queried, "the server asked the terminal");
    assert!(h.contains(want), "{h}");
}

#[test]
fn a_terminal_answering_only_da1_through_openssh_keeps_256() {
    if !ssh_available() {
        eprintln!("skip: OpenSSH `ssh` is not installed (apt-get install openssh-client)");
        return;
    }
    let (h, queried) = header_via_openssh(&[], b"\x1b[?1;2c", "256 (TERM)");
    assert!(queried);
    assert!(h.contains("| 256 (TERM) |"), "{h}");
}

#[test]
fn openssh_setenv_colorterm_gives_truecolor_without_asking() {
    if !ssh_available() {
        eprintln!("skip: OpenSSH `ssh` is not installed (apt-get install openssh-client)");
        return;
    }
    let want = "truecolor (COLORTERM)";
    let (h, queried) = header_via_openssh(&["-o", "SetEnv=COLORTERM=truecolor"], b"", want);
    assert!(h.contains(want), "{h}");
    assert!(!queried, "no query when COLORTERM came as an env request");
}
