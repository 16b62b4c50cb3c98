//! OpenSSH's own `ssh` with `TERM=xterm-256color` (it does not forward `COLORTERM`): the server
//! asks the client's terminal for 24-bit colour over the channel, or takes `COLORTERM` from
//! `ssh -o SetEnv=…`. Skipped with a notice where `ssh` is not installed.

use crate::serve_support;

use std::io::Write;
use std::time::Instant;

use serve_support::openssh::{ssh_available, SshPty};
use serve_support::{header_has, row_text, server, PATIENCE};

/// The query's first bytes (XTGETTCAP `RGB`).
const QUERY_START: &[u8] = b"\x1bP+q524742\x1b\\";

/// Runs `ssh EXTRA… ann@server` in an 80×24 pty playing a terminal that answers the colour
/// query with `answer`; returns the header once it shows `want` (or what it showed instead),
/// and whether the query was seen.
fn header_via_openssh(extra: &[&str], answer: &[u8], want: &str) -> (String, bool) {
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    let (srv, _dir) = rt.block_on(server(|_| {}));
    let extra: Vec<&std::ffi::OsStr> = extra.iter().map(|a| a.as_ref()).collect();
    let SshPty {
        mut child,
        mut writer,
        rx,
        ..
    } = SshPty::spawn(srv.local_addr().port(), &extra, (80, 24));
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
