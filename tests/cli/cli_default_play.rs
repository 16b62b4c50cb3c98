//! `play` is the default command: `halfcast MAP`, `halfcast --fps 60` and
//! `halfcast MAP --colors 256` start the game, other commands keep working, and `--help` lists
//! the keys.

use std::process::{Command, Stdio};

fn halfcast(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(Stdio::null())
        .output()
        .expect("run halfcast")
}

fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn help_lists_the_keys_and_the_default_command() {
    let o = halfcast(&["--help"]);
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout);
    for part in [
        "halfcast [MAP.cub] [PLAY OPTIONS]",
        "Keys while playing",
        "walk forward / back",
        "quit",
        "    o / u ",
        "next colour level / next block characters",
        "--glyphs <GLYPHS>",
        "--fps <FPS>",
        "render",
        "serve",
    ] {
        assert!(out.contains(part), "{part:?} missing from:\n{out}");
    }
    let o = halfcast(&["play", "--help"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("Keys while playing"));
}

#[test]
fn a_map_alone_starts_the_game_and_a_missing_one_is_a_map_error() {
    let o = halfcast(&["nonexistent.cub"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("error: nonexistent.cub: cannot read the file"),
        "{err}"
    );
    assert!(!err.contains("unrecognized subcommand"), "{err}");
}

#[test]
fn play_flags_without_a_command_reach_the_game() {
    // Without a terminal the game refuses to start: proof the flags were taken as play's.
    for args in [
        &["--fps", "60"][..],
        &["maps/default.cub", "--colors", "256"],
        &["maps/default.cub"],
    ] {
        let o = halfcast(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("standard input is not a terminal"),
            "{args:?}: {}",
            stderr(&o)
        );
    }
    // A play flag's own checks still apply.
    let o = halfcast(&["--fps", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--fps"), "{}", stderr(&o));
}

#[test]
fn other_commands_still_work() {
    let o = halfcast(&[
        "render",
        "maps/default.cub",
        "--format",
        "txt",
        "--size",
        "20x6",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!o.stdout.is_empty());
    // A command and play's map together is a mistake, said as such.
    let o = halfcast(&["maps/default.cub", "render"]);
    assert_eq!(o.status.code(), Some(2));
}
