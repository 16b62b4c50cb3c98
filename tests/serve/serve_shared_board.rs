//! One leaderboard for every world on a host: two servers on one SQLite file, each finishing
//! rounds as fast as the config lets them (0.3 s of play, 0.1 s of results), at once. Every
//! round either of them finished is in the file afterwards, and `halfcast scores` counts them
//! all.

use crate::serve_support;

use std::time::Duration;

use halfcast::serve::{RunningServer, ServeConfig};
use serve_support::{header_has, server_with, Client};

/// `tweak` for a world that records its quick rounds in `db`.
fn quick_rounds(db: std::path::PathBuf) -> impl FnOnce(&mut ServeConfig) {
    move |cfg| {
        cfg.db = Some(db);
        cfg.round_limit = Some(Duration::from_millis(300));
        cfg.results_time = Duration::from_millis(100);
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn two_worlds_on_one_sqlite_file_lose_no_round_and_scores_counts_them_all() {
    let dir = tempfile::tempdir().expect("tempdir");
    let db = dir.path().join("shared.sqlite");
    let world = serve_support::plain_default_world;
    let (a, _ka) = server_with(quick_rounds(db.clone()), world()).await;
    let (b, _kb) = server_with(quick_rounds(db.clone()), world()).await;
    // A player in each, so their rounds run.
    let mut players = Vec::new();
    for (srv, name) in [(&a, "ann"), (&b, "bob")] {
        let mut c = Client::connect(srv.local_addr(), name, 80, 24, "xterm-256color").await;
        assert!(c.until(|s| header_has(s, &format!("you are {name}"))).await);
        players.push(c);
    }
    let deadline = tokio::time::Instant::now() + Duration::from_secs(20);
    while a.rounds_finished() < 10 || b.rounds_finished() < 10 {
        assert!(
            tokio::time::Instant::now() < deadline,
            "rounds too slow: {} and {}",
            a.rounds_finished(),
            b.rounds_finished()
        );
        // Keep the clients' inboxes read.
        for c in &mut players {
            c.drain_for(Duration::from_millis(50)).await;
        }
    }
    // Without players no round runs: the counts settle.
    drop(players);
    let settled = |a: &RunningServer, b: &RunningServer| (a.rounds_finished(), b.rounds_finished());
    let mut counts = settled(&a, &b);
    loop {
        tokio::time::sleep(Duration::from_millis(800)).await;
        let now = settled(&a, &b);
        if now == counts {
            break;
        }
        assert!(
            tokio::time::Instant::now() < deadline,
            "rounds go on without players"
        );
        counts = now;
    }
    let (ra, rb) = counts;
    // Shutting down waits for each world's queued writes.
    a.shutdown().await;
    b.shutdown().await;

    let v = crate::scores_json::scores_json(&db);
    let maps = v["maps"].as_array().expect("maps");
    assert_eq!(maps.len(), 1, "one map, one board: {v:#}");
    let recorded = maps[0]["rounds"].as_u64().unwrap();
    // Rounds may end between the count and the shutdown; none is lost.
    assert!(
        recorded >= ra + rb,
        "{recorded} recorded of {ra} + {rb} finished"
    );
    let names: Vec<&str> = maps[0]["top"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["name"].as_str().unwrap())
        .collect();
    assert!(
        names.contains(&"ann") && names.contains(&"bob"),
        "{names:?}"
    );
}
