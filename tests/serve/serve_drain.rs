//! `halfcast serve` stopped with SIGTERM (systemd's stop, restart and upgrade): it drains
//! instead of dropping its players. `/healthz` says 503 at once, the SSH port closes (a
//! balancer's retry lands on another world), the players keep playing until the drain ends,
//! then each is told "this world restarts: reconnect to continue" and the process exits.

use crate::serve_process::{free_port, spawn_server};
use crate::serve_support;

use std::process::Command;
use std::time::{Duration, Instant};

use serve_support::http::{get, series};
use serve_support::{header_has, Client, PATIENCE};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sigterm_drains_then_tells_players_to_reconnect() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mport = free_port();
    let (mut srv, port, log) = spawn_server(
        dir.path(),
        &[
            "--metrics",
            &mport.to_string(),
            "--db",
            "none",
            "--drain-seconds",
            "3",
        ],
    );
    let addr = format!("127.0.0.1:{port}").parse().unwrap();
    let mut ann = Client::connect(addr, "ann", 80, 24, "xterm-256color").await;
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    assert_eq!(get(mport, "/healthz").0, 200);

    let pid = srv.0.id().to_string();
    let sent = Instant::now();
    if Command::new("kill").args(["-TERM", &pid]).status().is_err() {
        eprintln!("SKIPPED: no `kill` command to send SIGTERM");
        return;
    }
    // Draining: the check fails at once, and the SSH port no longer takes connections.
    let deadline = Instant::now() + PATIENCE;
    while get(mport, "/healthz") != (503, "draining\n".to_owned()) {
        assert!(Instant::now() < deadline, "/healthz never said draining");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    assert_eq!(series(&get(mport, "/metrics").1, "halfcast_draining"), 1.0);
    while std::net::TcpStream::connect(addr).is_ok() {
        assert!(Instant::now() < deadline, "the SSH port stayed open");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    // Ann is told at once, over her status line, and plays on meanwhile: she turns, and her
    // view follows.
    assert!(
        ann.until(|s| s.contents().contains("this world restarts soon"))
            .await,
        "{}",
        ann.screen.screen().contents()
    );
    let before = ann.bytes;
    ann.keys(b"d").await;
    ann.drain_for(Duration::from_millis(500)).await;
    assert!(ann.bytes > before, "no frames while draining");
    assert!(
        srv.0.try_wait().unwrap().is_none(),
        "stopped before the drain ended"
    );

    // Then she is told what to do, and the process exits.
    assert!(
        ann.until(|s| s
            .contents()
            .contains("this world restarts: reconnect to continue"))
            .await,
        "{}",
        ann.screen.screen().contents()
    );
    let status = loop {
        if let Some(s) = srv.0.try_wait().unwrap() {
            break s;
        }
        assert!(Instant::now() < deadline, "the server never exited");
        std::thread::sleep(Duration::from_millis(20));
    };
    let took = sent.elapsed();
    assert!(status.success(), "{status:?}");
    assert!(
        took >= Duration::from_millis(2500) && took < Duration::from_secs(8),
        "a 3 s drain took {took:?}"
    );
    let lines: Vec<String> = log.try_iter().collect();
    assert!(lines.iter().any(|l| l.contains("draining")), "{lines:#?}");
}

#[test]
fn sigterm_with_nobody_playing_stops_at_once() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (mut srv, _port, _log) = spawn_server(dir.path(), &["--db", "none"]);
    let pid = srv.0.id().to_string();
    let sent = Instant::now();
    if Command::new("kill").args(["-TERM", &pid]).status().is_err() {
        eprintln!("SKIPPED: no `kill` command to send SIGTERM");
        return;
    }
    let status = loop {
        if let Some(s) = srv.0.try_wait().unwrap() {
            break s;
        }
        assert!(sent.elapsed() < PATIENCE, "the server never exited");
        std::thread::sleep(Duration::from_millis(20));
    };
    assert!(status.success(), "{status:?}");
    // The default drain is 30 s; with nobody there it is not waited out.
    assert!(
        sent.elapsed() < Duration::from_secs(3),
        "{:?}",
        sent.elapsed()
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_second_sigterm_while_draining_stops_at_once() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (mut srv, port, log) = spawn_server(dir.path(), &["--db", "none", "--drain-seconds", "60"]);
    let addr = format!("127.0.0.1:{port}").parse().unwrap();
    let mut ann = Client::connect(addr, "ann", 80, 24, "xterm-256color").await;
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    let pid = srv.0.id().to_string();
    let term = || Command::new("kill").args(["-TERM", &pid]).status().is_ok();
    if !term() {
        eprintln!("SKIPPED: no `kill` command to send SIGTERM");
        return;
    }
    let deadline = Instant::now() + PATIENCE;
    while !log.try_iter().any(|l| l.contains("draining")) {
        assert!(Instant::now() < deadline, "never drained");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let again = Instant::now();
    assert!(term());
    assert!(
        ann.until(|s| s
            .contents()
            .contains("this world restarts: reconnect to continue"))
            .await
    );
    while srv.0.try_wait().unwrap().is_none() {
        assert!(Instant::now() < deadline, "the server never exited");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    assert!(
        again.elapsed() < Duration::from_secs(5),
        "{:?}",
        again.elapsed()
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_round_that_ends_while_draining_ends_the_drain_after_its_results() {
    let (srv, _dir) = serve_support::server(|cfg| {
        cfg.round_limit = Some(Duration::from_millis(1500));
        cfg.results_time = Duration::from_millis(500);
    })
    .await;
    let mut ann = Client::connect(srv.local_addr(), "ann", 80, 24, "xterm-256color").await;
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    assert_eq!(srv.health(), halfcast::serve::health::Health::Accepting);
    let rounds = srv.rounds_finished();
    let started = Instant::now();
    // A drain that could last 30 s ends with the round (at most 1.5 s away) and its results.
    {
        let drain = srv.drain(Duration::from_secs(30));
        let reading = async {
            loop {
                ann.drain_for(Duration::from_millis(100)).await;
            }
        };
        tokio::select! {
            () = drain => {}
            () = reading => {}
        }
    }
    let took = started.elapsed();
    assert_eq!(srv.health(), halfcast::serve::health::Health::Draining);
    // (Rounds this short end again during the 5 s pause; the default results alone last 8 s.)
    assert!(srv.rounds_finished() > rounds);
    assert!(
        took >= Duration::from_secs(5) && took < Duration::from_secs(9),
        "the drain took {took:?}"
    );
    srv.shutdown_restarting().await;
    assert!(
        ann.until(|s| s
            .contents()
            .contains("this world restarts: reconnect to continue"))
            .await
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_drain_begun_while_the_results_show_ends_with_them_and_starts_no_round() {
    // Results that would show for 40 s, and a drain that could last 60 s.
    let (srv, _dir) = serve_support::server(|cfg| {
        cfg.round_limit = Some(Duration::from_millis(800));
        cfg.results_time = Duration::from_secs(40);
    })
    .await;
    let mut ann = Client::connect(srv.local_addr(), "ann", 80, 24, "xterm-256color").await;
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    assert!(ann.until(|s| s.contents().contains("next round in")).await);
    assert_eq!(srv.rounds_finished(), 1);
    let started = Instant::now();
    {
        let drain = srv.drain(Duration::from_secs(60));
        let reading = async {
            loop {
                ann.drain_for(Duration::from_millis(100)).await;
            }
        };
        tokio::select! {
            () = drain => {}
            () = reading => {}
        }
    }
    let took = started.elapsed();
    // At most the results' 5 s after the round's end, not the 40 s of results or a round more.
    assert!(took < Duration::from_secs(7), "the drain took {took:?}");
    assert_eq!(srv.rounds_finished(), 1, "a round ended while draining");
    srv.shutdown_restarting().await;
    assert!(
        ann.until(|s| s
            .contents()
            .contains("this world restarts: reconnect to continue in"))
            .await
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_draining_world_holds_the_results_instead_of_starting_the_next_round() {
    // Short results: undrained, the next round would start within half a second.
    let (srv, _dir) = serve_support::server(|cfg| {
        cfg.round_limit = Some(Duration::from_millis(800));
        cfg.results_time = Duration::from_millis(300);
    })
    .await;
    let mut ann = Client::connect(srv.local_addr(), "ann", 80, 24, "xterm-256color").await;
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    let drained = {
        let drain = srv.drain(Duration::from_secs(60));
        let reading = async {
            loop {
                ann.drain_for(Duration::from_millis(100)).await;
            }
        };
        tokio::select! {
            () = drain => srv.rounds_finished(),
            () = reading => unreachable!(),
        }
    };
    // The round in play ended the drain, and its results still show: no round was started
    // after it, though several would have fitted in the drain's 5 s.
    assert_eq!(drained, 1);
    assert!(ann.until(|s| s.contents().contains("next round in")).await);
    srv.shutdown_restarting().await;
}
