//! OpenSSH's `ssh` against the server's limits: it is told why when refused, it gets in under a
//! pre-auth flood, and the server does not advertise `ping@openssh.com`. Skipped with a notice
//! where `ssh` is not installed.

use crate::serve_support;

use std::net::Ipv4Addr;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serve_support::openssh::ssh_available;
use serve_support::{header_has, server, tcp_from, Client};

/// Runs `ssh -vv … ann@127.0.0.1 true` against `port` in batch mode (no pty, no prompt), with
/// its debug log in `log`; returns the log text. Exec is refused by the server, so the command
/// never runs: what matters is how far the client got.
fn ssh_try(port: u16, log: &Path) -> String {
    let _ = std::fs::remove_file(log);
    let out = Command::new("ssh")
        .args(["-vv", "-F", "/dev/null", "-p", &port.to_string()])
        .args([
            "-o",
            "StrictHostKeyChecking=no",
            "-o",
            "UserKnownHostsFile=/dev/null",
        ])
        .args(["-o", "BatchMode=yes", "-o", "ConnectTimeout=5"])
        .arg("-E")
        .arg(log)
        .args(["ann@127.0.0.1", "true"])
        .stdin(Stdio::null())
        .output()
        .expect("run ssh");
    let mut text = std::fs::read_to_string(log).unwrap_or_default();
    text.push_str(&String::from_utf8_lossy(&out.stderr));
    text
}

#[test]
fn openssh_hears_why_it_is_refused_and_gets_in_under_a_flood() {
    if !ssh_available() {
        eprintln!("skip: OpenSSH `ssh` is not installed (apt-get install openssh-client)");
        return;
    }
    if !serve_support::many_loopback_addresses() {
        return;
    }
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    let (srv, dir) = rt.block_on(server(|c| {
        c.max_sessions = 1;
        c.login_grace = Duration::from_secs(2);
    }));
    let addr = srv.local_addr();
    let log = dir.path().join("ssh.log");

    // Not advertised: ping@openssh.com (the log lists the server's extensions).
    let text = ssh_try(addr.port(), &log);
    assert!(text.contains("Authenticated to"), "{text}");
    assert!(text.contains("kex_input_ext_info"), "{text}");
    assert!(!text.contains("ping@openssh.com"), "{text}");

    // Full: the one place is taken; ssh prints the server's reason.
    let mut player = rt.block_on(Client::connect(addr, "one", 40, 12, "xterm"));
    assert!(rt.block_on(player.until(|s| header_has(s, "you are one"))));
    let text = ssh_try(addr.port(), &log);
    assert!(
        text.contains("server full (1 players), try later"),
        "{text}"
    );
    drop(player);

    // Under a silent flood from 4 addresses, ssh logs in within the grace time.
    let flood = rt.block_on(async {
        let mut v = Vec::new();
        for a in 2..=5u8 {
            for _ in 0..8 {
                if let Ok(s) = tcp_from(Ipv4Addr::new(127, 0, 0, a), addr).await {
                    v.push(s);
                }
            }
        }
        v
    });
    let start = Instant::now();
    let mut tries = 0;
    let mut last;
    let got_in = loop {
        tries += 1;
        last = ssh_try(addr.port(), &log);
        if last.contains("Authenticated to") {
            break true;
        }
        if let Some(l) = last.lines().find(|l| l.contains("halfcast:")) {
            eprintln!("openssh refused before the version line, its log says: {l}");
        }
        if start.elapsed() > Duration::from_secs(8) {
            break false;
        }
        std::thread::sleep(Duration::from_millis(200));
    };
    eprintln!(
        "openssh under a 4x8 silent flood: logged in after {:.2} s ({tries} tries)",
        start.elapsed().as_secs_f64()
    );
    assert!(got_in, "{last}");
    drop(flood);
    rt.block_on(srv.shutdown());
}
