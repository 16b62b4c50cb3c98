//! End-to-end under tmux (the "must show" scenario): 160×48, first screen, walk, quit.
//! Skipped with a notice when tmux is not installed.

use std::process::Command;
use std::thread;
use std::time::{Duration, Instant};

use crate::tmux::Tmux;

fn status(screen: &str) -> String {
    screen
        .lines()
        .rev()
        .find(|l| !l.trim().is_empty())
        .unwrap_or_default()
        .to_owned()
}

#[test]
fn under_tmux_the_first_screen_walks_and_quits_cleanly() {
    let Some(tmux) = Tmux::new("test") else {
        return;
    };
    let bin = env!("CARGO_BIN_EXE_halfcast");
    // After the game, the shell reports its exit code and the terminal modes, then waits.
    let script = r#""$0"; echo "EXIT=$?"; stty -a; exec sleep 600"#;
    tmux.start(
        (160, 48),
        &["COLORTERM=truecolor"],
        &["sh", "-c", script, bin],
    );

    let first = tmux.wait_for("the first whole frame", |s| {
        s.contains("sideDistY") && s.contains("hit (15,0)") && status(s).contains("q quit")
    });
    assert!(first.contains("╭ map"), "{first}");
    assert!(status(&first).contains("pos 15.50,5.50"), "{first}");
    let coloured = tmux.capture(true);
    assert!(coloured.contains("▀"));
    assert!(
        coloured.contains("\x1b[38;2;"),
        "no 24-bit foreground colours"
    );
    assert!(coloured.contains("48;2;"), "no 24-bit background colours");

    for _ in 0..5 {
        tmux.run(&["send-keys", "-t", "t", "w"]);
        thread::sleep(Duration::from_millis(80));
    }
    tmux.wait_for("the player to move", |s| {
        let st = status(s);
        st.contains("pos ") && !st.contains("pos 15.50,5.50")
    });

    tmux.run(&["send-keys", "-t", "t", "q"]);
    let after = tmux.wait_for("the game to exit and stty to report", |s| {
        s.contains("EXIT=") && s.contains("icanon") && s.contains("isig") && s.contains("echo")
    });
    assert!(after.contains("EXIT=0"), "{after}");
    // Cooked mode again: canonical input and echo are back on.
    let modes: Vec<&str> = after.split_whitespace().collect();
    for flag in ["icanon", "echo", "isig"] {
        assert!(modes.contains(&flag), "{flag} is off:\n{after}");
    }
    // Back on the main screen with a visible cursor.
    let state = tmux.text(&[
        "display-message",
        "-p",
        "-t",
        "t",
        "#{alternate_on} #{cursor_flag}",
    ]);
    assert_eq!(state.trim(), "0 1");
}

/// Closing the window (tmux kills the session: the terminal hangs up) ends the game promptly,
/// even though the terminal library's reader would spin on the dead terminal forever.
#[test]
fn a_closed_terminal_ends_the_game() {
    let Some(tmux) = Tmux::new("hangup") else {
        return;
    };
    let bin = env!("CARGO_BIN_EXE_halfcast");
    // Two arguments: tmux runs the game directly, so the pane's process is the game.
    tmux.start((100, 30), &[], &[bin, "play"]);
    tmux.wait_for("the first frame", |s| status(s).contains("q quit"));
    let pid = tmux.text(&["display-message", "-p", "-t", "t", "#{pane_pid}"]);
    let pid = pid.trim().to_owned();
    assert!(!pid.is_empty());
    tmux.run(&["kill-session", "-t", "t"]);
    let alive = || {
        std::fs::read_to_string(format!("/proc/{pid}/stat"))
            .is_ok_and(|s| s.split_whitespace().nth(2).is_none_or(|st| st != "Z"))
    };
    let start = Instant::now();
    while alive() && start.elapsed() < Duration::from_secs(10) {
        thread::sleep(Duration::from_millis(50));
    }
    let still = alive();
    if still {
        let _ = Command::new("kill").args(["-9", &pid]).status();
    }
    assert!(
        !still,
        "the game (pid {pid}) kept running after its terminal closed"
    );
}

/// (x, y, angle): the position from the status line ("pos 15.50,5.50"), the facing from the
/// ray pane's centre ray ("rayDir = (0.00, -1.00)", kept at the top of a cut pane), since at
/// 80 columns the game's figures leave no room for the angle on the status line.
fn pose(screen: &str) -> (f64, f64, f64) {
    let line = status(screen);
    let i = line
        .find("pos ")
        .unwrap_or_else(|| panic!("no pos: {line}"));
    let pos: String = line[i + 4..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || matches!(c, '.' | ','))
        .collect();
    let (x, y) = pos.split_once(',').expect("x,y");
    let ray = screen
        .lines()
        .find_map(|l| {
            let (_, r) = l.split_once("rayDir")?;
            r.split_once('(').map(|(_, r)| r.to_owned())
        })
        .unwrap_or_else(|| panic!("no rayDir:\n{screen}"));
    let (dx, rest) = ray.split_once(", ").expect("dx, dy");
    let dy: String = rest.chars().take_while(|c| *c != ')').collect();
    let (dx, dy): (f64, f64) = (dx.trim().parse().unwrap(), dy.trim().parse().unwrap());
    let angle = (-dy).atan2(dx).to_degrees().rem_euclid(360.0);
    (x.parse().unwrap(), y.parse().unwrap(), angle)
}

/// The issue's setting: 80×24 in tmux with TERM=xterm-256color (tmux sends no key releases).
/// Both panes show, a tap of d turns at most 10° and a tap of w walks at most 0.3 cells, and the
/// help is on screen over the view.
#[test]
fn under_tmux_at_80x24_taps_are_small_steps_and_the_help_shows() {
    let Some(tmux) = Tmux::new("80x24") else {
        return;
    };
    let bin = env!("CARGO_BIN_EXE_halfcast");
    let config = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/no-such-dir");
    let config = format!("XDG_CONFIG_HOME={config}");
    tmux.start((80, 24), &["TERM=xterm-256color", &config], &[bin, "play"]);
    let first = tmux.wait_for("the first frame", |s| {
        s.contains("sideDist") && status(s).contains("q quit")
    });
    assert!(first.contains(" map ") && first.contains("ray"), "{first}");
    let (x0, y0, a0) = pose(&first);

    tmux.run(&["send-keys", "-t", "t", "d"]);
    let turned = tmux.wait_for("a turn", |s| pose(s).2 != a0);
    thread::sleep(Duration::from_millis(800));
    let (_, _, a1) = pose(&tmux.capture(false));
    let t = (a0 - a1 + 540.0).rem_euclid(360.0) - 180.0;
    assert!(t > 0.0 && t <= 10.0, "one tap turned {t} deg:\n{turned}");

    // Face the open floor again, then one tap of w.
    tmux.run(&["send-keys", "-t", "t", "a"]);
    thread::sleep(Duration::from_millis(800));
    tmux.run(&["send-keys", "-t", "t", "w"]);
    tmux.wait_for("a step", |s| pose(s).1 != y0);
    thread::sleep(Duration::from_millis(800));
    let (x2, y2, _) = pose(&tmux.capture(false));
    let walked = (x2 - x0).hypot(y2 - y0);
    assert!(walked > 0.0 && walked <= 0.3, "one tap walked {walked}");

    tmux.run(&["send-keys", "-t", "t", "?"]);
    let help = tmux.wait_for("the help", |s| s.contains("walk forward / back"));
    thread::sleep(Duration::from_millis(300));
    let help_again = tmux.capture(false);
    for needle in ["look straight ahead again", "night mode on / off", "jump"] {
        assert!(help_again.contains(needle), "{needle}:\n{help}");
    }
    tmux.run(&["send-keys", "-t", "t", "q"]);
}

/// tmux 3.3 answers neither XTGETTCAP nor DECRQSS (only DA1): with `TERM=xterm-256color` and
/// no `COLORTERM` the game still starts at once, at 256 colours by the `TERM` rule, and says so.
#[test]
fn under_tmux_xterm_256color_gets_256_by_the_term_rule() {
    let Some(tmux) = Tmux::new("colour") else {
        return;
    };
    let bin = env!("CARGO_BIN_EXE_halfcast");
    tmux.start(
        (140, 30),
        &[],
        &[
            "env",
            "-u",
            "COLORTERM",
            "-u",
            "NO_COLOR",
            "TERM=xterm-256color",
            bin,
            "--fps",
            "30",
        ],
    );
    tmux.wait_for("256 (TERM)", |s| status(s).contains(" 256 (TERM)"));
    let _ = tmux.run(&["send-keys", "-t", "t", "o"]);
    tmux.wait_for("16 (O key)", |s| status(s).contains(" 16 (O key)"));
    let _ = tmux.run(&["send-keys", "-t", "t", "q"]);
}
