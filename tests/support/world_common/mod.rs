//! Shared helpers for the world-feature tests: small maps built from text with embedded textures.

use std::path::PathBuf;

use halfcast::map::parse_map;
use halfcast::snapshot::{assert_png_golden, Tolerance};
use halfcast::world::{TextureSource, World};
use halfcast::Framebuffer;

/// Header shared by the test maps: embedded wall, floor and ceiling textures.
pub const HEADER: &str = "NO textures/bricks.png\nSO textures/bricks.png\nWE textures/stone.png\nEA textures/stone.png\nF 96,88,80\nC 150,146,136\nFT textures/floor.png\nCT textures/ceiling.png\n";

/// A 10 × 6 room with a wall block at (6, 3) and the player at (1, 3) facing east.
pub const ROOM: &str = "1111111111\n1000000001\n1000000001\n1E00001001\n1000000001\n1111111111\n";

/// Builds a world from extra header lines and a grid, textures from the embedded set.
pub fn world(extra: &str, grid: &str) -> World {
    let text = format!("{HEADER}{extra}\n{grid}");
    let map = parse_map("test.cub", text.as_bytes()).unwrap_or_else(|e| panic!("{e}"));
    let (w, warnings) = World::load(map, &TextureSource::Embedded, true).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    w
}

/// The golden image path for a case.
pub fn golden_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/images/world")
        .join(format!("{name}.png"))
}

/// Compares with `tests/images/world/<name>.png` (tolerance: rounding only).
pub fn golden(fb: &Framebuffer, name: &str) {
    assert_png_golden(fb, golden_path(name), Tolerance::default());
}

/// Path of an embedded sprite's PNG in the repository (for maps written to disk).
pub fn sprite_png(name: &str) -> String {
    format!("{}/textures/sprites/{name}.png", env!("CARGO_MANIFEST_DIR"))
}

/// Runs the binary with `args`.
pub fn halfcast(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(args)
        .output()
        .expect("run halfcast")
}

/// Writes a map (header + `extra` + grid) into a temporary folder; textures are absolute paths
/// into the repository, so it loads from disk like a user's map.
pub fn map_file(extra: &str, grid: &str) -> (tempfile::TempDir, PathBuf) {
    let root = env!("CARGO_MANIFEST_DIR");
    let header = HEADER.replace("textures/", &format!("{root}/textures/"));
    let extra = extra.replace("textures/", &format!("{root}/textures/"));
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("test.cub");
    std::fs::write(&path, format!("{header}{extra}\n{grid}")).expect("write map");
    (dir, path)
}
