//! A server as game servers are run: maps in rotation (one per round, the results naming the
//! next; every map checked before the server listens), and a leaderboard in SQLite that the
//! next round's results show, that `halfcast scores --json` reads after a restart, and that
//! refuses a damaged file at start-up without touching it. Rounds are made short through the config (1 s of play, 0.8 s of results).

use crate::serve_support;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use halfcast::serve::{start_maps, RunningServer, ServeConfig, ServedMap};
use serve_support::{header_has, Client};
use tempfile::TempDir;

const COLS: u16 = 110;
const ROWS: u16 = 50;

/// Writes the game test room as `names` (distinct contents: each has its own content hash)
/// with the textures it needs, in a temporary tree.
fn maps(names: &[&str]) -> (TempDir, Vec<PathBuf>) {
    let dir = tempfile::tempdir().expect("tempdir");
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    for t in ["bricks.png", "stone.png", "sprites/treasure.png"] {
        let to = dir.path().join("textures").join(t);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        std::fs::copy(repo.join("textures").join(t), &to).unwrap();
    }
    let room = std::fs::read_to_string(repo.join("tests/fixtures/game_serve_room.cub")).unwrap();
    let at = dir.path().join("maps/rotation");
    std::fs::create_dir_all(&at).unwrap();
    let paths = names
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let p = at.join(n);
            // A floor shade of its own makes each file's bytes (and so its board) its own.
            let text = room.replace("F 96,88,80", &format!("F 96,88,{}", 80 + i));
            std::fs::write(&p, text).unwrap();
            p
        })
        .collect();
    (dir, paths)
}

fn config(dir: &Path, db: Option<PathBuf>) -> ServeConfig {
    let mut cfg = ServeConfig::local("127.0.0.1:0".parse().unwrap(), dir.join("hk"));
    cfg.quiet = true;
    cfg.round_limit = Some(Duration::from_millis(1000));
    cfg.results_time = Duration::from_millis(800);
    cfg.db = db;
    cfg
}

async fn serve(cfg: ServeConfig, paths: &[PathBuf]) -> RunningServer {
    let maps = paths
        .iter()
        .map(|p| ServedMap::from_file(p, true).expect("map loads").0)
        .collect();
    start_maps(cfg, maps).await.expect("server starts")
}

async fn see(c: &mut Client, what: &str, ok: impl Fn(&str) -> bool) {
    assert!(
        c.until(|s| ok(&s.contents())).await,
        "gave up waiting for {what}; screen:\n{}",
        c.screen.screen().contents()
    );
}

async fn join(srv: &RunningServer, name: &str) -> Client {
    let mut c = Client::connect(srv.local_addr(), name, COLS, ROWS, "xterm-256color").await;
    let me = format!("you are {name}");
    assert!(c.until(|s| header_has(s, &me)).await, "{name} never joined");
    c
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn three_maps_rotate_over_three_rounds_and_each_results_screen_names_the_next() {
    let (tree, paths) = maps(&["a.cub", "b.cub", "c.cub"]);
    let srv = serve(config(tree.path(), None), &paths).await;
    let mut ann = join(&srv, "ann").await;
    for (now, next) in [("a.cub", "b.cub"), ("b.cub", "c.cub"), ("c.cub", "a.cub")] {
        let on = format!("on {next}");
        see(
            &mut ann,
            &format!("the results of {now} naming {next}"),
            |t| {
                t.contains("Time is up!")
                    && t.contains("next round in")
                    && t.contains(&on)
                    && t.contains(now)
            },
        )
        .await;
        // Then the next round starts (the results go) before the next results come.
        see(&mut ann, "the next round", |t| !t.contains("next round in")).await;
    }
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn results_land_in_the_database_show_next_round_and_scores_json_reads_them_after_a_restart() {
    let (tree, paths) = maps(&["one.cub"]);
    let db = tree.path().join("lb.sqlite");
    let srv = serve(config(tree.path(), Some(db.clone())), &paths).await;
    let mut ann = join(&srv, "ann").await;
    // The first round's results, then the second's: by then round 1 is on the board.
    see(&mut ann, "the first results", |t| {
        t.contains("next round in")
    })
    .await;
    see(&mut ann, "the second round", |t| {
        !t.contains("next round in")
    })
    .await;
    see(&mut ann, "ann on the board of the second results", |t| {
        t.contains("next round in")
            && t.contains("All-time top 10")
            && t.contains(" 1. ann")
            && t.contains("your best")
    })
    .await;
    drop(ann);
    srv.shutdown().await;

    // A restart opens the same file (its boards load at start) and keeps serving.
    let srv = serve(config(tree.path(), Some(db.clone())), &paths).await;
    let v = crate::scores_json::scores_json(&db);
    assert_eq!(v["schema"], 3);
    let maps = v["maps"].as_array().expect("maps");
    assert_eq!(maps.len(), 1, "{v}");
    let m = &maps[0];
    assert_eq!(m["mode"], "coop");
    assert!(m["name"].as_str().unwrap().ends_with("one.cub"), "{m}");
    assert!(m["rounds"].as_u64().unwrap() >= 2, "{m}");
    assert_eq!(m["hash"].as_str().unwrap().len(), 16);
    let top = &m["top"][0];
    assert_eq!(top["rank"], 1);
    assert_eq!(top["name"], "ann");
    assert_eq!(top["points"], 0);
    assert_eq!(top["cleared"], false);
    assert!(top["seconds"].as_f64().unwrap() >= 1.0);

    // --map picks the board by the file's content; text names escape and align.
    let out = Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(["scores", "--db"])
        .arg(&db)
        .arg("--map")
        .arg(&paths[0])
        .output()
        .expect("halfcast scores runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("   1. ann"), "{text}");
    assert!(text.contains("0 pts"), "{text}");
    srv.shutdown().await;
}

/// `halfcast serve ARGS --listen 127.0.0.1:0 --host-key KEY`, run from the repository with no
/// stdin, which must refuse to start (exit code 2): its standard error.
fn serve_refused(args: &[&str], host_key: &Path) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .arg("serve")
        .args(args)
        .args(["--listen", "127.0.0.1:0", "--host-key"])
        .arg(host_key)
        .stdin(std::process::Stdio::null())
        .output()
        .expect("halfcast serve runs");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{err}");
    err
}

#[test]
fn a_damaged_database_stops_the_start_with_a_clear_error_and_is_left_as_it_was() {
    let dir = tempfile::tempdir().expect("tempdir");
    let db = dir.path().join("halfcast.sqlite");
    let junk: Vec<u8> = (0..4096u32).map(|i| (i * 7 + 3) as u8).collect();
    std::fs::write(&db, &junk).unwrap();
    let err = serve_refused(&[], &dir.path().join("hk"));
    let want = format!(
        "error: leaderboard {}: cannot read: file is not a database",
        db.display()
    );
    assert!(err.contains(&want), "{err}");
    assert!(!err.contains("listening on"), "{err}");
    assert!(std::fs::read(&db).unwrap() == junk, "the file was changed");
    // Nothing else appeared beside it either (no journal left behind).
    assert!(!dir.path().join("halfcast.sqlite-journal").exists());
}

#[test]
fn every_map_is_checked_before_listening_and_every_bad_one_named_at_file_line_col() {
    let dir = tempfile::tempdir().expect("tempdir");
    let err = serve_refused(
        &[
            "tests/fixtures/game_serve_room.cub",
            "tests/fixtures/invalid_serve_rotation.cub",
            "tests/fixtures/no_such_map.cub",
        ],
        &dir.path().join("hk"),
    );
    assert_eq!(
        err,
        "error: tests/fixtures/invalid_serve_rotation.cub:7:1: unknown identifier 'Q'\n\
         error: tests/fixtures/no_such_map.cub: cannot read the file: No such file or directory \
         (os error 2)\n"
    );
    // Nothing was started: no host key, no leaderboard.
    assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
}
