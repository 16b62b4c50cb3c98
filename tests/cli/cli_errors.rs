//! Issue 56: careless input gets one line saying what is wrong, with README's exit codes (2 bad
//! input, 1 an I/O failure): a word that is neither a command nor a map, a size past the range,
//! a `--pos` off the map or in a wall (naming the map's size), a port already in use.

use std::net::TcpListener;

use halfcast::map::Cell;
use halfcast::World;

use crate::common::{halfcast, root};

/// The commands, as the unknown-word message lists them.
const COMMANDS: &str = "render, play, bench, record, replay, serve, scores, trace, diff, glyphs";

/// Asserts exit `code`, nothing on stdout and exactly `line` (plus a newline) on stderr.
fn refused(args: &[&str], code: i32, line: &str) {
    let out = halfcast(args);
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!("{line}\n"),
        "halfcast {args:?}"
    );
    assert_eq!(out.status.code(), Some(code), "halfcast {args:?}");
    assert!(out.stdout.is_empty(), "halfcast {args:?} wrote output");
}

#[test]
fn a_word_that_is_neither_a_command_nor_a_file_lists_the_commands() {
    for (word, near) in [
        ("frobnicate", ""),
        ("xyzzy-42", ""),
        ("rendr", " (did you mean render?)"),
        ("serv", " (did you mean serve?)"),
        ("glpyhs", " (did you mean glyphs?)"),
    ] {
        refused(
            &[word],
            2,
            &format!(
                "error: no such command or map: {word}{near}; commands: {COMMANDS} (or a .cub \
                 map file to play)"
            ),
        );
        // With play's flags after it, the same.
        refused(
            &[word, "--fps", "30"],
            2,
            &format!(
                "error: no such command or map: {word}{near}; commands: {COMMANDS} (or a .cub \
                 map file to play)"
            ),
        );
    }
    // Named as a map (`play WORD`), or written as a file (a folder or an extension), it is a
    // map that cannot be read, as before.
    for args in [
        &["play", "frobnicate"][..],
        &["no-such-level.cub"],
        &["maps/no-such-level"],
        &["maps/no-such-level.cub", "--fps", "30"],
    ] {
        let out = halfcast(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        let word = args[usize::from(args[0] == "play")];
        assert!(
            stderr.starts_with(&format!("error: {word}: cannot read the file: ")),
            "{args:?}: {stderr}"
        );
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
    }
}

#[test]
fn a_size_past_the_range_says_the_range() {
    for command in [
        &["render", "--format", "txt"][..],
        &["trace", "--column", "0"],
    ] {
        for size in [
            "100000x100000",
            "4001x10",
            "10x2001",
            "0x24",
            "80x0",
            "99999999999999999999x3",
        ] {
            let mut args = command.to_vec();
            args.extend(["--size", size]);
            refused(
                &args,
                2,
                &format!(
                    "error: invalid value '{size}' for '--size <SIZE>': size {size} is out of \
                     range (1x1 to 4000x2000)"
                ),
            );
        }
        for size in ["80x", "axb", "80*24", "-5x10", "1.5x3"] {
            let mut args = command.to_vec();
            args.extend(["--size", size]);
            refused(
                &args,
                2,
                &format!(
                    "error: invalid value '{size}' for '--size <SIZE>': '{size}' is not COLSxROWS \
                     (two whole numbers, such as 80x24)"
                ),
            );
        }
    }
    // The largest size is accepted.
    let out = halfcast(&[
        "render",
        "--size",
        "4000x2000",
        "--format",
        "txt",
        "-o",
        "/dev/null",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The map (`None`: the embedded one), loaded as the binary loads it.
fn world(map: Option<&str>) -> World {
    match map {
        None => World::default_world(),
        Some(path) => World::from_file(&root().join(path), false).unwrap().0,
    }
}

/// How the binary names a map in messages: its file's name.
fn shown_name(map: Option<&str>) -> String {
    let path = std::path::Path::new(map.unwrap_or("maps/default.cub"));
    path.file_name().unwrap().to_string_lossy().into_owned()
}

/// The first cell of `world` (row by row) for which `pick` holds.
fn first_cell(world: &World, pick: impl Fn(Cell) -> bool) -> Option<(i64, i64)> {
    let (w, h) = (world.map.width as i64, world.map.height as i64);
    (0..h)
        .flat_map(|j| (0..w).map(move |i| (i, j)))
        .find(|&(i, j)| pick(world.map.cell(i, j)))
}

/// Every command that takes `--pos`, with `map` and `pos`: render, trace and the game (the
/// default command, `play` and `record`, which refuse before they need a terminal).
fn commands_at(map: Option<&str>, pos: &str, out: &str) -> Vec<Vec<String>> {
    let with = |words: &[&str]| {
        let mut v: Vec<String> = words.iter().map(|w| (*w).to_owned()).collect();
        if let Some(m) = map {
            v.insert(usize::from(!words.is_empty()), m.to_owned());
        }
        v.extend(["--pos".to_owned(), pos.to_owned()]);
        v
    };
    vec![
        with(&["render", "--size", "20x6", "--format", "txt"]),
        with(&["trace", "--column", "1", "--size", "20x6"]),
        with(&[]),
        with(&["play"]),
        with(&["record", "-o", out]),
    ]
}

#[test]
fn a_position_off_the_map_or_in_a_wall_names_the_maps_size() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("never.hcr");
    let out = out.to_str().unwrap();
    for map in [
        None,
        Some("maps/level1.cub"),
        Some("maps/level3.cub"),
        Some("maps/heights.cub"),
    ] {
        let w = world(map);
        let (name, width, height) = (shown_name(map), w.map.width, w.map.height);
        let size = format!("{width}x{height} cells, x 0 to {width} and y 0 to {height}");
        let mut cases = vec![
            (
                format!("{}.5,1.5", width + 3),
                format!("is outside the map: {name} is {size}"),
            ),
            (
                "-0.25,2.5".to_owned(),
                format!("is outside the map: {name} is {size}"),
            ),
            (
                format!("1.5,{}", height as f64 + 0.5),
                format!("is outside the map: {name} is {size}"),
            ),
        ];
        let (i, j) = first_cell(&w, |c| matches!(c, Cell::Wall(_))).expect("a wall");
        cases.push((
            format!("{i}.5,{j}.5"),
            format!("is inside a wall, cell ({i},{j}) of {name} ({size}): start in an open cell"),
        ));
        if let Some((i, j)) = first_cell(&w, |c| c == Cell::Void) {
            cases.push((
                format!("{i}.5,{j}.5"),
                format!(
                    "is outside the map's walls, in the void of cell ({i},{j}) of {name} ({size})"
                ),
            ));
        }
        for (pos, problem) in cases {
            for args in commands_at(map, &pos, out) {
                let args: Vec<&str> = args.iter().map(String::as_str).collect();
                refused(&args, 2, &format!("error: --pos {pos} {problem}"));
            }
        }
    }
    assert!(!std::path::Path::new(out).exists());
}

/// `halfcast serve` on a host key in a scratch folder, with `extra` flags; its exit code and
/// standard error.
fn serve(dir: &std::path::Path, extra: &[&str]) -> (Option<i32>, String) {
    let key = dir.join("hk");
    let mut args = vec!["serve", "--host-key", key.to_str().unwrap(), "--db", "none"];
    if !extra.contains(&"--listen") {
        args.extend(["--listen", "127.0.0.1:0"]);
    }
    args.extend_from_slice(extra);
    let out = halfcast(&args);
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn a_port_in_use_is_an_io_failure_and_nothing_is_announced() {
    let dir = tempfile::tempdir().unwrap();
    let taken = TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port();
    let busy = format!("127.0.0.1:{port}");
    for (extra, what) in [
        (
            vec!["--web", &busy],
            format!("cannot serve the web page on {busy}: "),
        ),
        (
            vec!["--metrics", &busy],
            format!("cannot serve metrics on {busy}: "),
        ),
        (
            vec![
                "--listen",
                &busy,
                "--web",
                "127.0.0.1:0",
                "--metrics",
                "127.0.0.1:0",
            ],
            format!("cannot listen on {busy}: "),
        ),
        (
            vec!["--web", "127.0.0.1:0", "--metrics", &busy],
            format!("cannot serve metrics on {busy}: "),
        ),
    ] {
        let (code, stderr) = serve(dir.path(), &extra);
        assert_eq!(code, Some(1), "{extra:?}: {stderr}");
        let last = stderr.lines().last().unwrap_or_default();
        assert!(
            last.starts_with(&format!("error: {what}")),
            "{extra:?}: {stderr}"
        );
        assert!(
            last.to_lowercase().contains("in use"),
            "{extra:?}: {stderr}"
        );
        // Before it: the host key's notes only; no port is announced.
        for line in stderr.lines().filter(|l| !l.starts_with("error: ")) {
            assert!(line.contains("host key"), "{extra:?} announced: {line}");
        }
        assert_eq!(stderr.matches("error: ").count(), 1, "{stderr}");
    }
}
