//! A terminal nobody reads: `halfcast play` must still end on SIGTERM and restore the line
//! discipline, even though its frames (and its restore sequences) can no longer be written.
#![cfg(unix)]

use crate::pty_support;

use std::thread;
use std::time::{Duration, Instant};

use pty_support::{contains, PtyRun, PATIENCE};

#[test]
fn sigterm_ends_a_game_whose_terminal_nobody_reads() {
    let mut run = PtyRun::spawn(&["play", "--fps", "60"], (160, 48));
    let before = run.master.get_termios().expect("termios");
    run.wait_for("the first frame", |out| {
        contains(out, "sideDist".as_bytes())
    });
    let raw = run.master.get_termios().expect("termios");
    assert_ne!(
        before.local_flags, raw.local_flags,
        "the game is in raw mode"
    );
    // Stop draining the pty, and keep the view turning so every frame is a big redraw.
    run.pause_reading(true);
    let stalled = Instant::now();
    let mut last_len = run.bytes().len();
    let mut still_since = Instant::now();
    // The output stops growing once the pty's buffer is full and the game's write waits.
    while still_since.elapsed() < Duration::from_millis(700) {
        run.send(b"d");
        thread::sleep(Duration::from_millis(40));
        let len = run.bytes().len();
        if len != last_len {
            last_len = len;
            still_since = Instant::now();
        }
        assert!(stalled.elapsed() < PATIENCE, "the output never stalled");
    }
    nix::sys::signal::kill(
        nix::unistd::Pid::from_raw(run.pid()),
        nix::sys::signal::Signal::SIGTERM,
    )
    .unwrap();
    let status = run.wait_exit();
    assert_eq!(status.exit_code(), 128 + 15);
    let after = run.master.get_termios().expect("termios");
    assert_eq!(
        before.local_flags, after.local_flags,
        "raw mode was left on"
    );
    assert_eq!(before.input_flags, after.input_flags);
}
