//! The binary's colour ladder and bench command, checked on its real output.

use std::path::Path;
use std::process::{Command, Output};

use halfcast::{Framebuffer, Rgb};

fn halfcast(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_halfcast"));
    cmd.args(args)
        .env_remove("COLORTERM")
        .env_remove("TERM")
        .env_remove("NO_COLOR");
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.output().expect("the binary runs")
}

fn render_ansi(colors: Option<&str>, env: &[(&str, &str)]) -> Vec<u8> {
    let mut args = vec!["render", "--format", "ansi", "--size", "60x20"];
    if let Some(c) = colors {
        args.extend(["--colors", c]);
    }
    let out = halfcast(&args, env);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// The parameter lists of every `ESC[…m` in `bytes`; panics on any other escape sequence.
fn sgr_params(bytes: &[u8]) -> Vec<String> {
    let s = String::from_utf8(bytes.to_vec()).expect("UTF-8 output");
    let mut out = Vec::new();
    let mut rest = s.as_str();
    while let Some(i) = rest.find('\x1b') {
        let seq = &rest[i..];
        assert!(
            seq.starts_with("\x1b["),
            "non-CSI escape: {:?}",
            &seq[..seq.len().min(12)]
        );
        let end = seq
            .find(|c: char| c.is_ascii_alphabetic())
            .expect("terminated CSI");
        assert_eq!(
            &seq[end..=end],
            "m",
            "only SGR expected: {:?}",
            &seq[..=end]
        );
        out.push(seq[2..end].to_string());
        rest = &seq[end + 1..];
    }
    out
}

#[test]
fn colors_256_emits_no_24_bit_sequences() {
    let out = render_ansi(Some("256"), &[]);
    let params = sgr_params(&out);
    assert!(!params.is_empty());
    for p in &params {
        let v: Vec<&str> = p.split(';').collect();
        let mut i = 0;
        while i < v.len() {
            match v[i] {
                "" | "0" | "39" | "49" => i += 1,
                "38" | "48" => {
                    assert_eq!(v[i + 1], "5", "24-bit or odd colour in {p:?}");
                    let n: u8 = v[i + 2].parse().unwrap();
                    assert!(n >= 16, "theme colour {n} in {p:?}");
                    i += 3;
                }
                other => panic!("unexpected parameter {other} in {p:?}"),
            }
        }
    }
}

#[test]
fn colors_16_emits_only_16_colour_sgrs() {
    let out = render_ansi(Some("16"), &[]);
    let params = sgr_params(&out);
    assert!(!params.is_empty());
    for p in &params {
        for v in p.split(';') {
            let ok = v.is_empty()
                || matches!(
                    v.parse::<u8>(),
                    Ok(0 | 30..=37 | 39 | 40..=47 | 49 | 90..=97 | 100..=107)
                );
            assert!(ok, "parameter {v:?} in {p:?} is not a 16-colour SGR");
        }
    }
}

#[test]
fn colors_mono_emits_no_escape_sequences_and_matches_the_text_view() {
    let out = render_ansi(Some("mono"), &[]);
    assert!(!out.contains(&0x1b));
    assert!(out.is_ascii());
    let txt = halfcast(&["render", "--format", "txt", "--size", "60x20"], &[]);
    assert_eq!(out, txt.stdout);
}

#[test]
fn truecolor_uses_24_bit_sequences() {
    let out = render_ansi(Some("truecolor"), &[]);
    assert!(sgr_params(&out)
        .iter()
        .any(|p| p.contains("38;2;") || p.contains("48;2;")));
}

#[test]
fn the_level_is_detected_from_the_environment_when_not_given() {
    let has = |out: &[u8], needle: &str| String::from_utf8_lossy(out).contains(needle);
    let tc = render_ansi(
        None,
        &[("COLORTERM", "truecolor"), ("TERM", "xterm-256color")],
    );
    assert!(has(&tc, "8;2;"));
    let c256 = render_ansi(None, &[("TERM", "xterm-256color")]);
    assert!(has(&c256, "8;5;") && !has(&c256, "8;2;"));
    let mono = render_ansi(None, &[("COLORTERM", "truecolor"), ("NO_COLOR", "1")]);
    assert!(!mono.contains(&0x1b));
}

#[test]
fn a_bad_colour_level_is_a_usage_error() {
    let out = halfcast(&["render", "--format", "ansi", "--colors", "lots"], &[]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("not a colour level"));
}

fn write_frame(dir: &Path, name: &str, cols: u16, rows: u16, shade: u8) {
    let mut fb = Framebuffer::for_cells(cols, rows);
    for y in 0..fb.height() {
        for x in 0..fb.width() {
            let v = shade.wrapping_add((x * 7 + y * 3) as u8);
            fb.set(x, y, Rgb::new(v, v / 2, 255 - v));
        }
    }
    std::fs::write(dir.join(name), fb.to_png().unwrap()).unwrap();
}

#[test]
fn bench_frames_dump_writes_one_file_per_frame_that_replays_to_the_last_frame() {
    let dir = tempfile::tempdir().unwrap();
    let frames = dir.path().join("frames");
    let dump = dir.path().join("out");
    std::fs::create_dir(&frames).unwrap();
    for (i, shade) in [0u8, 40, 40, 90].iter().enumerate() {
        write_frame(&frames, &format!("f{i:02}.png"), 12, 5, *shade);
    }
    let out = halfcast(
        &[
            "bench",
            "--frames",
            frames.to_str().unwrap(),
            "--colors",
            "256",
            "--dump",
            dump.to_str().unwrap(),
            "--json",
        ],
        &[],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let run = &json["runs"][0];
    assert_eq!(run["colors"], "256");
    assert_eq!(
        (run["cols"].as_u64(), run["rows"].as_u64()),
        (Some(12), Some(5))
    );
    assert_eq!(run["frames"], 4);
    for key in [
        "bytes_per_frame",
        "first_frame_bytes",
        "zlib_bytes_per_frame",
        "encode_ms",
    ] {
        assert!(run["halfcast"][key].is_number(), "{key}");
    }
    assert!(run["ratatui"]["bytes_per_frame"].is_number());
    let mut names: Vec<String> = std::fs::read_dir(&dump)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "frame-000.ansi",
            "frame-001.ansi",
            "frame-002.ansi",
            "frame-003.ansi"
        ]
    );
    let first = std::fs::read(dump.join("frame-000.ansi")).unwrap();
    assert!(first.starts_with(b"\x1b[?2026h") && first.ends_with(b"\x1b[?2026l"));
    // An identical frame sends nothing.
    assert!(std::fs::read(dump.join("frame-002.ansi"))
        .unwrap()
        .is_empty());
    let mut term = vt100::Parser::new(5, 12, 0);
    for n in &names {
        term.process(&std::fs::read(dump.join(n)).unwrap());
    }
    let cell = term.screen().cell(0, 0).unwrap();
    assert!(matches!(cell.bgcolor(), vt100::Color::Idx(i) if i >= 16));
}

#[test]
fn bench_frames_reports_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let run = |d: &Path| halfcast(&["bench", "--frames", d.to_str().unwrap()], &[]);
    let missing = run(&dir.path().join("nope"));
    assert_eq!(missing.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("cannot read frames directory"));

    let mixed = dir.path().join("mixed");
    std::fs::create_dir(&mixed).unwrap();
    write_frame(&mixed, "a.png", 8, 4, 0);
    std::fs::write(mixed.join("b.png"), b"not a png").unwrap();
    let out = run(&mixed);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("is not a PNG"));

    let sizes = dir.path().join("sizes");
    std::fs::create_dir(&sizes).unwrap();
    write_frame(&sizes, "a.png", 8, 4, 0);
    write_frame(&sizes, "b.png", 9, 4, 0);
    let out = run(&sizes);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("same size"));

    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    assert_eq!(run(&empty).status.code(), Some(2));
}

#[test]
fn bench_json_has_the_documented_shape() {
    let out = halfcast(
        &["bench", "--json", "--frame-count", "2", "--colors", "16"],
        &[],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let runs = json["runs"].as_array().unwrap();
    let scenes: Vec<&str> = runs.iter().map(|r| r["scene"].as_str().unwrap()).collect();
    assert!(scenes.contains(&"turn") && scenes.contains(&"walk"));
    let sizes: Vec<(u64, u64)> = runs
        .iter()
        .map(|r| (r["cols"].as_u64().unwrap(), r["rows"].as_u64().unwrap()))
        .collect();
    assert!(sizes.contains(&(240, 68)) && sizes.contains(&(160, 48)));
    for r in runs {
        assert_eq!(r["colors"], "16");
        assert_eq!(r["frames"], 3);
        for key in [
            "bytes_per_frame",
            "first_frame_bytes",
            "zlib_bytes_per_frame",
            "encode_ms",
            "render_ms",
        ] {
            assert!(r["halfcast"][key].is_number(), "{key}");
        }
        for key in ["bytes_per_frame", "first_frame_bytes"] {
            assert!(r["ratatui"][key].is_number(), "{key}");
        }
        // Issues 12 and 20: how the colours look, per run, beside nearest and Floyd–Steinberg.
        for key in ["scielab_45", "scielab_9"] {
            assert!(r[key].as_f64().is_some_and(|d| d > 0.0), "{key}: {r}");
            for baseline in ["nearest", "floyd_steinberg"] {
                assert!(r[baseline][key].as_f64().is_some_and(|d| d > 0.0), "{r}");
            }
        }
        for key in ["chroma_kept", "hue_error"] {
            assert!(r[key].is_number() || r[key].is_null());
        }
    }
}
