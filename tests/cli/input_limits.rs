//! Hostile inputs through the binary: each is refused (or streamed) with bounded work, exit 2
//! and its exact message. Every case here took seconds to minutes, gigabytes, a panic or a
//! blocked process before the limits existed.

use crate::common;

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use common::{halfcast, root};

/// Asserts exit code 2 and exactly `message` (after `error: `) on stderr, nothing on stdout.
fn refused(args: &[&str], message: &str) {
    let out = halfcast(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert_eq!(stderr, format!("error: {message}\n"), "{args:?}");
    assert!(out.stdout.is_empty(), "{args:?} wrote output");
}

fn has_dev_zero() -> bool {
    let ok = Path::new("/dev/zero").exists();
    if !ok {
        println!("SKIPPED: no /dev/zero on this system");
    }
    ok
}

/// A map in `dir` whose four wall faces use `texture`.
fn map_with_texture(dir: &Path, texture: &str) -> String {
    let path = dir.join("m.cub");
    let text = format!(
        "NO {texture}\nSO {texture}\nWE {texture}\nEA {texture}\nF 1,2,3\nC 4,5,6\n\n111\n1N1\n111\n"
    );
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_owned()
}

#[test]
fn a_png_claiming_a_huge_image_is_refused_before_decoding() {
    refused(
        &["render", "--strict", "tests/fixtures/huge_texture.cub", "--format", "txt"],
        "tests/fixtures/huge_texture.cub:1:4: cannot load texture './invalid_huge_texture.png': image is 20000x20000 pixels; the limit is 4096x4096",
    );
    // Without --strict it is one warning and the built-in texture.
    let out = halfcast(&[
        "render",
        "tests/fixtures/huge_texture.cub",
        "--format",
        "txt",
    ]);
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "warning: tests/fixtures/huge_texture.cub:1:4: cannot load texture './invalid_huge_texture.png': image is 20000x20000 pixels; the limit is 4096x4096; using the built-in 'bricks' texture\n"
    );
}

/// A sparse file of `len` bytes in `dir` (no disk space used): over a cap without writing it.
fn sparse(dir: &Path, name: &str, len: u64) -> String {
    let path = dir.join(name);
    std::fs::File::create(&path).unwrap().set_len(len).unwrap();
    path.to_str().unwrap().to_owned()
}

#[test]
fn a_map_at_dev_zero_is_not_read_and_a_huge_one_stops_at_the_byte_cap() {
    let dir = tempfile::tempdir().unwrap();
    let big = sparse(dir.path(), "big.cub", (32 << 20) + 1);
    refused(
        &["render", &big, "--format", "txt"],
        &format!("{big}: file is larger than 33554432 bytes (the limit for a map)"),
    );
    if !has_dev_zero() {
        return;
    }
    refused(
        &["render", "/dev/zero", "--format", "txt"],
        "/dev/zero: cannot read the file: not a regular file (a FIFO, device or socket)",
    );
}

#[test]
fn a_texture_at_a_device_is_not_opened() {
    if !has_dev_zero() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let map = map_with_texture(dir.path(), "/dev/zero");
    refused(
        &["render", "--strict", &map, "--format", "txt"],
        &format!("{map}:1:4: cannot load texture '/dev/zero': not a regular file (a FIFO, device or socket)"),
    );
}

#[test]
fn a_texture_at_a_fifo_never_blocks_the_load() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("t.png");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        println!("SKIPPED: mkfifo is not available");
        return;
    }
    let map = map_with_texture(dir.path(), "t.png");
    let message = format!(
        "{map}:1:4: cannot load texture 't.png': not a regular file (a FIFO, device or socket)"
    );
    refused(&["render", "--strict", &map, "--format", "txt"], &message);
    let out = halfcast(&["render", &map, "--format", "txt", "--size", "10x4"]);
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!("warning: {message}; using the built-in 'bricks' texture\n")
    );
}

#[test]
fn a_map_with_lights_may_not_be_huge() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("wide.cub");
    // One row of 2^20 + 3 cells: over the lit-map limit, within the 2^24-cell one.
    let w = (1 << 20) + 3;
    let mut text = String::from("NO a\nSO a\nWE a\nEA a\nF 1,2,3\nC 4,5,6\nLIGHT 1.5,1.5 2\n");
    text.push_str(&"1".repeat(w));
    text.push_str("\n1N");
    text.push_str(&"0".repeat(w - 3));
    text.push_str("1\n");
    text.push_str(&"1".repeat(w));
    text.push('\n');
    std::fs::write(&path, text).unwrap();
    let p = path.to_str().unwrap();
    refused(
        &["render", p, "--format", "txt"],
        &format!("{p}:7:1: map is too large for LIGHT (3145737 cells; lights are baked over at most 1048576)"),
    );
}

#[test]
fn a_replay_at_dev_zero_or_naming_it_as_its_map_is_not_read() {
    if !has_dev_zero() {
        return;
    }
    refused(
        &["replay", "/dev/zero", "--format", "cast"],
        "/dev/zero: cannot read: not a regular file (a FIFO, device or socket)",
    );
    let dir = tempfile::tempdir().unwrap();
    let hcr = dir.path().join("r.hcr");
    std::fs::write(
        &hcr,
        concat!(
            r#"{"halfcast_replay":1,"map":"/dev/zero","start":{"pos":[1.5,1.5],"angle":0.0,"fov":66.0},"size":[20,10],"fps":30,"seed":0}"#,
            "\n",
            r#"{"end":3}"#,
            "\n"
        ),
    )
    .unwrap();
    refused(
        &["replay", hcr.to_str().unwrap(), "--format", "cast"],
        "/dev/zero: cannot read the file: not a regular file (a FIFO, device or socket)",
    );
}

#[test]
fn frame_lists_are_bounded_by_the_format() {
    let out = halfcast(&[
        "replay",
        "tests/fixtures/walk_turn_debug.hcr",
        "--format",
        "txt",
        "--frames",
        "0-2000000",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("a replay holds at most 1000000 frames (0 to 999999)"),
        "{stderr}"
    );
}

#[test]
fn a_cast_streams_while_it_renders() {
    // 166 bytes claiming a million frames: the first events must arrive long before the end
    // (before, the whole cast was built in memory and nothing was written until it finished).
    let mut child = Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args([
            "replay",
            "tests/fixtures/million_frames.hcr",
            "--max-frames",
            "1000000",
            "--format",
            "cast",
        ])
        .current_dir(root())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("run halfcast");
    let stdout = child.stdout.take().unwrap();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let lines: Vec<String> = BufReader::new(stdout)
            .lines()
            .take(5)
            .map_while(Result::ok)
            .collect();
        let _ = tx.send(lines);
    });
    let got = rx.recv_timeout(Duration::from_secs(60));
    let _ = child.kill();
    let _ = child.wait();
    let lines = got.expect("no asciicast events within 60 s: the cast is not streamed");
    assert_eq!(lines.len(), 5);
    assert!(
        lines[0].starts_with(r#"{"version":2,"width":40,"height":12"#),
        "{}",
        lines[0]
    );
    assert!(
        lines[2].starts_with("[0.0,\"o\",") || lines[2].starts_with("[0.03"),
        "{}",
        lines[2]
    );
}

#[test]
fn diff_refuses_frames_whose_cursor_is_far_away() {
    refused(
        &["diff", "tests/fixtures/invalid_cursor_65535.ansi", "tests/fixtures/invalid_cursor_65535.ansi"],
        "tests/fixtures/invalid_cursor_65535.ansi: ANSI frame is 65535x65535 cells; the limit is 4000x2000",
    );
    refused(
        &["diff", "tests/fixtures/invalid_cursor_10000.ansi", "tests/fixtures/invalid_cursor_65535.ansi"],
        "tests/fixtures/invalid_cursor_10000.ansi: ANSI frame is 10000x10000 cells; the limit is 4000x2000",
    );
}

#[test]
fn diff_refuses_a_cells_header_whose_size_would_wrap() {
    refused(
        &["diff", "tests/fixtures/invalid_cells_size_wraps.cells.txt", "tests/fixtures/invalid_cursor_65535.ansi"],
        "tests/fixtures/invalid_cells_size_wraps.cells.txt: line 1: size 17216961135462248175x1 is over the limit of 4000x2000 cells",
    );
}

#[test]
fn diff_stops_reading_at_the_byte_cap_and_reads_no_device() {
    let dir = tempfile::tempdir().unwrap();
    let big = sparse(dir.path(), "big.ansi", (64 << 20) + 1);
    refused(
        &["diff", &big, "tests/fixtures/invalid_cursor_65535.ansi"],
        &format!("{big}: cannot read: file is larger than 67108864 bytes (the limit)"),
    );
    if !has_dev_zero() {
        return;
    }
    refused(
        &[
            "diff",
            "/dev/zero",
            "tests/fixtures/invalid_cursor_65535.ansi",
        ],
        "/dev/zero: cannot read: not a regular file (a FIFO, device or socket)",
    );
}

#[test]
fn a_maps_images_share_one_pixel_budget() {
    // Three distinct 4096×4096 files: each is within the per-image limit, but together they pass
    // the map's 2^25-pixel budget, so the third falls back like a missing texture.
    let dir = tempfile::tempdir().unwrap();
    let mut png = Vec::new();
    image::GrayImage::new(4096, 4096)
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    for name in ["a.png", "b.png", "c.png"] {
        std::fs::write(dir.path().join(name), &png).unwrap();
    }
    let map = dir.path().join("m.cub");
    std::fs::write(
        &map,
        "NO a.png\nSO b.png\nWE c.png\nEA a.png\nF 1,2,3\nC 4,5,6\n\n111\n1N1\n111\n",
    )
    .unwrap();
    let map = map.to_str().unwrap();
    refused(
        &["render", "--strict", map, "--format", "txt"],
        &format!("{map}:3:4: cannot load texture 'c.png': the map's images together would exceed 33554432 pixels (the limit)"),
    );
}
