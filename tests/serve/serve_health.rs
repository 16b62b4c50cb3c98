//! `/healthz` on the `--metrics` address, as a load balancer's health check uses it: 200 while
//! the world takes players, 503 when it is full; the checks are neither players in the log nor
//! connections in `halfcast_connections_total`, but have a counter of their own. And the
//! operator's series beside them: the build and the process's own figures.

use crate::serve_process::{free_port, spawn_server};
use crate::serve_support;

use std::time::Instant;

use serve_support::http::{get, series};
use serve_support::{header_has, Client, PATIENCE};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn healthz_says_accepting_then_full_and_its_checks_are_not_players() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mport = free_port();
    let (_srv, port, log) = spawn_server(
        dir.path(),
        &[
            "--metrics",
            &mport.to_string(),
            "--max-sessions",
            "1",
            "--db",
            "none",
            "--threads",
            "2",
        ],
    );
    for _ in 0..5 {
        assert_eq!(get(mport, "/healthz"), (200, "accepting\n".to_owned()));
    }
    assert_eq!(get(mport, "/nothing-here").0, 404);
    let (status, m) = get(mport, "/metrics");
    assert_eq!(status, 200);
    assert_eq!(series(&m, "halfcast_connections_total"), 0.0, "{m}");
    assert_eq!(
        series(&m, r#"halfcast_health_checks_total{answer="accepting"}"#),
        5.0,
        "{m}"
    );
    // The world says which build it runs (the release and the commit), and how the process
    // fares.
    let commit = env!("HALFCAST_COMMIT");
    let version = format!(
        r#"halfcast_build_info{{version="{}",commit="{commit}"}}"#,
        env!("CARGO_PKG_VERSION")
    );
    assert_eq!(series(&m, &version), 1.0, "{m}");
    let head = std::process::Command::new("git")
        .args(["-C", env!("CARGO_MANIFEST_DIR"), "rev-parse", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success());
    match head {
        // A checkout: the commit it was built from.
        Some(o)
            if std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join(".git")
                .exists() =>
        {
            assert_eq!(commit, String::from_utf8_lossy(&o.stdout).trim());
        }
        // A package without its history.
        _ => assert_eq!(commit, "unknown"),
    }
    // Every labelled series is there from the start, at 0: a first refusal or failed write is
    // an increase from 0, not a series appearing.
    for zero in [
        r#"halfcast_refusals_total{reason="full"} 0"#,
        r#"halfcast_refusals_total{reason="proxy"} 0"#,
        r#"halfcast_leaderboard_writes_total{result="error"} 0"#,
        r#"halfcast_leaderboard_writes_total{result="dropped"} 0"#,
        r#"halfcast_rounds_total{mode="tag"} 0"#,
        r#"halfcast_link_level_steps_total{direction="down"} 0"#,
        r#"halfcast_health_checks_total{answer="draining"} 0"#,
        "halfcast_leaderboard_pending_rounds 0",
    ] {
        assert!(m.lines().any(|l| l == zero), "no {zero}: {m}");
    }
    assert!(series(&m, "process_resident_memory_bytes") > 1e6, "{m}");
    assert!(series(&m, "process_open_fds") >= 3.0, "{m}");
    assert!(series(&m, "process_max_fds") >= series(&m, "process_open_fds"));
    assert!(series(&m, "process_cpu_seconds_total") > 0.0, "{m}");
    // Its workers and at most 6 more (main, leaderboard, blocking pool): what the unit's
    // TasksMax is sized from.
    let threads = series(&m, "process_threads");
    assert!(
        (3.0..=8.0).contains(&threads),
        "{threads} threads with --threads 2"
    );
    assert_eq!(series(&m, "halfcast_draining"), 0.0, "{m}");

    // The one session place taken: a balancer should send players elsewhere.
    let addr = format!("127.0.0.1:{port}").parse().unwrap();
    let mut ann = Client::connect(addr, "ann", 80, 24, "xterm-256color").await;
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    let deadline = Instant::now() + PATIENCE;
    while get(mport, "/healthz") != (503, "full\n".to_owned()) {
        assert!(Instant::now() < deadline, "never full");
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    }
    let (_, m) = get(mport, "/metrics");
    assert_eq!(series(&m, "halfcast_connections_total"), 1.0, "{m}");
    assert!(
        series(&m, r#"halfcast_health_checks_total{answer="full"}"#) >= 1.0,
        "{m}"
    );
    // Only ann's connection is in the log: none of the checks is.
    let lines: Vec<String> = log.try_iter().collect();
    let connects: Vec<&String> = lines
        .iter()
        .filter(|l| l.ends_with("] connected"))
        .collect();
    assert_eq!(connects.len(), 1, "{lines:#?}");
    assert!(connects[0].contains("[session 1 127.0.0.1:"), "{lines:#?}");
}
