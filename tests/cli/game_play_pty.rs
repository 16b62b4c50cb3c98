//! End-to-end: the game in the real binary through a pseudo-terminal at 80×24 (a terminal
//! without the kitty keyboard protocol), read back through a VT100 parser: the start message
//! over the view, the HUD on the status line, a pickup, the minimap's objects in mono, and a
//! campaign going from one map's exit to the next.
#![cfg(unix)]

use crate::common;
use crate::pty_support;

use std::thread;
use std::time::{Duration, Instant};

use pty_support::{PtyRun, PATIENCE};

const SIZE: (u16, u16) = (80, 24);

fn status_line(s: &vt100::Screen) -> String {
    s.contents().lines().last().unwrap_or_default().to_owned()
}

/// The screen's first row (the top of the 3D view, where game messages show).
fn top_row(s: &vt100::Screen) -> String {
    s.rows(0, SIZE.0).next().unwrap_or_default()
}

/// Taps `w` until `done` holds for the screen (each tap walks a little way).
fn walk_until(run: &mut PtyRun, what: &str, done: impl Fn(&vt100::Screen) -> bool) {
    let start = Instant::now();
    loop {
        run.answer_probe();
        if done(run.screen()) {
            return;
        }
        assert!(
            start.elapsed() < PATIENCE,
            "gave up walking until {what}; screen:\n{}",
            run.screen().contents()
        );
        run.send(b"w");
        thread::sleep(Duration::from_millis(120));
    }
}

#[test]
fn level1_starts_with_its_message_and_hud_and_a_treasure_scores_ten() {
    let mut run = PtyRun::spawn(&["maps/level1.cub", "--seed", "1", "--fps", "30"], SIZE);
    run.wait_for_screen("the start message and the HUD", |sc| {
        top_row(sc).contains("Find the exit. 0/8 treasures.")
            && status_line(sc).contains("0 pts")
            && status_line(sc).contains("8 left")
    });
    walk_until(&mut run, "the first treasure", |sc| {
        top_row(sc).contains("Treasure! +10 points") && status_line(sc).contains("10 pts")
    });
    assert!(
        status_line(run.screen()).contains("7 left"),
        "{}",
        status_line(run.screen())
    );
    run.send(b"q");
    assert!(run.wait_exit().success());
}

/// The minimap pane's inside (between its top and bottom borders, right of the view) as text.
fn minimap_pane(text: &str) -> String {
    let map_row = text
        .lines()
        .position(|l| l.contains("+ map"))
        .expect("map pane");
    let map_col = text.lines().nth(map_row).unwrap().find("+ map").unwrap();
    text.lines()
        .skip(map_row + 1)
        .take_while(|l| !l[map_col..].starts_with('+'))
        .map(|l| format!("{}\n", &l[map_col..]))
        .collect()
}

#[test]
fn mono_shows_treasures_and_the_exit_on_the_minimap_in_plain_ascii() {
    // level1 at 80x24: everything ASCII, the start message over the view, treasures nearby.
    let mut run = PtyRun::spawn(
        &["maps/level1.cub", "--colors", "mono", "--seed", "1"],
        SIZE,
    );
    // The wait names the start message too: a read can end mid-frame (the panes and the
    // status line drawn, the view's rows not yet), so the HUD alone does not mean the view is there.
    run.wait_for_screen(
        "the first mono frame with the HUD and the start message",
        |sc| {
            status_line(sc).contains("0 pts")
                && sc.contents().contains("+ map")
                && top_row(sc).contains("Find the exit. 0/8 treasures.")
        },
    );
    let sc = run.screen().clone();
    let text = sc.contents();
    assert!(text.is_ascii(), "non-ASCII on a mono screen:\n{text}");
    assert!(minimap_pane(&text).contains('$'), "{text}");
    run.send(b"q");
    assert!(run.wait_exit().success());
    // A small map fits the pane whole: its treasure and its exit are both marked (facing
    // north, so the centre ray's trace does not cover the corridor).
    let mut run = PtyRun::spawn(
        &[
            "tests/fixtures/game_tiny_b.cub",
            "--colors",
            "mono",
            "--angle",
            "90",
        ],
        SIZE,
    );
    run.wait_for_screen("the tiny map in mono", |sc| {
        status_line(sc).contains("0 pts") && sc.contents().contains("+ map")
    });
    let text = run.screen().contents();
    assert!(text.is_ascii(), "non-ASCII on a mono screen:\n{text}");
    let pane = minimap_pane(&text);
    assert!(pane.contains('$'), "no treasure on the minimap:\n{pane}");
    assert!(pane.contains('E'), "no exit on the minimap:\n{pane}");
    run.send(b"q");
    assert!(run.wait_exit().success());
}

#[test]
fn a_campaign_shows_the_results_at_the_exit_and_enter_plays_the_next_map() {
    let (a, b) = (
        "tests/fixtures/game_tiny_a.cub",
        "tests/fixtures/game_tiny_b.cub",
    );
    let mut run = PtyRun::spawn(&[a, b, "--seed", "3"], SIZE);
    run.wait_for_screen("the first map's start message", |sc| {
        top_row(sc).contains("Find the exit. 0/1 treasures.")
    });
    walk_until(&mut run, "the first map's exit", |sc| {
        sc.contents().contains("Level complete!")
    });
    let text = run.screen().contents();
    for want in [
        "Points",
        "10",
        "Treasures",
        "1 of 1",
        "next level: game_tiny_b.cub",
        "Enter",
    ] {
        assert!(
            text.contains(want),
            "{want:?} missing from the results:\n{text}"
        );
    }
    // Let the emulated key hold of the last `w` run out, so it cannot walk the next map.
    thread::sleep(Duration::from_millis(1000));
    run.send(b"\r");
    run.wait_for_screen("the second map", |sc| {
        top_row(sc).contains("Find the exit. 0/2 treasures.")
            && !sc.contents().contains("Level complete!")
            && status_line(sc).contains("0 pts")
            && status_line(sc).contains("2 left")
    });
    // The campaign's last map leads back to itself.
    walk_until(&mut run, "the second map's exit", |sc| {
        sc.contents().contains("Level complete!")
    });
    let text = run.screen().contents();
    assert!(text.contains("2 of 2") && text.contains("35"), "{text}");
    assert!(text.contains("play this level again"), "{text}");
    // And Enter does that: the second map again, not the first.
    thread::sleep(Duration::from_millis(1000));
    run.send(b"\r");
    run.wait_for_screen("the second map again", |sc| {
        top_row(sc).contains("Find the exit. 0/2 treasures.")
            && !sc.contents().contains("Level complete!")
    });
    run.send(b"q");
    assert!(run.wait_exit().success());
}

#[test]
fn record_refuses_a_campaign() {
    let out = common::halfcast(&[
        "record",
        "-o",
        "/dev/null",
        "tests/fixtures/game_tiny_a.cub",
        "tests/fixtures/game_tiny_b.cub",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("record plays one map, got 2"), "{err}");
}
