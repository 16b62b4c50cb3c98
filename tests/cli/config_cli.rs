//! The config file: `--print-config` prints defaults that load back, and every
//! `tests/fixtures/invalid_config_*.toml` is refused with exit code 2 and its exact message.

use crate::common;

use std::process::{Command, Output};

use common::root;

/// Runs halfcast from the project root with no user config file in reach.
fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(args)
        .current_dir(root())
        .env("XDG_CONFIG_HOME", root().join("tests/fixtures/no-such-dir"))
        .stdin(std::process::Stdio::null())
        .output()
        .expect("run halfcast")
}

const CASES: &[(&str, &str)] = &[
    ("invalid_config_bad_bool", "2:11: invalid type: string \"yes\", expected a boolean"),
    (
        "invalid_config_bad_colour",
        "2:10: display.colors: 'rainbow' is not a colour level (auto, truecolor, 256, 16 or mono)",
    ),
    (
        "invalid_config_bad_glyphs",
        "2:10: display.glyphs: 'braille' is not a glyph setting (half, quadrant, sextant or octant)",
    ),
    (
        "invalid_config_bad_key",
        "2:23: keys.forward: unknown key 'sup' (a single character like \"w\" or \"?\", or one of: space, up, down, left, right, enter, esc, tab, backspace, pageup, pagedown, home, end, insert, delete, f1-f12; \"shift+\" may prefix a named key)",
    ),
    (
        "invalid_config_bad_speed",
        "3:8: speeds.turn must be above 0 and at most 3600 (degrees per second), not -5",
    ),
    (
        "invalid_config_key_twice",
        "3:1: keys: 'w' is bound to both forward and jump (give one of them other keys)",
    ),
    ("invalid_config_syntax", "1:8: unclosed table, expected `]`"),
    (
        "invalid_config_unknown_action",
        "3:1: keys: unknown action 'fly' (known: forward, back, turn_left, turn_right, strafe_left, strafe_right, look_up, look_down, centre_pitch, crouch, jump, use_door, tag, night, pause, column_left, column_right, column_left_10, column_right_10, step_dda, run_to_hit, save_figure, minimap, ray_pane, colours, glyphs, help, quit)",
    ),
    (
        "invalid_config_unknown_field",
        "2:1: unknown field `colours`, expected one of `colors`, `glyphs`, `minimap`, `ray_pane`",
    ),
    (
        "invalid_config_unknown_section",
        "1:2: unknown field `sound`, expected one of `speeds`, `display`, `keys`",
    ),
];

#[test]
fn each_invalid_config_gives_its_exact_message_and_exit_2() {
    for (name, tail) in CASES {
        let path = format!("tests/fixtures/{name}.toml");
        // The config is read before the terminal is touched: no tty is needed to see the error.
        let out = run(&["play", "--config", &path]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
        assert_eq!(stderr, format!("error: {path}:{tail}\n"), "{name}");
    }
}

#[test]
fn every_invalid_config_fixture_is_listed() {
    let mut on_disk: Vec<String> = std::fs::read_dir(root().join("tests/fixtures"))
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.starts_with("invalid_config_") && n.ends_with(".toml"))
        .map(|n| n.trim_end_matches(".toml").to_owned())
        .collect();
    on_disk.sort();
    let listed: Vec<String> = CASES.iter().map(|(n, _)| (*n).to_owned()).collect();
    assert_eq!(on_disk, listed);
}

#[test]
fn printed_defaults_load_back_and_a_missing_config_is_an_error() {
    let out = run(&["play", "--print-config"]);
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("[keys]") && text.contains("forward = [\"w\", \"up\"]"),
        "{text}"
    );
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("config.toml");
    std::fs::write(&file, &text).unwrap();
    // Loading succeeds, so the next thing checked (the map) is what fails.
    let out = run(&[
        "play",
        "--config",
        file.to_str().unwrap(),
        "no-such-map.cub",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr.contains("no-such-map.cub") && !stderr.contains("config"),
        "{stderr}"
    );
    // The same file found through XDG_CONFIG_HOME.
    std::fs::create_dir(dir.path().join("halfcast")).unwrap();
    std::fs::write(
        dir.path().join("halfcast/config.toml"),
        "[speeds]\nturn = 0\n",
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(["play"])
        .current_dir(root())
        .env("XDG_CONFIG_HOME", dir.path())
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr.starts_with("error: ") && stderr.contains("halfcast/config.toml:2:8: speeds.turn"),
        "{stderr}"
    );
    let out = run(&["play", "--config", "tests/fixtures/no-such.toml"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with("error: tests/fixtures/no-such.toml: "),
        "{stderr}"
    );
}

#[test]
fn speed_flags_are_checked() {
    for (flag, v) in [
        ("--turn-speed", "0"),
        ("--move-speed", "nan"),
        ("--move-speed", "100"),
    ] {
        let out = run(&["play", flag, v]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{flag} {v}: {stderr}");
        assert!(stderr.starts_with(&format!("error: {flag}: ")), "{stderr}");
    }
}
