//! End-to-end snapshots of the real TUI: `halfcast replay` of the shipped recording on screen in
//! a pseudo-terminal, its last screen read back through vt100 and pinned as cells text (glyphs
//! and colours). Cut points: the first screen, after walking and turning, and with the debugger
//! paused and stepped. Update after an intended change: `INSTA_UPDATE=always cargo test --test
//! replay_pty` (then review the `.snap` diffs).
#![cfg(unix)]

use crate::common;
use crate::pty_support;

use halfcast::snapshot::cells_text;
use halfcast::termframe::{self, TermFrame};
use pty_support::{final_screen, replay_on_screen, replay_size};

const FIXTURE: &str = "tests/fixtures/walk_turn_debug.hcr";

/// The text of row `y` (glyphs only), for checking a snapshot shows what its name says.
fn row_text(frame: &TermFrame, y: usize) -> String {
    (0..frame.cols)
        .map(|x| frame.cell(x, y).glyph.as_str())
        .collect()
}

fn all_text(frame: &TermFrame) -> String {
    (0..frame.rows).map(|y| row_text(frame, y) + "\n").collect()
}

fn status(frame: &TermFrame) -> String {
    row_text(frame, frame.rows - 1)
}

/// Frame `n` as the headless replay draws it (`--format cells`).
fn headless(n: usize) -> TermFrame {
    let dir = tempfile::tempdir().unwrap();
    let out = common::halfcast(&[
        "replay",
        FIXTURE,
        "--frames",
        &n.to_string(),
        "--format",
        "cells",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    termframe::load(&dir.path().join(format!("frame-{n:05}.cells.txt")))
        .unwrap()
        .0
}

fn assert_same_look(want: &TermFrame, seen: &TermFrame) {
    let report = termframe::diff(want, seen);
    assert!(report.is_equal(), "{}", report.summary());
}

/// The value after `label ` on the status line (e.g. `pos`, `angle`).
fn status_field(frame: &TermFrame, label: &str) -> String {
    let st = status(frame);
    st.split(&format!("{label} "))
        .nth(1)
        .and_then(|r| r.split_whitespace().next())
        .unwrap_or_default()
        .to_owned()
}

#[test]
fn first_screen() {
    let screen = replay_on_screen(FIXTURE, Some(0));
    let text = all_text(&screen);
    assert!(
        text.contains("sideDistY") && text.contains("hit (15,0)"),
        "{text}"
    );
    assert!(status(&screen).contains("q quit"), "{text}");
    assert_eq!(status_field(&screen, "angle"), "90.0°");
    insta::assert_snapshot!(cells_text(screen));
}

#[test]
fn after_walking_and_turning() {
    let first = replay_on_screen(FIXTURE, Some(0));
    let screen = replay_on_screen(FIXTURE, Some(19));
    for field in ["pos", "angle"] {
        assert_ne!(
            status_field(&screen, field),
            status_field(&first, field),
            "{}",
            status(&screen)
        );
    }
    insta::assert_snapshot!(cells_text(screen));
}

#[test]
fn debugger_paused_and_stepped() {
    let screen = replay_on_screen(FIXTURE, Some(23));
    let text = all_text(&screen);
    assert!(
        status(&screen).to_lowercase().contains("paused"),
        "{}",
        status(&screen)
    );
    insta::assert_snapshot!(cells_text(screen));
    // Two more steps later (after moving the traced column), the pane shows a different trace.
    let later = replay_on_screen(FIXTURE, Some(26));
    assert_ne!(all_text(&later), text);
}

/// The live terminal shows exactly what the headless replay draws for the same frame.
#[test]
fn the_live_screen_is_the_headless_frame() {
    for n in [0, 23] {
        assert_same_look(&headless(n), &replay_on_screen(FIXTURE, Some(n)));
    }
}

/// `--format cast` played through a terminal model ends on the live run's final screen.
#[test]
fn the_asciicast_ends_on_the_live_screen() {
    let text = common::replay_cast(FIXTURE, &[]);
    let mut lines = text.lines();
    let header: serde_json::Value = serde_json::from_str(lines.next().unwrap()).unwrap();
    let size = replay_size(&common::root().join(FIXTURE));
    assert_eq!(
        (header["width"].as_u64(), header["height"].as_u64()),
        (Some(u64::from(size.0)), Some(u64::from(size.1)))
    );
    let mut bytes = Vec::new();
    for line in lines {
        let event: (f64, String, String) = serde_json::from_str(line).unwrap();
        assert_eq!(event.1, "o");
        bytes.extend_from_slice(event.2.as_bytes());
    }
    let from_cast = final_screen(&bytes, size);
    let live = replay_on_screen(FIXTURE, None);
    assert_eq!(cells_text(from_cast), cells_text(live));
}
