//! The glyph ladder on the command line: `render --glyphs`, the `glyphs` test card, and a bad
//! setting's message.

use crate::common;

use common::{halfcast, halfcast_ok};

fn has_octant(s: &str) -> bool {
    s.chars()
        .any(|c| (0x1CD00..=0x1CDE5).contains(&u32::from(c)))
}

#[test]
fn render_writes_each_setting_as_the_terminal_shows_it() {
    // PNG: cells come out 1:2 — half 20×12, quadrant and octant 40×24, sextant 120×72.
    for (g, size) in [
        ("half", (20, 12)),
        ("quadrant", (40, 24)),
        ("sextant", (120, 72)),
        ("octant", (40, 24)),
    ] {
        let out = halfcast_ok(&["render", "--size", "20x6", "--glyphs", g]);
        let img = image::load_from_memory(&out.stdout).unwrap();
        assert_eq!((img.width(), img.height()), size, "{g}");
    }
    let cells = halfcast_ok(&[
        "render", "--size", "20x6", "--glyphs", "octant", "--format", "cells",
    ]);
    let text = String::from_utf8(cells.stdout).unwrap();
    assert!(text.starts_with("ratatui-cells v1 20x6\n") && has_octant(&text));
    let ansi = halfcast_ok(&[
        "render", "--size", "20x6", "--glyphs", "octant", "--format", "ansi", "--colors", "256",
    ]);
    let text = String::from_utf8(ansi.stdout).unwrap();
    assert!(has_octant(&text) && text.contains("\x1b[38;5;") && text.lines().count() == 6);
    let txt = halfcast_ok(&[
        "render", "--size", "20x6", "--glyphs", "sextant", "--format", "txt",
    ]);
    assert!(txt.stdout.is_ascii() && txt.stdout.split(|&b| b == b'\n').count() >= 6);
}

#[test]
fn a_bad_setting_is_exit_2_with_the_choices() {
    let out = halfcast(&["render", "--glyphs", "braille"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("'braille' is not a glyph setting (half, quadrant, sextant or octant)"),
        "{err}"
    );
}

#[test]
fn the_test_card_shows_every_set() {
    let out = halfcast_ok(&["glyphs", "--colors", "truecolor"]);
    let text = String::from_utf8(out.stdout).unwrap();
    for needle in [
        "half ",
        "quadrant ",
        "sextant ",
        "octant ",
        "▟",
        "\u{1FB00}",
        "\u{1CD00}",
    ] {
        assert!(text.contains(needle), "{needle:?} missing");
    }
    assert!(has_octant(&text));
}

#[test]
fn bench_glyphs_measures_every_setting_at_both_sizes_against_half_blocks() {
    let out = halfcast_ok(&["bench", "--glyphs", "--json", "--frame-count", "2"]);
    let runs: Vec<serde_json::Value> = serde_json::from_slice(&out.stdout).unwrap();
    let names = ["half", "quadrant", "sextant", "octant"];
    let shape: Vec<(String, u64, u64)> = runs
        .iter()
        .map(|r| {
            let g = r["glyphs"].as_str().unwrap().to_owned();
            (g, r["cols"].as_u64().unwrap(), r["rows"].as_u64().unwrap())
        })
        .collect();
    let want: Vec<(String, u64, u64)> = [(80, 24), (240, 68)]
        .iter()
        .flat_map(|&(c, r)| names.iter().map(move |g| ((*g).to_owned(), c, r)))
        .collect();
    assert_eq!(shape, want);
    let f = |r: &serde_json::Value, k: &str| r[k].as_f64().unwrap_or_else(|| panic!("{k}: {r}"));
    for r in &runs {
        for k in [
            "render_ms",
            "encode_ms",
            "bytes_per_frame",
            "scielab_9",
            "scielab_18",
        ] {
            assert!(f(r, k) > 0.0, "{k}: {r}");
        }
        let fps = 1000.0 / (f(r, "render_ms") + f(r, "encode_ms"));
        assert!((f(r, "fps") - fps).abs() < 1e-6 * fps, "{r}");
        if r["glyphs"] == "half" {
            for k in ["error_vs_half", "bytes_vs_half", "time_vs_half"] {
                assert_eq!(f(r, k), 1.0, "{k}: {r}");
            }
        }
        if r["glyphs"] == "octant" {
            // Four times the pixels: the picture comes much closer to the octant-grid render.
            assert!(f(r, "error_vs_half") < 0.5, "{r}");
        }
    }
}
