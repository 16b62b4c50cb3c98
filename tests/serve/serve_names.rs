//! Over SSH, who is who: two people with the same user name get distinct names (`ada`,
//! `ada-2`) in everyone's header, and the server's shutdown summary counts sessions that were
//! still running when it stopped.

use crate::serve_support;

use std::process::Command;
use std::time::Duration;

use crate::serve_process::spawn_server;
use serve_support::{header_has, row_text, server, Client, PATIENCE};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn two_adas_become_ada_and_ada_2() {
    let (srv, _dir) = server(|_| {}).await;
    let addr = srv.local_addr();
    let mut first = Client::connect(addr, "ada", 100, 16, "xterm-256color").await;
    assert!(first.until(|s| header_has(s, "you are ada |")).await);
    let mut second = Client::connect(addr, "ada", 100, 16, "xterm-256color").await;
    assert!(
        second
            .until(|s| header_has(s, "you are ada-2 |") && header_has(s, "2 here: ada, ada-2"))
            .await,
        "{}",
        row_text(second.screen.screen(), 0)
    );
    assert!(
        first
            .until(|s| header_has(s, "you are ada |") && header_has(s, "2 here: ada, ada-2"))
            .await,
        "{}",
        row_text(first.screen.screen(), 0)
    );
    srv.shutdown().await;
}

#[test]
fn the_shutdown_summary_counts_sessions_still_running() {
    let dir = tempfile::tempdir().expect("tempdir");
    // No drain: SIGTERM stops the server while both sessions still play (serve_drain.rs has
    // the drain).
    let (mut server, port, rx) = spawn_server(dir.path(), &["--drain-seconds", "0"]);
    let wait_for = |needle: &str, seen: &mut Vec<String>| loop {
        match rx.recv_timeout(PATIENCE) {
            Ok(l) if l.contains(needle) => return l,
            Ok(l) => seen.push(l),
            Err(_) => panic!("no line with {needle:?}: {seen:?}"),
        }
    };
    let mut seen = Vec::new();
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    // The client stays connected (and playing) while the server is told to stop.
    let client = rt.block_on(async {
        let addr = format!("127.0.0.1:{port}").parse().expect("addr");
        let mut c = Client::connect(addr, "ann", 60, 16, "xterm-256color").await;
        assert!(c.until(|s| header_has(s, "you are ann")).await);
        // A second `ann` plays as `ann-2`, and the log says so (its login line named `ann`).
        let mut twin = Client::connect(addr, "ann", 60, 16, "xterm-256color").await;
        assert!(twin.until(|s| header_has(s, "you are ann-2")).await);
        c.drain_for(Duration::from_millis(300)).await;
        (c, twin)
    });
    let renamed = wait_for("was taken", &mut seen);
    assert!(
        renamed.contains(r#""ann" was taken: plays as "ann-2""#),
        "{renamed}"
    );
    let killed = Command::new("kill")
        .args(["-TERM", &server.0.id().to_string()])
        .status();
    if killed.is_err() {
        eprintln!("skip: no `kill` command to send SIGTERM");
        return;
    }
    let summary = wait_for("served ", &mut seen);
    let _ = server.0.wait();
    drop(client);
    // "served 2 connections (0 refused), N frames, M bytes"
    let frames: u64 = summary
        .split(", ")
        .find_map(|p| p.strip_suffix(" frames"))
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{summary}"));
    assert!(summary.contains("served 2 connections"), "{summary}");
    assert!(
        frames > 0,
        "the live session's frames are counted: {summary}"
    );
}
