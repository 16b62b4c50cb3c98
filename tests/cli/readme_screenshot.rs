//! The README's screenshot is the game screen (view, map and ray panes, the message, the status
//! line) of a replay, drawn by `output::screenshot`: replaying docs/screenshots/readme.hcr and
//! drawing its last frame gives docs/screenshot.png exactly (`RATATUI_CELLS_UPDATE=1` redraws
//! it after an intended change to the screen).

use halfcast::output::screenshot::screenshot;
use halfcast::snapshot::{assert_png_golden, Tolerance};
use halfcast::termframe;

use crate::common::{halfcast_ok, root};

#[test]
fn the_readme_screenshot_is_a_replay_drawn_by_the_screenshot_writer() {
    let dir = tempfile::tempdir().unwrap();
    let replay = root().join("docs/screenshots/readme.hcr");
    let out = format!("{}/", dir.path().display());
    halfcast_ok(&[
        "replay",
        replay.to_str().unwrap(),
        "--frames",
        "19",
        "--format",
        "cells",
        "--out",
        &out,
    ]);
    let (frame, _) = termframe::load(&dir.path().join("frame-00019.cells.txt")).unwrap();
    assert_eq!((frame.cols, frame.rows), (80, 24));
    let shot = screenshot(&frame);
    assert_eq!((shot.width(), shot.height()), (640, 384));
    assert_png_golden(&shot, root().join("docs/screenshot.png"), Tolerance::EXACT);
}
