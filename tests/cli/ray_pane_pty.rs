//! The ray pane's lesson at 80×24 with the minimap showing, as a learner meets it: the real
//! binary in a pseudo-terminal (read back through `vt100`), paused, then `↑` pressed once per
//! stop until the start of the derivation. Every line of the setup shows on the way, and
//! `cameraX` at the end (issue 53: `↑` used to stop at "↑ 10 more above").
#![cfg(unix)]

use std::collections::BTreeSet;

use crate::pty_support;

use pty_support::PtyRun;

const UP: &[u8] = b"\x1b[A";

fn status(s: &vt100::Screen) -> String {
    s.contents().lines().last().unwrap_or_default().to_owned()
}

/// The steps of the paused ray, from the status line's `step 10/10 hit`.
fn steps(s: &vt100::Screen) -> usize {
    let line = status(s);
    let at = line
        .find("step ")
        .expect("the paused status names the step")
        + "step ".len();
    let shown: String = line[at..]
        .chars()
        .skip_while(char::is_ascii_digit)
        .skip(1)
        .take_while(char::is_ascii_digit)
        .collect();
    shown
        .parse()
        .unwrap_or_else(|_| panic!("no step count in {line:?}"))
}

#[test]
fn at_80x24_with_the_minimap_the_paused_pane_scrolls_back_to_camera_x() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/no-such-dir");
    let args = ["play", "--fps", "30", "--no-mouse"];
    let mut run = PtyRun::spawn_with(&args, (80, 24), &[("XDG_CONFIG_HOME", dir)]);
    run.wait_for_screen("the first frame", |s| status(s).contains("q quit"));
    run.send(b" ");
    run.wait_for_screen("the paused ray", |s| {
        status(s).contains("PAUSED") && s.contents().contains("texture x")
    });
    let first = run.screen().contents();
    assert!(first.contains(" map "), "the minimap shows:\n{first}");
    assert!(
        !first.contains("cameraX"),
        "a pane this short starts at the hit:\n{first}"
    );
    // One stop per step and the hit, then one per part of the setup past its end; the pane
    // moves on each press until its first line shows.
    let stops = steps(run.screen()) + 1 + 4;
    let mut seen: BTreeSet<String> = first.lines().map(str::to_owned).collect();
    let mut before = first;
    for press in 1..=stops {
        run.send(UP);
        let what = format!("the pane to move on press {press} of {stops}");
        run.wait_for_screen(&what, |s| s.contents() != before);
        before = run.screen().contents();
        seen.extend(before.lines().map(str::to_owned));
        if before.contains("cameraX = 2x/w") {
            break;
        }
    }
    assert!(
        before.contains("cameraX = 2x/w"),
        "scrolled to the top:\n{before}"
    );
    let seen = seen.into_iter().collect::<Vec<_>>().join("\n");
    for name in [
        "cameraX",
        "rayDir",
        "deltaDist",
        "pos (",
        "stepX",
        "sideDistX",
        "stepY",
        "sideDistY",
    ] {
        assert!(
            seen.contains(name),
            "{name} never showed; screens seen:\n{seen}"
        );
    }
    // And `↓` comes back down.
    run.send(b"\x1b[B");
    run.wait_for_screen("the pane to move down", |s| s.contents() != before);
    run.send(b"q");
    run.wait_exit();
}
