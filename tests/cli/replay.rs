//! `halfcast replay`: frames written per file, byte-identical runs, diffs that notice a changed
//! key, a valid asciicast whose final screen matches the replayed frame, and clear errors.

use crate::common;

use common::{halfcast, replay_cast, root};
use halfcast::termframe::{self, from_screen};

const FIXTURE: &str = "tests/fixtures/walk_turn_debug.hcr";

fn replay_frames(file: &str, frames: &str, format: &str, out: &std::path::Path) {
    let o = halfcast(&[
        "replay",
        file,
        "--frames",
        frames,
        "--format",
        format,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn the_shipped_replay_has_at_least_20_frames_and_uses_the_debugger() {
    let text = std::fs::read_to_string(root().join(FIXTURE)).unwrap();
    let r = halfcast::replay::Replay::parse(FIXTURE, &text).unwrap();
    assert!(r.frames.len() >= 20);
    assert!(
        text.contains("toggle_pause") && text.contains("step_dda") && text.contains("turn_left")
    );
}

#[test]
fn writes_one_file_per_requested_frame() {
    let dir = tempfile::tempdir().unwrap();
    replay_frames(FIXTURE, "0,5,10", "ansi", dir.path());
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(
        names,
        ["frame-00000.ansi", "frame-00005.ansi", "frame-00010.ansi"]
    );
    for n in &names {
        let bytes = std::fs::read(dir.path().join(n)).unwrap();
        assert!(
            bytes.starts_with(b"\x1b[?2026h") && bytes.ends_with(b"\x1b[?2026l"),
            "{n}"
        );
    }
}

#[test]
fn two_runs_are_byte_identical_and_diff_agrees() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    replay_frames(FIXTURE, "0-31", "ansi", a.path());
    replay_frames(FIXTURE, "0-31", "ansi", b.path());
    for i in 0..32 {
        let name = format!("frame-{i:05}.ansi");
        let (x, y) = (a.path().join(&name), b.path().join(&name));
        assert_eq!(
            std::fs::read(&x).unwrap(),
            std::fs::read(&y).unwrap(),
            "{name}"
        );
    }
    let last = "frame-00031.ansi";
    let o = halfcast(&[
        "diff",
        a.path().join(last).to_str().unwrap(),
        b.path().join(last).to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&o.stdout).contains(" 0 differ"));
}

#[test]
fn changing_one_key_in_the_replay_changes_the_frames() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(root().join(FIXTURE)).unwrap();
    let changed = text.replacen(
        "\"held\":[\"forward\",\"turn_left\"]",
        "\"held\":[\"forward\",\"turn_right\"]",
        1,
    );
    assert_ne!(text, changed);
    let edited = dir.path().join("edited.hcr");
    std::fs::write(&edited, changed).unwrap();
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    replay_frames(FIXTURE, "31", "png", &a);
    replay_frames(edited.to_str().unwrap(), "31", "png", &b);
    let o = halfcast(&[
        "diff",
        a.join("frame-00031.png").to_str().unwrap(),
        b.join("frame-00031.png").to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
}

#[test]
fn the_asciicast_is_valid_v2_and_ends_on_the_last_frame() {
    let text = replay_cast(FIXTURE, &[]);
    let mut lines = text.lines();
    let header: serde_json::Value = serde_json::from_str(lines.next().unwrap()).unwrap();
    assert_eq!(header["version"], 2);
    let (w, h) = (
        header["width"].as_u64().unwrap() as u16,
        header["height"].as_u64().unwrap() as u16,
    );
    let mut term = vt100::Parser::new(h, w, 0);
    let mut last_t = 0.0;
    let mut events = 0;
    for line in lines {
        let e: serde_json::Value = serde_json::from_str(line).unwrap();
        let arr = e.as_array().unwrap();
        assert_eq!(arr.len(), 3);
        let t = arr[0].as_f64().unwrap();
        assert!(t >= last_t, "timestamps go forward");
        last_t = t;
        assert_eq!(arr[1], "o");
        term.process(arr[2].as_str().unwrap().as_bytes());
        events += 1;
    }
    assert_eq!(
        events, 33,
        "one event to hide the cursor, then one per frame"
    );
    assert!((last_t - 31.0 / 30.0).abs() < 1e-9);
    let dir = tempfile::tempdir().unwrap();
    replay_frames(FIXTURE, "31", "cells", dir.path());
    let (want, _) = termframe::load(&dir.path().join("frame-00031.cells.txt")).unwrap();
    let seen = from_screen(term.screen(), usize::from(w), usize::from(h));
    assert!(
        termframe::diff(&want, &seen).is_equal(),
        "{}",
        termframe::diff(&want, &seen).summary()
    );
}

#[test]
fn corrupt_future_and_short_replays_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("future.hcr", "{\"halfcast_replay\":9}\n", "future.hcr:1: replay version 9 is newer than this halfcast reads (version 1); upgrade halfcast"),
        ("junk.hcr", "\u{1}\u{2}garbage\n", "junk.hcr:1: not a halfcast replay header: "),
    ];
    for (name, body, want) in cases {
        let p = dir.path().join(name);
        std::fs::write(&p, body).unwrap();
        let o = halfcast(&["replay", p.to_str().unwrap(), "--format", "cast"]);
        assert_eq!(o.status.code(), Some(2));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.starts_with("error: ") && err.contains(want), "{err}");
    }
    let o = halfcast(&[
        "replay",
        FIXTURE,
        "--frames",
        "99",
        "--format",
        "png",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr)
        .contains("frame 99 is past the end (the replay has 32 frames, 0 to 31)"));
}

#[test]
fn until_frame_ends_the_run_on_that_frame() {
    let text = replay_cast(FIXTURE, &["--until-frame", "10"]);
    // The header, the cursor hide, then frames 0..=10.
    assert_eq!(text.lines().count(), 1 + 1 + 11);
    let o = halfcast(&["replay", FIXTURE, "--until-frame", "32", "--format", "cast"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr)
        .contains("frame 32 is past the end (the replay has 32 frames, 0 to 31)"));
}
