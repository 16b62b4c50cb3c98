//! Keys, help and panes as a player meets them: the real binary in a pseudo-terminal that has no
//! kitty keyboard protocol (so no key releases, like tmux), read back through `vt100`.
//! The tap and hold figures are printed (`cargo test --test play_keys_pty -- --nocapture`).
#![cfg(unix)]

use crate::pty_support;

use std::thread;
use std::time::{Duration, Instant};

use pty_support::PtyRun;

/// Starts the game with no user config file, waits for its first whole frame.
fn start(size: (u16, u16), extra: &[&str]) -> PtyRun {
    let mut args = vec!["play", "--fps", "30", "--no-mouse"];
    args.extend_from_slice(extra);
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/no-such-dir");
    let mut run = PtyRun::spawn_with(&args, size, &[("XDG_CONFIG_HOME", dir)]);
    run.wait_for_screen("the first frame", |s| {
        status(s).contains("q quit") || status(s).contains("hidden")
    });
    run
}

fn status(s: &vt100::Screen) -> String {
    s.contents().lines().last().unwrap_or_default().to_owned()
}

/// (x, y, angle) from the status line ("pos 15.50,5.50" and "angle 90.0°").
fn pose(run: &mut PtyRun) -> (f64, f64, f64) {
    let line = status(run.screen());
    let after = |key: &str| -> &str {
        let i = line
            .find(key)
            .unwrap_or_else(|| panic!("no {key} in {line:?}"));
        &line[i + key.len()..]
    };
    let pos: String = after("pos ")
        .chars()
        .take_while(|c| c.is_ascii_digit() || matches!(c, '.' | ',' | '-'))
        .collect();
    let (x, y) = pos.split_once(',').expect("pos x,y");
    let angle: String = after("angle ")
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    (
        x.parse().unwrap(),
        y.parse().unwrap(),
        angle.parse().unwrap(),
    )
}

/// Sends `key` then waits `settle` so the motion it causes is over and drawn.
fn after_keys(run: &mut PtyRun, key: &[u8], settle: Duration) -> (f64, f64, f64) {
    run.send(key);
    thread::sleep(settle);
    pose(run)
}

/// Signed smallest difference of two angles in degrees.
fn turned(from: f64, to: f64) -> f64 {
    (to - from + 540.0).rem_euclid(360.0) - 180.0
}

#[test]
fn without_releases_a_tap_is_a_small_step_and_a_hold_moves_steadily() {
    let mut run = start((120, 30), &[]);
    let settle = Duration::from_millis(900);
    let (x0, y0, _) = pose(&mut run);

    // One tap of w: a short walk (the start faces open floor).
    let (x1, y1, a1) = after_keys(&mut run, b"w", settle);
    let walked = (x1 - x0).hypot(y1 - y0);
    eprintln!("one tap of w walks {walked:.2} cells");
    assert!(walked > 0.0 && walked <= 0.3, "walked {walked}");

    // One tap of d: a small turn.
    let (_, _, a2) = after_keys(&mut run, b"d", settle);
    let one = turned(a1, a2).abs();
    eprintln!("one tap of d turns {one:.1} deg");
    assert!(one > 0.0 && one <= 10.0, "turned {one}");

    // Five taps 0.6 s apart: five small turns.
    for _ in 0..5 {
        run.send(b"a");
        thread::sleep(Duration::from_millis(600));
    }
    thread::sleep(Duration::from_millis(300));
    let (_, _, a3) = pose(&mut run);
    let five = turned(a2, a3);
    eprintln!("five taps of a 0.6 s apart turn {five:.1} deg");
    assert!(five > 5.0 * 5.0 && five <= 50.0, "five taps turned {five}");

    // Held for 1 s: a press, the keyboard's repeat delay, then repeats every 33 ms.
    let t0 = Instant::now();
    run.send(b"d");
    thread::sleep(Duration::from_millis(500));
    while t0.elapsed() < Duration::from_secs(1) {
        run.send(b"d");
        thread::sleep(Duration::from_millis(33));
    }
    thread::sleep(settle);
    let (_, _, a4) = pose(&mut run);
    let held = turned(a3, a4).abs();
    eprintln!("d held for 1 s (500 ms delay, 33 ms repeats) turns {held:.1} deg");
    // Two taps (press and first repeat) plus half a second at ~149 deg/s.
    assert!(held > 60.0 && held < 120.0, "held {held}");
    let (x5, y5, _) = pose(&mut run);
    assert_eq!((x5, y5), (x1, y1), "turning does not walk");
    run.send(b"q");
    run.wait_exit();
}

/// The debugged column the ray pane names ("ray - column 37").
fn column(s: &vt100::Screen) -> Option<u32> {
    let text = s.contents();
    let i = text.find("ray - column ")?;
    let n: String = text[i + 13..]
        .chars()
        .take_while(char::is_ascii_digit)
        .collect();
    n.parse().ok()
}

#[test]
fn paused_arrows_move_the_column_and_resuming_does_not_turn() {
    let mut run = start((120, 30), &[]);
    let (_, _, a0) = pose(&mut run);
    run.send(b"p");
    run.wait_for_screen("paused", |s| status(s).contains("PAUSED"));
    let c0 = column(run.screen()).expect("column shown");
    // Paused: right arrow, then resume at once (within 0.5 s).
    run.send(b"\x1b[C");
    thread::sleep(Duration::from_millis(150));
    run.send(b" ");
    run.wait_for_screen("resumed", |s| !status(s).contains("PAUSED"));
    thread::sleep(Duration::from_millis(900));
    let (_, _, a1) = pose(&mut run);
    let t = turned(a0, a1).abs();
    assert!(t < 0.05, "turned {t} deg across pause, right arrow, resume");
    // The arrow moved the column (seen by pausing again: resuming goes back to the centre).
    run.send(b"p");
    run.wait_for_screen("paused again", |s| status(s).contains("PAUSED"));
    run.send(b"\x1b[C");
    run.wait_for_screen("column moved", |s| column(s) == Some(c0 + 1));
    let (_, _, a2) = pose(&mut run);
    assert!(
        turned(a1, a2).abs() < 0.05,
        "a paused arrow turned the view"
    );
    run.send(b"q");
    run.wait_exit();
}

#[test]
fn help_is_visible_over_the_view_at_80x24_and_lists_every_key() {
    let mut run = start((80, 24), &[]);
    run.send(b"?");
    run.wait_for_screen("the help", |s| s.contents().contains("walk forward / back"));
    // Let a few more frames go by: the view must not paint over the box.
    thread::sleep(Duration::from_millis(500));
    let text = run.screen().contents();
    for needle in [
        "walk forward / back",
        "turn (paused: move the debugged column)",
        "strafe left / right",
        "look up / down",
        "look straight ahead again",
        "jump",
        "crouch (hold)",
        "open / close a door / throw a tag",
        "night mode on / off",
        "pause / resume the world",
        "single-step the DDA",
        "run the DDA to its hit",
        "show / hide the minimap / the ray pane",
        "quit",
    ] {
        assert!(text.contains(needle), "{needle} missing:\n{text}");
    }
    // The box is over the view (which starts at column 0), not only over the side panes.
    let row = text
        .lines()
        .position(|l| l.contains("walk forward"))
        .unwrap();
    let col = text.lines().nth(row).unwrap().find("w up").unwrap();
    assert!(col < 40, "help at column {col}");
    run.send(b"\x1b");
    run.wait_for_screen("help closed", |s| !s.contents().contains("walk forward"));
    run.send(b"q");
    run.wait_exit();
}

#[test]
fn at_80x24_both_panes_show_and_too_narrow_says_why_a_pane_is_hidden() {
    let mut run = start((80, 24), &[]);
    let text = run.screen().contents();
    assert!(
        text.contains(" map ") && text.contains("ray - column"),
        "{text}"
    );
    assert!(text.contains("perp = sideDistY"), "{text}");
    run.send(b"q");
    run.wait_exit();

    let mut run = start((58, 24), &[]);
    run.wait_for_screen("the notice", |s| {
        status(s).contains("minimap and ray pane hidden: no room at 58x24")
    });
    run.send(b"q");
    run.wait_exit();
}

#[test]
fn mono_screens_are_plain_ascii_with_a_readable_map() {
    let mut run = start((80, 24), &["--colors", "mono"]);
    run.wait_for_screen("the panes", |s| s.contents().contains("hit (15,0)"));
    let bytes = run.bytes();
    let text = run.screen().contents();
    // The minimap: walls, floor, the player and the ray.
    let map: Vec<&str> = text.lines().skip(1).take(7).map(|l| &l[51..79]).collect();
    let joined = map.join("\n");
    for c in ['#', '.', '@', '*'] {
        assert!(joined.contains(c), "{c} not on the map:\n{joined}");
    }
    // The ray pane in ASCII: `-` for the minus sign, `->` for the arrow.
    assert!(text.contains("perp = sideDistY-deltaDistY"), "{text}");
    assert!(text.contains("-> "), "{text}");
    // At 80 columns the game's figures and the position fill the status line (ASCII too).
    let line = status(run.screen());
    assert!(
        line.contains(" 0 pts  12 left") && line.contains("pos 15.50,5.50"),
        "{line}"
    );
    run.send(b"?");
    run.wait_for_screen("the help", |s| s.contents().contains("walk forward"));
    run.send(b"q");
    run.wait_exit();
    // Wider, the angle shows too, in ASCII.
    let mut wide = start((120, 30), &["--colors", "mono"]);
    wide.wait_for_screen("the status line", |s| s.contents().contains("q quit"));
    assert!(
        status(wide.screen()).contains("90.0 deg"),
        "{}",
        wide.screen().contents()
    );
    wide.send(b"q");
    wide.wait_exit();
    let bytes_after = run.bytes();
    assert!(bytes.len() <= bytes_after.len());
    let odd: Vec<u8> = bytes_after
        .iter()
        .copied()
        .filter(|b| !b.is_ascii())
        .collect();
    assert!(odd.is_empty(), "{} non-ASCII bytes", odd.len());
}
