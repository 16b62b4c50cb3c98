//! A SQLite leaderboard on a full disk (SQLite's own limit on the file's pages stands in for
//! the disk, and a file where the queue's directory was for a queue that cannot be written
//! either): rounds wait in memory up to the bound, the next is dropped, and all those kept are
//! written once there is room again.

use super::*;
use crate::game::multi::round::PlayerResult;
use crate::serve::leaderboard::backlog::MEMORY_ONLY;

fn round(i: usize) -> RoundRecord {
    RoundRecord {
        uid: format!("full-{i}"),
        map_hash: "h".into(),
        map_name: "m.cub".into(),
        mode: "coop".into(),
        seconds: 1.0,
        cleared: false,
        ended_at: i as i64,
        players: (0..24)
            .map(|p| PlayerResult {
                name: format!("player-{p}"),
                points: 1,
                items: 0,
                it_seconds: 0.0,
                reached_exit: false,
            })
            .collect(),
    }
}

fn pragma(w: &Writer, sql: &str) -> i64 {
    let Some(Database::Sqlite(store)) = &w.db else {
        panic!("a SQLite leaderboard")
    };
    store
        .connection()
        .query_row(sql, [], |r| r.get(0))
        .expect("the pragma runs")
}

#[test]
fn on_a_full_disk_rounds_wait_in_memory_up_to_a_bound_and_are_written_when_room_returns() {
    let dir = tempfile::tempdir().unwrap();
    let queue_dir = dir.path().join("queue");
    let (queue, (found, _)) = DiskQueue::open(&queue_dir).unwrap();
    let mut w = Writer {
        target: Target {
            db: dir.path().join("lb.sqlite"),
            access: super::database::Access::default(),
            queue_dir: queue_dir.clone(),
            start_on_error: false,
        },
        db: None,
        served: Vec::new(),
        backlog: Backlog::new(queue, found),
        writes: Outage::new(),
        next_probe: Instant::now(),
        reads: Outage::new(),
        boards: watch::channel(Arc::new(Boards::default())).0,
        log: Log::new(true),
    };
    assert_eq!(w.connect(true), Ok(true));
    // The queue cannot be written (a file where its directory was), and the database may not
    // grow: rounds are written until a page runs out.
    std::fs::remove_dir_all(&queue_dir).unwrap();
    std::fs::write(&queue_dir, b"not a directory").unwrap();
    let pages = pragma(&w, "PRAGMA page_count");
    assert_eq!(
        pragma(&w, &format!("PRAGMA max_page_count = {pages}")),
        pages
    );
    let mut next = 0;
    while w.backlog.is_empty() {
        assert!(next < 10_000, "the database never filled");
        w.backlog.push(round(next), w.log);
        w.catch_up();
        next += 1;
    }
    let written = next - 1;
    assert!(w.writes.is_away());
    // Memory holds up to the bound; the round after it is dropped.
    while w.backlog.len() < MEMORY_ONLY {
        w.backlog.push(round(next), w.log);
        w.catch_up();
        next += 1;
    }
    w.backlog.push(round(next), w.log);
    assert_eq!(
        w.backlog.len(),
        MEMORY_ONLY,
        "the round past the bound is dropped"
    );
    // Room again: at the next try, every round kept is written, in order.
    assert_eq!(pragma(&w, "PRAGMA max_page_count = 1000000"), 1_000_000);
    std::thread::sleep(w.writes.until_next_try(Instant::now()));
    w.catch_up();
    assert!(w.backlog.is_empty() && !w.writes.is_away());
    let Some(Database::Sqlite(store)) = &mut w.db else {
        unreachable!()
    };
    let rounds = store.maps().unwrap()[0].3 as usize;
    assert_eq!(rounds, written + MEMORY_ONLY);
}
