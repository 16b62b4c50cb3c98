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
