//! The glyph key inside tmux, which drops octant characters when its host's width table does
//! not know them (tmux 3.3a on Debian 12): pressing U four times goes quadrant, sextant, half
//! (octant skipped, with one note saying why), quadrant. The game never sends an octant, and
//! what tmux shows is what the game meant, row by row. The recording keeps the settings, so it
//! replays the same outside tmux. Skipped with a notice when tmux is not installed.

use std::process::Command;
use std::thread;
use std::time::{Duration, Instant};

use unicode_width::UnicodeWidthStr;

use crate::tmux::{Tmux, PATIENCE};

const SIZE: (u16, u16) = (80, 24);

fn count_in(text: &str, range: std::ops::RangeInclusive<u32>) -> usize {
    text.chars()
        .filter(|c| range.contains(&u32::from(*c)))
        .count()
}

fn octants(text: &str) -> usize {
    count_in(text, 0x1CD00..=0x1CDE5)
}

fn sextants(text: &str) -> usize {
    count_in(text, 0x1FB00..=0x1FB3B)
}

/// Quadrants that only the quadrant setting draws (`▖ ▗ ▘ ▙ ▚ ▛ ▜ ▝ ▞ ▟`).
fn quadrants(text: &str) -> usize {
    count_in(text, 0x2596..=0x259F)
}

/// Everything the game wrote to the pane so far (tmux's `pipe-pane` log).
fn sent(log: &std::path::Path) -> String {
    String::from_utf8_lossy(&std::fs::read(log).unwrap_or_default()).into_owned()
}

/// Waits until the game's output after byte `from` of the log holds `what`.
fn wait_sent(log: &std::path::Path, from: usize, what: &str, ok: impl Fn(&str) -> bool) {
    let start = Instant::now();
    while !ok(sent(log).get(from..).unwrap_or_default()) {
        assert!(start.elapsed() < PATIENCE, "gave up waiting for {what}");
        thread::sleep(Duration::from_millis(50));
    }
}

/// The rows above the status line: as tmux shows them, and as the game meant them (its bytes
/// through a terminal model that gives every block character one column).
fn rows_shown_and_meant(tmux: &Tmux, log: &std::path::Path) -> (Vec<String>, Vec<String>) {
    let shown: Vec<String> = tmux
        .capture(false)
        .lines()
        .take(usize::from(SIZE.1 - 1))
        .map(|l| l.trim_end().to_owned())
        .collect();
    let mut model = vt100::Parser::new(SIZE.1, SIZE.0, 0);
    model.process(&std::fs::read(log).expect("pipe-pane log"));
    let meant = model
        .screen()
        .rows(0, SIZE.0)
        .take(usize::from(SIZE.1 - 1))
        .map(|l| l.trim_end().to_owned())
        .collect();
    (shown, meant)
}

/// Waits for a quiet moment where tmux's rows are the game's rows, each as wide.
fn assert_ungarbled(tmux: &Tmux, log: &std::path::Path, when: &str) {
    let start = Instant::now();
    loop {
        let (shown, meant) = rows_shown_and_meant(tmux, log);
        if shown == meant {
            for (y, row) in shown.iter().enumerate() {
                // The view and the panes beside it reach the right edge on every row.
                assert_eq!(row.width(), usize::from(SIZE.0), "{when}: row {y}: {row}");
            }
            return;
        }
        if start.elapsed() > PATIENCE {
            let diff: Vec<String> = shown
                .iter()
                .zip(&meant)
                .enumerate()
                .filter(|(_, (a, b))| a != b)
                .map(|(y, (a, b))| {
                    format!(
                        "row {y}: tmux ({} wide) {a}\n       meant ({} wide) {b}",
                        a.width(),
                        b.width()
                    )
                })
                .collect();
            panic!("{when}: tmux garbled the screen:\n{}", diff.join("\n"));
        }
        thread::sleep(Duration::from_millis(100));
    }
}

#[test]
fn inside_tmux_the_glyph_key_skips_octants_and_the_recording_replays_the_same_anywhere() {
    let Some(tmux) = Tmux::new("glyphs") else {
        return;
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let log = dir.path().join("pane.log");
    let hcr = dir.path().join("run.hcr");
    let bin = env!("CARGO_BIN_EXE_halfcast");
    let config = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/no-such-dir");
    // The game waits for Enter, so the pane's log starts before its first byte.
    let script = r#"read go; exec "$0" record --fps 20 --seed 1 -o "$1""#;
    let config = format!("XDG_CONFIG_HOME={config}");
    tmux.start(
        (80, 24),
        &["TERM=xterm-256color", "COLORTERM=truecolor", &config],
        &["sh", "-c", script, bin, hcr.to_str().expect("utf-8 path")],
    );
    let piped = tmux.run(&[
        "pipe-pane",
        "-t",
        "t",
        &format!("cat >> '{}'", log.display()),
    ]);
    assert!(piped.status.success(), "{piped:?}");
    tmux.run(&["send-keys", "-t", "t", "Enter"]);
    tmux.wait_for("the first frame", |s| s.contains("q quit"));
    assert_ungarbled(&tmux, &log, "half-blocks");

    // U: quadrant.
    let from = sent(&log).len();
    tmux.run(&["send-keys", "-t", "t", "u"]);
    wait_sent(&log, from, "quadrants", |s| quadrants(s) > 20);
    assert_ungarbled(&tmux, &log, "quadrant");
    // U: sextant.
    let from = sent(&log).len();
    tmux.run(&["send-keys", "-t", "t", "u"]);
    wait_sent(&log, from, "sextants", |s| sextants(s) > 20);
    assert_ungarbled(&tmux, &log, "sextant");
    // U: not octant but half-blocks again, and the status line says why.
    tmux.run(&["send-keys", "-t", "t", "u"]);
    tmux.wait_for("the note", |s| {
        s.contains("octants off: tmux drops them; --glyphs octant forces")
    });
    // U: quadrant again, once the note has gone.
    tmux.wait_for("the note to go", |s| s.contains("q quit"));
    let from = sent(&log).len();
    tmux.run(&["send-keys", "-t", "t", "u"]);
    wait_sent(&log, from, "quadrants again", |s| quadrants(s) > 20);
    assert_ungarbled(&tmux, &log, "quadrant again");
    assert_eq!(octants(&sent(&log)), 0, "the game sent octants into tmux");

    tmux.run(&["send-keys", "-t", "t", "q"]);
    let start = Instant::now();
    while !std::fs::read_to_string(&hcr).is_ok_and(|t| t.contains("{\"end\":")) {
        assert!(start.elapsed() < PATIENCE, "no recording written");
        thread::sleep(Duration::from_millis(50));
    }
    let text = std::fs::read_to_string(&hcr).unwrap();
    let set: Vec<&str> = text
        .lines()
        .filter(|l| l.contains("\"ui\":\"set_glyphs\""))
        .map(|l| l.split("\"glyphs\":\"").nth(1).unwrap_or_default())
        .collect();
    assert_eq!(
        set,
        ["quadrant\"}", "sextant\"}", "half\"}", "quadrant\"}"],
        "{text}"
    );
    assert!(!text.contains("cycle_glyphs"), "{text}");

    // Replayed outside tmux (and in another multiplexer), the run is the same bytes (at one
    // colour level: the replay command otherwise takes it from TERM).
    let cast = |name: &str, env: &[(&str, &str)]| {
        let out = dir.path().join(name);
        let mut cmd = Command::new(bin);
        cmd.args(["replay", hcr.to_str().unwrap(), "--colors", "truecolor"])
            .args(["--format", "cast", "--out"])
            .arg(&out)
            .env_remove("TMUX");
        for (k, v) in env {
            cmd.env(k, v);
        }
        let run = cmd.output().expect("run halfcast replay");
        assert!(run.status.success(), "{run:?}");
        std::fs::read_to_string(out).expect("cast written")
    };
    let plain = cast("plain.cast", &[("TERM", "xterm-kitty")]);
    let other = cast(
        "other.cast",
        &[("TERM", "screen-256color"), ("TMUX", "/tmp/elsewhere,1,0")],
    );
    assert!(plain == other, "the replay depends on where it runs");
    assert_eq!(octants(&plain), 0);
    assert!(sextants(&plain) > 20 && quadrants(&plain) > 20);
}
