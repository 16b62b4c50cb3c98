//! End-to-end: the real binary in a real pseudo-terminal, read back through a VT100 parser.
//! Start at 160×48, check the first screen, walk forward, quit, check the terminal is restored.
#![cfg(unix)]

use crate::pty_support;

use std::thread;
use std::time::{Duration, Instant};

use pty_support::{contains, last_index, PtyRun, KITTY, PATIENCE};

const SIZE: (u16, u16) = (160, 48);

/// The game in a 160×48 pseudo-terminal, and the line discipline before it started.
fn spawn_with(args: &[&str], env: &[(&str, &str)]) -> (PtyRun, nix::sys::termios::Termios) {
    let run = PtyRun::spawn_with(args, SIZE, env);
    let cooked = run.master.get_termios().expect("termios");
    (run, cooked)
}

fn spawn(args: &[&str]) -> (PtyRun, nix::sys::termios::Termios) {
    spawn_with(args, &[])
}

/// Waits for the child to exit (it must within the patience).
fn exit_status(s: &mut PtyRun, what: &str) -> portable_pty::ExitStatus {
    let start = Instant::now();
    loop {
        s.answer_probe();
        if let Some(st) = s.try_wait() {
            // Let the reader drain what the child wrote last.
            thread::sleep(Duration::from_millis(200));
            return st;
        }
        assert!(start.elapsed() < PATIENCE, "{what}");
        thread::sleep(Duration::from_millis(20));
    }
}

/// The colours of every cell in the top-left view region.
fn view_colours(s: &vt100::Screen) -> Vec<(vt100::Color, vt100::Color)> {
    let mut v = Vec::new();
    for row in 0..40 {
        for col in 0..100 {
            let c = s.cell(row, col).unwrap();
            v.push((c.fgcolor(), c.bgcolor()));
        }
    }
    v
}

fn status_line(s: &vt100::Screen) -> String {
    s.contents().lines().last().unwrap_or_default().to_owned()
}

#[test]
fn play_start_walk_quit_restores_the_terminal() {
    let (mut s, before) = spawn(&["play", "--fps", "30"]);
    s.wait_for_screen("the first whole frame", |sc| {
        let text = sc.contents();
        text.contains("hit (15,0)")
            && text.contains("sideDistY")
            && text.contains(" map ")
            && status_line(sc).contains("q quit")
    });
    let sc = s.screen().clone();
    let sc = &sc;
    // The view: half blocks in 24-bit colour.
    // (The encoder may draw a cell of one colour as a space with that background.)
    let cell = sc.cell(10, 10).unwrap();
    assert!(
        matches!(cell.contents().as_str(), "▀" | "▄" | "█" | " " | ""),
        "{:?}",
        cell.contents()
    );
    assert!(
        matches!(cell.bgcolor(), vt100::Color::Rgb(..)),
        "{:?} {:?}",
        cell.fgcolor(),
        cell.bgcolor()
    );
    let half_blocks = (0..40u16)
        .flat_map(|y| (0..100u16).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let c = sc.cell(y, x).unwrap();
            c.contents() == "▀" && matches!(c.fgcolor(), vt100::Color::Rgb(..))
        })
        .count();
    assert!(
        half_blocks > 1000,
        "only {half_blocks} truecolor ▀ cells in the view"
    );
    // The minimap is half blocks too, inside its bordered pane on the right.
    let text = sc.contents();
    let map_row = text
        .lines()
        .position(|l| l.contains("╭ map"))
        .expect("map pane");
    let map_col = text
        .lines()
        .nth(map_row)
        .unwrap()
        .chars()
        .position(|c| c == '╭')
        .unwrap();
    let inner = sc.cell(map_row as u16 + 3, map_col as u16 + 3).unwrap();
    assert_eq!(inner.contents(), "▀");
    // The ray pane derives the centre ray's hit: its cell (x,y) and perp.
    assert!(text.contains("hit (15,0) wall 1"), "{text}");
    assert!(text.contains("perp = sideDistY"), "{text}");
    let status = status_line(sc);
    assert!(status.contains("pos 15.50,5.50"), "{status}");
    assert!(status.contains("fps"), "{status}");

    let first_view = view_colours(sc);
    for _ in 0..4 {
        s.send(b"w");
        thread::sleep(Duration::from_millis(60));
    }
    s.wait_for_screen("the view to change after walking", |sc| {
        view_colours(sc) != first_view && !status_line(sc).contains("pos 15.50,5.50")
    });

    s.send(b"q");
    let status = exit_status(&mut s, "halfcast did not exit after q");
    assert!(status.success(), "exit status {status:?}");
    let out = s.bytes();
    let entered = last_index(&out, b"\x1b[?1049h").expect("entered the alternate screen");
    let left = last_index(&out, b"\x1b[?1049l").expect("left the alternate screen");
    assert!(left > entered);
    let hidden = last_index(&out, b"\x1b[?25l").expect("hid the cursor");
    let shown = last_index(&out, b"\x1b[?25h").expect("showed the cursor");
    assert!(shown > hidden);
    // Nothing but mode resets after leaving the alternate screen.
    assert!(!contains(&out[left..], "▀".as_bytes()));
    // Raw mode is off again: the line discipline is as it was before the game started.
    let after = s.master.get_termios().expect("termios");
    assert_eq!(before.local_flags, after.local_flags);
    assert_eq!(before.input_flags, after.input_flags);
}

#[test]
fn not_a_terminal_is_a_clear_error_with_exit_code_2() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .arg("play")
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("is not a terminal"), "{err}");
    assert!(out.stdout.is_empty());
}

#[test]
fn sigterm_restores_the_terminal_and_exits() {
    let (mut s, before) = spawn(&["play"]);
    s.wait_for_screen("the first frame", |sc| sc.contents().contains("sideDistY"));
    nix::sys::signal::kill(
        nix::unistd::Pid::from_raw(s.pid()),
        nix::sys::signal::Signal::SIGTERM,
    )
    .unwrap();
    let status = exit_status(&mut s, "halfcast ignored SIGTERM");
    assert_eq!(status.exit_code(), 128 + 15);
    let out = s.bytes();
    assert!(last_index(&out, b"\x1b[?1049l") > last_index(&out, b"\x1b[?1049h"));
    let after = s.master.get_termios().expect("termios");
    assert_eq!(before.local_flags, after.local_flags);
}

fn pos_of(sc: &vt100::Screen) -> String {
    let st = status_line(sc);
    st.split("pos ")
        .nth(1)
        .and_then(|r| r.split_whitespace().next())
        .unwrap_or_default()
        .to_owned()
}

#[test]
fn kitty_keyboard_protocol_holds_until_release() {
    let (mut s, _) = spawn(&["play"]);
    s.probe_answer = KITTY;
    s.wait_for_screen("the first frame in kitty mode", |sc| {
        status_line(sc).contains("kitty keys") && status_line(sc).contains("q quit")
    });
    // The game asked for press/repeat/release events with all keys as escape codes.
    let out = s.bytes();
    // 15 = disambiguate | event types | alternate keys | all keys as escape codes.
    assert!(contains(&out, b"\x1b[>15u"), "kitty flags not pushed");
    let start_pos = pos_of(s.screen());
    // Press w (no repeats are sent): the player keeps walking while it is held...
    s.send(b"\x1b[119;1:1u");
    s.wait_for_screen("walking", |sc| pos_of(sc) != start_pos);
    let walking = pos_of(s.screen());
    s.wait_for_screen("still walking", |sc| pos_of(sc) != walking);
    // ...and stops at the release.
    s.send(b"\x1b[119;1:3u");
    let start = Instant::now();
    loop {
        let a = pos_of(s.screen());
        thread::sleep(Duration::from_millis(300));
        if pos_of(s.screen()) == a {
            break;
        }
        assert!(
            start.elapsed() < PATIENCE,
            "still walking after the release"
        );
    }
    s.send(b"\x1b[113;1:1u");
    let status = exit_status(&mut s, "q (kitty-encoded) did not quit");
    assert!(status.success());
    // The keyboard mode was popped before leaving.
    assert!(contains(&s.bytes(), b"\x1b[<1u"));
}

/// Debug builds panic after the first frame when HALFCAST_TEST_PANIC is set.
#[cfg(debug_assertions)]
#[test]
fn a_panic_restores_the_terminal_before_the_message() {
    let (mut s, before) = spawn_with(&["play"], &[("HALFCAST_TEST_PANIC", "1")]);
    let status = exit_status(&mut s, "no panic exit");
    assert!(!status.success());
    let out = s.bytes();
    let left = last_index(&out, b"\x1b[?1049l").expect("left the alternate screen");
    let message = last_index(&out, b"HALFCAST_TEST_PANIC is set").expect("panic message shown");
    assert!(
        left < message,
        "the message must come after the restore, on the main screen"
    );
    assert!(last_index(&out, b"\x1b[?25h") > last_index(&out, b"\x1b[?25l"));
    // The buffered frame that was being drawn is not spilled after the restore.
    assert!(!contains(&out[left..], "\u{2580}".as_bytes()));
    let after = s.master.get_termios().expect("termios");
    assert_eq!(before.local_flags, after.local_flags);
}

#[test]
fn keys_are_taken_even_when_every_frame_is_late() {
    // At 1000 fps every frame is due before the one before it is drawn (a slow machine, a
    // debug build at a big size): the loop must still read what was typed, not skip input.
    let (mut s, _) = spawn(&["play", "--fps", "1000"]);
    s.wait_for_screen("the first whole frame", |sc| {
        status_line(sc).contains("q quit")
    });
    s.send(b"q");
    let st = exit_status(
        &mut s,
        "halfcast did not quit on q while every frame was late",
    );
    assert!(st.success());
}
