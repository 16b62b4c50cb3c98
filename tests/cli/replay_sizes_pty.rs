//! `halfcast replay` on screen in a terminal of another size than the recording's: centred in a
//! larger one (the same cells, offset), a clear note in a smaller one (never a cut-up frame).
#![cfg(unix)]

use crate::pty_support;

use halfcast::termframe::{self, TermFrame};
use pty_support::{final_screen, replay_on_screen, PtyRun};

const FIXTURE: &str = "tests/fixtures/walk_turn_debug.hcr";

/// The `cols` × `rows` part of `frame` starting at (`x`, `y`).
fn crop(frame: &TermFrame, x: usize, y: usize, cols: usize, rows: usize) -> TermFrame {
    let mut cells = Vec::with_capacity(cols * rows);
    for r in 0..rows {
        for c in 0..cols {
            cells.push(frame.cell(x + c, y + r).clone());
        }
    }
    TermFrame { cols, rows, cells }
}

#[test]
fn a_larger_terminal_shows_the_recording_centred() {
    let native = replay_on_screen(FIXTURE, Some(30));
    let size = (140u16, 42u16);
    let mut run = PtyRun::spawn(&["replay", FIXTURE, "--until-frame", "30"], size);
    let status = run.wait_exit();
    assert!(status.success(), "{status:?}");
    let seen = final_screen(&run.bytes(), size);
    let (dx, dy) = (
        (usize::from(size.0) - native.cols) / 2,
        (usize::from(size.1) - native.rows) / 2,
    );
    let middle = crop(&seen, dx, dy, native.cols, native.rows);
    let report = termframe::diff(&native, &middle);
    assert!(report.is_equal(), "{}", report.summary());
    // Around it: nothing.
    for x in 0..seen.cols {
        assert_eq!(seen.cell(x, 0).glyph, ' ', "row 0 col {x}");
    }
}

#[test]
fn a_smaller_terminal_says_what_size_the_recording_needs() {
    let size = (80u16, 24u16);
    let mut run = PtyRun::spawn(&["replay", FIXTURE], size);
    run.wait_for_screen("the note", |s| {
        s.contents()
            .contains("this recording is 120x36; the terminal is 80x24")
    });
    let text = run.screen().contents();
    assert!(
        !text.contains('▀') && !text.contains('▄') && !text.contains("ray"),
        "part of a frame is on screen:\n{text}"
    );
    run.send(b"q");
    let status = run.wait_exit();
    assert!(status.success(), "{status:?}");
}
