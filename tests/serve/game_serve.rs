//! The game over SSH, end to end: real russh clients on a loopback server playing a small
//! room (the first player spawns at the start, the second one cell east of it, both facing
//! east, with a treasure and then the exit ahead). Coop pools the points in both headers, tag
//! names who is "it" and passes it on a touch, the exit ends the round for everyone with the
//! results, and spectators see the scoreboard. The countdown between rounds is driven through
//! `Players` directly (it takes game seconds, not wall time).

use crate::serve_support;

use std::sync::Arc;
use std::time::Duration;

use halfcast::game::multi::players::Players;
use halfcast::game::multi::round::{Mode, RESULTS_SECONDS};
use halfcast::game::{Action, Held, Input};
use halfcast::serve::{start, RunningServer, ServeConfig};
use halfcast::World;
use serve_support::{header_has, Client};
use tempfile::TempDir;

const ROOM: &str = "tests/fixtures/game_serve_room.cub";
const COLS: u16 = 120;
const ROWS: u16 = 40;

fn room() -> World {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(ROOM);
    World::from_file(&path, true).expect("the room loads").0
}

async fn serve(mode: Mode) -> (RunningServer, TempDir) {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut cfg = ServeConfig::local("127.0.0.1:0".parse().unwrap(), dir.path().join("hk"));
    cfg.quiet = true;
    cfg.mode = mode;
    (start(cfg, room()).await.expect("server starts"), dir)
}

async fn join(srv: &RunningServer, name: &str) -> Client {
    let mut c = Client::connect(srv.local_addr(), name, COLS, ROWS, "xterm-256color").await;
    let me = format!("you are {name}");
    assert!(
        c.until(|s| header_has(s, &me)).await,
        "{name} never saw the header:\n{}",
        c.screen.screen().contents()
    );
    c
}

/// Waits until `what` holds on `c`'s screen (fails the test with the screen otherwise).
async fn see(c: &mut Client, what: &str, ok: impl Fn(&vt100::Screen) -> bool) {
    assert!(
        c.until(|s| ok(s)).await,
        "gave up waiting for {what}; screen:\n{}",
        c.screen.screen().contents()
    );
}

/// Taps `w` on `c` until `ok` holds for its screen.
async fn walk_until(c: &mut Client, what: &str, ok: impl Fn(&vt100::Screen) -> bool) {
    for _ in 0..60 {
        if ok(c.screen.screen()) {
            return;
        }
        c.keys(b"w").await;
        c.drain_for(Duration::from_millis(100)).await;
    }
    see(c, what, ok).await;
}

fn text(c: &Client) -> String {
    c.screen.screen().contents()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn coop_pools_a_treasure_in_both_headers_and_the_exit_ends_the_round_for_both() {
    let (srv, _dir) = serve(Mode::Coop).await;
    let mut ann = join(&srv, "ann").await;
    let mut bob = join(&srv, "bob").await;
    see(&mut ann, "the coop scoreboard", |s| {
        header_has(s, "team 0 pts") && header_has(s, "bob")
    })
    .await;
    // A spectator sees the same scoreboard.
    let mut watcher =
        Client::connect(srv.local_addr(), "watch", COLS, ROWS, "xterm-256color").await;
    see(&mut watcher, "the scoreboard as a spectator", |s| {
        header_has(s, "team 0 pts") && header_has(s, "ann") && header_has(s, "bob")
    })
    .await;
    // Bob, one cell nearer the treasure, walks over it: the team has 10 points on both screens.
    walk_until(&mut bob, "bob's treasure", |s| header_has(s, "team 10 pts")).await;
    see(&mut ann, "the team's 10 points on ann's screen", |s| {
        header_has(s, "team 10 pts")
    })
    .await;
    see(
        &mut watcher,
        "the team's 10 points for the spectator",
        |s| header_has(s, "team 10 pts"),
    )
    .await;
    // On to the exit: the round ends for everyone, with the results and the countdown.
    walk_until(&mut bob, "the results on bob's screen", |s| {
        s.contents().contains("next round in")
    })
    .await;
    see(&mut ann, "the results on ann's screen", |s| {
        let t = s.contents();
        t.contains("Level complete!")
            && t.contains("bob reached the exit")
            && t.contains("next round in")
            && t.contains("1 of 1")
    })
    .await;
    let t = text(&ann);
    assert!(t.contains("10"), "{t}");
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn tag_names_who_is_it_and_a_touch_passes_it_on() {
    let (srv, _dir) = serve(Mode::Tag).await;
    let mut ann = join(&srv, "ann").await;
    see(&mut ann, "ann is it", |s| header_has(s, "it is ann")).await;
    let mut bob = join(&srv, "bob").await;
    see(&mut bob, "bob's header naming ann", |s| {
        header_has(s, "it is ann")
    })
    .await;
    // The grace after "it" changes hands ends; then ann (facing east, bob right ahead) walks
    // into bob and "it" passes to him.
    ann.drain_for(Duration::from_millis(2200)).await;
    walk_until(&mut ann, "it passing to bob", |s| {
        header_has(s, "it is bob")
    })
    .await;
    see(&mut bob, "bob's header naming bob", |s| {
        header_has(s, "it is bob")
    })
    .await;
    // Ann sees bob's avatar right ahead of her, tagged as "it".
    see(&mut ann, "bob's name tag with (it)", |s| {
        s.contents().contains("bob (it)")
    })
    .await;
    srv.shutdown().await;
}

/// Holds forward for `player` in `ps` and ticks at 30 Hz until `done` (at most 20 game s).
fn walk(ps: &mut Players, player: u64, done: impl Fn(&mut Players) -> bool) {
    let forward = Input {
        held: [Action::Forward].into_iter().collect::<Held>(),
        commands: vec![],
    };
    for _ in 0..600 {
        ps.input(player, forward.clone(), 80);
        ps.tick(1.0 / 30.0);
        if done(ps) {
            return;
        }
    }
    panic!("never happened in 20 game seconds");
}

#[test]
fn the_next_round_starts_after_the_results_with_the_scoreboard_reset() {
    let mut ps = Players::with_mode(Arc::new(room()), Mode::Coop, 5);
    ps.join(1, "ann");
    ps.join(2, "bob");
    assert!(ps.snapshot().scoreboard.summary.contains("team 0 pts"));
    // Bob walks over the treasure and on to the exit.
    walk(&mut ps, 2, |ps| ps.snapshot().ended.is_some());
    let snap = ps.snapshot();
    let end = snap.ended.clone().expect("the round ended");
    assert_eq!(end.by.as_deref(), Some("bob"));
    assert_eq!((end.points, end.treasures), (10, (1, 1)));
    assert!(
        snap.scoreboard.summary.contains("team 10 pts"),
        "{}",
        snap.scoreboard
    );
    // The results stay for RESULTS_SECONDS of game time, the world waiting.
    let ticks = (RESULTS_SECONDS * 30.0) as usize;
    for _ in 0..ticks - 3 {
        ps.tick(1.0 / 30.0);
    }
    let snap = ps.snapshot();
    assert!(snap.ended.is_some(), "the results went too early");
    assert!(snap.ended.as_ref().unwrap().left > 0.0);
    for _ in 0..6 {
        ps.tick(1.0 / 30.0);
    }
    // A new round: no results, the team's points back to 0, the treasure back, everyone
    // respawned away from the exit.
    let snap = ps.snapshot();
    assert!(snap.ended.is_none(), "no new round after the results");
    assert!(
        snap.scoreboard.summary.contains("team 0 pts"),
        "{}",
        snap.scoreboard
    );
    assert!(
        snap.scoreboard.summary.contains("1 item left"),
        "{}",
        snap.scoreboard
    );
    assert_eq!(snap.level.finished(), None);
    let bob = snap.player(2).expect("bob is still here");
    assert!(bob.state.camera.pos.x < 3.0, "{:?}", bob.state.camera.pos);
    assert_eq!(bob.state.score.points, 0);
}

/// At 80 columns (the size most people have) the header keeps the whole coop scoreboard for
/// four players by dropping the key hint, the program's name and the colour level first; the
/// row stays one line, and narrower the board's tail shortens to "+N more".
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn at_80_columns_the_header_keeps_the_scoreboard() {
    let (srv, _dir) = serve(Mode::Coop).await;
    let mut players = Vec::new();
    for name in ["ann", "bob", "cyd"] {
        players.push(join(&srv, name).await);
    }
    let mut small = Client::connect(srv.local_addr(), "eve", 80, 24, "xterm-256color").await;
    // The board: what follows the coop summary ("coop: team N pts, N items left | ...").
    let board = |s: &vt100::Screen| {
        let top = serve_support::row_text(s, 0);
        top.split_once("left | ")
            .map(|(_, b)| b.trim_end().to_owned())
    };
    see(&mut small, "the whole scoreboard at 80 columns", |s| {
        board(s).is_some_and(|b| ["ann", "bob", "cyd", "eve"].iter().all(|n| b.contains(n)))
    })
    .await;
    let top = serve_support::row_text(small.screen.screen(), 0);
    assert!(top.starts_with(" you are eve | coop: team "), "{top}");
    assert!(!top.contains("O colours") && !top.contains("more"), "{top}");
    small.resize(64, 20).await;
    see(&mut small, "a shortened scoreboard at 64 columns", |s| {
        board(s).is_some_and(|b| b.ends_with(" more"))
    })
    .await;
    let b = board(small.screen.screen()).expect("a board");
    let shown = b.split(", ").count() - 1;
    assert!(
        (1..4).contains(&shown) && b.ends_with(&format!("+{} more", 4 - shown)),
        "{b}"
    );
    drop(players);
    srv.shutdown().await;
}
