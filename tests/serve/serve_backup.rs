//! `halfcast scores --backup FILE`: a copy of a leaderboard that a world is still writing (its
//! last rounds only in the WAL, not yet in the main file), made without the `sqlite3` program;
//! `halfcast scores` reads the same boards from the copy, and its seconds are rounded.

use std::path::Path;
use std::process::{Command, Output};

use halfcast::game::multi::round::PlayerResult;
use halfcast::serve::leaderboard::store::Store;
use halfcast::serve::leaderboard::RoundRecord;

fn halfcast(args: &[&str], db: &Path) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(args)
        .arg("--db")
        .arg(db)
        .output()
        .expect("halfcast runs");
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn round(i: u32) -> RoundRecord {
    RoundRecord {
        uid: format!("backup-test-{i}"),
        map_hash: "00000000000000aa".into(),
        map_name: "maps/a.cub".into(),
        mode: "coop".into(),
        // What summed ticks make of 30 s.
        seconds: 30.000_000_000_000_65 + f64::from(i),
        cleared: true,
        ended_at: 1_764_680_000 + i64::from(i),
        players: vec![PlayerResult {
            name: format!("p{i}"),
            points: i64::from(i),
            items: 1,
            it_seconds: 0.0,
            reached_exit: true,
        }],
    }
}

#[test]
fn a_backup_of_a_leaderboard_being_written_holds_every_round_and_reads_the_same() {
    let dir = tempfile::tempdir().expect("tempdir");
    let db = dir.path().join("halfcast.sqlite");
    // A world's connection, open and writing, as a running server's is.
    let mut world = Store::open(&db).expect("opens");
    for i in 0..25 {
        world.record(&round(i)).expect("records");
    }
    assert!(
        dir.path().join("halfcast.sqlite-wal").exists(),
        "rounds waiting in the WAL"
    );
    let copy = dir.path().join("copy.sqlite");
    let said = halfcast(&["scores", "--backup", copy.to_str().unwrap()], &db);
    let said = String::from_utf8_lossy(&said.stdout);
    assert!(
        said.contains("backed up to") && said.contains(": 25 rounds"),
        "{said}"
    );
    // One self-contained file: no WAL beside it, nothing half-written left.
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("copy") || n.starts_with(".copy"))
        .collect();
    assert_eq!(names, ["copy.sqlite"]);

    let live = halfcast(&["scores", "--json"], &db).stdout;
    let copied = halfcast(&["scores", "--json"], &copy).stdout;
    assert_eq!(
        String::from_utf8_lossy(&live),
        String::from_utf8_lossy(&copied)
    );
    let v: serde_json::Value = serde_json::from_slice(&copied).unwrap();
    assert_eq!(v["maps"][0]["rounds"], 25);
    assert_eq!(v["maps"][0]["top"][0]["seconds"].to_string(), "30.0");

    // The world writes on; tomorrow's backup replaces today's.
    world.record(&round(25)).expect("records");
    let said = halfcast(&["scores", "--backup", copy.to_str().unwrap()], &db);
    assert!(String::from_utf8_lossy(&said.stdout).contains(": 26 rounds"));
}
