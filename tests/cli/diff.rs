//! `halfcast diff`: exit 0 for equal frames in any format pair, 1 for different, 2 for errors.

use crate::common;

use common::{halfcast, halfcast_ok};

fn render(dir: &std::path::Path, name: &str, extra: &[&str]) -> String {
    let path = dir.join(name).to_str().unwrap().to_owned();
    let mut args = vec!["render", "--size", "30x9", "-o", &path];
    args.extend_from_slice(extra);
    halfcast_ok(&args);
    path
}

#[test]
fn the_same_frame_in_png_ansi_and_cells_form_is_equal() {
    let dir = tempfile::tempdir().unwrap();
    let png = render(dir.path(), "a.png", &["--format", "png"]);
    let ansi = render(
        dir.path(),
        "a.ansi",
        &["--format", "ansi", "--colors", "truecolor"],
    );
    let cells = render(dir.path(), "a.txt", &["--format", "cells"]);
    for (x, y) in [(&png, &ansi), (&ansi, &cells), (&cells, &png)] {
        let out = halfcast(&["diff", x, y]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{x} vs {y}: {}",
            String::from_utf8_lossy(&out.stdout)
        );
        assert_eq!(
            String::from_utf8_lossy(&out.stdout),
            "30x9 cells, 0 differ (0.00%), max colour delta 0\n"
        );
    }
}

#[test]
fn a_turned_camera_differs_and_writes_a_highlight() {
    let dir = tempfile::tempdir().unwrap();
    let a = render(dir.path(), "a.png", &["--format", "png"]);
    let b = render(dir.path(), "b.png", &["--format", "png", "--angle", "100"]);
    let hl = dir.path().join("d.png");
    let out = halfcast(&["diff", &a, &b, "--out", hl.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.starts_with("30x9 cells, "), "{stdout}");
    assert!(!stdout.contains(" 0 differ"));
    let picture = halfcast::Framebuffer::from_image_bytes(&std::fs::read(hl).unwrap()).unwrap();
    assert_eq!((picture.width(), picture.height()), (30, 18));
}

#[test]
fn different_sizes_differ_and_missing_files_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let a = render(dir.path(), "a.png", &["--format", "png"]);
    let b = render(dir.path(), "b.png", &["--format", "png", "--size", "31x9"]);
    let out = halfcast(&["diff", &a, &b]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        "sizes differ: 30x9 vs 31x9 cells\n"
    );
    let out = halfcast(&["diff", &a, "no/such/file.png"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&out.stderr).starts_with("error: no/such/file.png: cannot read: ")
    );
}

/// An insta `.snap` file as insta writes it: a YAML header between `---` lines, then the value.
fn snap(dir: &std::path::Path, name: &str, body: &str) -> String {
    let path = dir.join(name);
    let text = format!("---\nsource: tests/app.rs\nexpression: buffer\n---\n{body}\n");
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_owned()
}

#[test]
fn insta_snapshots_of_a_ratatui_buffer_diff_in_either_form() {
    use ratatui::buffer::Buffer;
    use ratatui::layout::Rect;
    use ratatui::style::{Color, Modifier, Style};
    let draw = |title: Style| {
        let mut buf = Buffer::empty(Rect::new(0, 0, 12, 2));
        buf.set_string(0, 0, "Build ok", title);
        buf.set_string(
            0,
            1,
            "> test",
            Style::new().add_modifier(Modifier::REVERSED),
        );
        buf
    };
    let bold = Style::new().fg(Color::Green).add_modifier(Modifier::BOLD);
    let (a, b) = (draw(bold), draw(Style::new().fg(Color::Green)));
    let dir = tempfile::tempdir().unwrap();
    let debug_a = snap(dir.path(), "debug_a.snap", &format!("{a:?}"));
    let cells_a = snap(
        dir.path(),
        "cells_a.snap",
        &halfcast::snapshot::cells_text(&a),
    );
    let debug_b = snap(dir.path(), "debug_b.snap", &format!("{b:?}"));
    let out = halfcast(&["diff", &debug_a, &cells_a]);
    assert_eq!(
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stdout).as_ref()
        ),
        (
            Some(0),
            "12x2 cells, 0 differ (0.00%), max colour delta 0\n"
        )
    );
    let picture = dir.path().join("d.png");
    let out = halfcast(&[
        "diff",
        &cells_a,
        &debug_b,
        "--out",
        picture.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    // Text frames: the picture is a screenshot (8×16 pixels a cell), changed cells in magenta.
    let picture =
        halfcast::Framebuffer::from_image_bytes(&std::fs::read(picture).unwrap()).unwrap();
    assert_eq!((picture.width(), picture.height()), (96, 32));
    let (changed, same) = (picture.get(3, 3), picture.get(3, 16 + 3));
    assert!(
        changed.r > changed.g && changed.b > changed.g,
        "{changed:?}"
    );
    assert_eq!((same.r, same.g), (same.g, same.b), "{same:?}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.starts_with("12x2 cells, 8 differ (33.33%), max colour delta 0\n")
            && stdout.contains("  cell (0,0) attributes: \"B\" fg=green bold -> \"B\" fg=green\n"),
        "{stdout}"
    );
}

#[test]
fn a_snapshot_that_is_not_a_frame_is_an_error_with_a_reason() {
    let dir = tempfile::tempdir().unwrap();
    let json = snap(dir.path(), "rays.snap", "{\n  \"rays\": []\n}");
    let repo_snap = common::root()
        .join("tests/lib/snapshots/lib__ratatui_dashboard__the_cells_text_is_no_longer_than_ratatuis_debug.snap");
    let repo_snap = repo_snap.to_str().unwrap();
    let out = halfcast(&["diff", repo_snap, &json]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("rays.snap: an insta snapshot whose contents are not a frame"),
        "{stderr}"
    );
    let out = halfcast(&["diff", repo_snap, repo_snap]);
    assert_eq!(out.status.code(), Some(0));
}
