//! One leaderboard for worlds on several hosts: `--db postgres://…`, against a real PostgreSQL
//! server (`.ci/run` installs Debian's and starts it; the tests that need it print a skip notice
//! without one). Two worlds recording rounds at once into one database lose none and `halfcast
//! scores --db postgres://…` counts them all; a connection the server cuts mid-game costs no
//! frame and no round; a server that is not there at start-up is said, with its cause, and the
//! world starts anyway (`serve_pg_outage` has the whole outage).

use crate::serve_process::{free_port, spawn};
use crate::serve_support;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use halfcast::serve::{RunningServer, ServeConfig};
use serve_support::postgres::TestDatabase;
use serve_support::{header_has, server_with, Client, PATIENCE};

/// `tweak` for a world that records its quick rounds (0.3 s of play, 0.1 s of results) in `db`.
fn quick_rounds(db: &str) -> impl FnOnce(&mut ServeConfig) {
    let db = PathBuf::from(db);
    move |cfg| {
        cfg.db = Some(db);
        cfg.round_limit = Some(Duration::from_millis(300));
        cfg.results_time = Duration::from_millis(100);
    }
}

/// `halfcast scores --json --db URL`: the rounds recorded on its one map.
fn scored_rounds(url: &str) -> (u64, Vec<String>) {
    let v = crate::scores_json::scores_json(url);
    let maps = v["maps"].as_array().expect("maps");
    assert_eq!(maps.len(), 1, "one map, one board: {v:#}");
    let names = maps[0]["top"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["name"].as_str().unwrap().to_owned())
        .collect();
    (maps[0]["rounds"].as_u64().unwrap(), names)
}

/// Waits until nobody plays and the worlds' round counts stop moving; the counts.
async fn settled(worlds: &[&RunningServer]) -> Vec<u64> {
    let deadline = tokio::time::Instant::now() + PATIENCE;
    let counts = || {
        worlds
            .iter()
            .map(|w| w.rounds_finished())
            .collect::<Vec<_>>()
    };
    let mut last = counts();
    loop {
        tokio::time::sleep(Duration::from_millis(800)).await;
        let now = counts();
        if now == last {
            return now;
        }
        assert!(
            tokio::time::Instant::now() < deadline,
            "rounds go on without players"
        );
        last = now;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn two_worlds_on_one_postgres_database_lose_no_round_and_scores_counts_them_all() {
    let Some(db) = TestDatabase::create("two worlds on PostgreSQL") else {
        return;
    };
    let world = serve_support::plain_default_world;
    let (a, _ka) = server_with(quick_rounds(&db.url), world()).await;
    let (b, _kb) = server_with(quick_rounds(&db.url), world()).await;
    let mut players = Vec::new();
    for (srv, name) in [(&a, "ann"), (&b, "bob")] {
        let mut c = Client::connect(srv.local_addr(), name, 80, 24, "xterm-256color").await;
        assert!(c.until(|s| header_has(s, &format!("you are {name}"))).await);
        players.push(c);
    }
    let deadline = tokio::time::Instant::now() + Duration::from_secs(20);
    while a.rounds_finished() < 10 || b.rounds_finished() < 10 {
        assert!(tokio::time::Instant::now() < deadline, "rounds too slow");
        for c in &mut players {
            c.drain_for(Duration::from_millis(50)).await;
        }
    }
    drop(players);
    let counts = settled(&[&a, &b]).await;
    a.shutdown().await;
    b.shutdown().await;
    let (recorded, names) = scored_rounds(&db.url);
    assert_eq!(recorded, counts[0] + counts[1], "of {counts:?}");
    assert!(
        names.contains(&"ann".to_owned()) && names.contains(&"bob".to_owned()),
        "{names:?}"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_connection_cut_mid_game_costs_no_frame_and_no_round() {
    let Some(db) = TestDatabase::create("PostgreSQL cut mid-game") else {
        return;
    };
    let (w, _k) = server_with(quick_rounds(&db.url), serve_support::plain_default_world()).await;
    let mut ann = Client::connect(w.local_addr(), "ann", 80, 24, "xterm-256color").await;
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    let wait_rounds = |n: u64| {
        let deadline = Instant::now() + PATIENCE;
        move |w: &RunningServer| {
            assert!(Instant::now() < deadline, "rounds too slow");
            w.rounds_finished() >= n
        }
    };
    let until = wait_rounds(3);
    while !until(&w) {
        ann.drain_for(Duration::from_millis(50)).await;
    }
    // The database server cuts the world's connection (as a restart of it would).
    let cut = db.execute(
        "SELECT pg_terminate_backend(pid) FROM pg_stat_activity
         WHERE datname = current_database() AND pid <> pg_backend_pid()",
    );
    assert!(cut >= 1, "the world's connection was there to cut");
    // Play goes on: frames keep coming while rounds end and are written again.
    let before = ann.bytes;
    let until = wait_rounds(w.rounds_finished() + 3);
    while !until(&w) {
        ann.keys(b"d").await;
        ann.drain_for(Duration::from_millis(50)).await;
    }
    assert!(ann.bytes > before, "no frames after the cut");
    drop(ann);
    let counts = settled(&[&w]).await;
    w.shutdown().await;
    assert_eq!(
        scored_rounds(&db.url).0,
        counts[0],
        "a round was lost to the cut"
    );
}

#[test]
fn a_database_not_there_at_start_up_is_said_with_its_cause_and_the_world_starts_anyway() {
    let dir = tempfile::tempdir().expect("tempdir");
    // Nothing listens on this port; the password comes from the environment.
    let url = format!("postgres://ann@127.0.0.1:{}/halfcast", free_port());
    let (mut srv, log) = spawn(
        free_port(),
        &dir.path().join("hk"),
        &["--db", &url, "--log-format", "json"],
        &[("PGPASSWORD", "s3cret")],
    );
    let deadline = Instant::now() + PATIENCE;
    let mut said = Vec::new();
    while !said.iter().any(|l: &String| l.contains("listening on")) {
        assert!(
            Instant::now() < deadline,
            "the world did not start: {said:#?}"
        );
        assert!(srv.0.try_wait().unwrap().is_none(), "it exited: {said:#?}");
        said.extend(log.recv_timeout(Duration::from_millis(50)));
    }
    let said = said.join("\n");
    assert!(
        said.contains("leaderboard postgres://ann@127.0.0.1:")
            && said.contains("is away")
            && said.contains("onnection refused"),
        "{said}"
    );
    assert!(!said.contains("s3cret"), "{said}");
}
