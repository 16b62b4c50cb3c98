//! End-to-end: the real binary in a real pseudo-terminal, read back through a VT100 parser.
//! Start at 160×48, check the first screen, walk forward, quit, check the terminal is restored.
#![cfg(unix)]

use std::io::{Read, Write};
use std::sync::{Arc, Mutex};
use std::thread;
use std::time::{Duration, Instant};

use portable_pty::{native_pty_system, Child, CommandBuilder, MasterPty, PtySize};

const COLS: u16 = 160;
const ROWS: u16 = 48;

/// A hang guard only (the test never asserts on speed): generous for a loaded CI machine.
const PATIENCE: Duration = Duration::from_secs(60);

/// Probe answer of a terminal without the kitty keyboard protocol.
const NO_KITTY: &[u8] = b"\x1b[?62;22c";

/// Probe answer of a terminal with it (current flags 0, then device attributes).
const KITTY: &[u8] = b"\x1b[?0u\x1b[?62;22c";

struct Session {
    master: Box<dyn MasterPty + Send>,
    writer: Box<dyn Write + Send>,
    child: Box<dyn Child + Send + Sync>,
    out: Arc<Mutex<Vec<u8>>>,
    answered_da1: bool,
    parser: vt100::Parser,
    parsed: usize,
    /// What the "terminal" answers to the keyboard probe.
    probe_answer: &'static [u8],
    /// The line discipline before the game started (to compare after it exits).
    cooked: nix::sys::termios::Termios,
}

impl Session {
    fn spawn(args: &[&str]) -> Self {
        Self::spawn_with(args, &[])
    }

    fn spawn_with(args: &[&str], env: &[(&str, &str)]) -> Self {
        let pty = native_pty_system();
        let pair = pty
            .openpty(PtySize {
                rows: ROWS,
                cols: COLS,
                pixel_width: 0,
                pixel_height: 0,
            })
            .expect("openpty");
        let cooked = pair.master.get_termios().expect("termios");
        let mut cmd = CommandBuilder::new(env!("CARGO_BIN_EXE_halfcast"));
        cmd.args(args);
        cmd.env("TERM", "xterm-256color");
        cmd.env("COLORTERM", "truecolor");
        for (k, v) in env {
            cmd.env(k, v);
        }
        let child = pair.slave.spawn_command(cmd).expect("spawn halfcast");
        drop(pair.slave);
        let mut reader = pair.master.try_clone_reader().expect("reader");
        let writer = pair.master.take_writer().expect("writer");
        let out = Arc::new(Mutex::new(Vec::new()));
        let sink = Arc::clone(&out);
        thread::spawn(move || {
            let mut buf = [0u8; 65536];
            while let Ok(n) = reader.read(&mut buf) {
                if n == 0 {
                    break;
                }
                sink.lock().unwrap().extend_from_slice(&buf[..n]);
            }
        });
        Self {
            master: pair.master,
            writer,
            child,
            out,
            answered_da1: false,
            parser: vt100::Parser::new(ROWS, COLS, 0),
            parsed: 0,
            probe_answer: NO_KITTY,
            cooked,
        }
    }

    fn bytes(&self) -> Vec<u8> {
        self.out.lock().unwrap().clone()
    }

    /// The screen so far (only new output is parsed each time).
    fn screen(&mut self) -> &vt100::Parser {
        let new = self.out.lock().unwrap()[self.parsed..].to_vec();
        self.parsed += new.len();
        self.parser.process(&new);
        &self.parser
    }

    /// Answers the start-up keyboard probe (by default like a terminal without the kitty
    /// protocol: primary device attributes only), so it does not wait for its timeout.
    fn answer_probe(&mut self) {
        if !self.answered_da1 && contains(&self.bytes(), b"\x1b[c") {
            self.writer.write_all(self.probe_answer).unwrap();
            self.writer.flush().unwrap();
            self.answered_da1 = true;
        }
    }

    fn wait_for(&mut self, what: &str, ok: impl Fn(&vt100::Screen) -> bool) {
        let start = Instant::now();
        loop {
            self.answer_probe();
            if ok(self.screen().screen()) {
                return;
            }
            let contents = self.screen().screen().contents();
            assert!(
                start.elapsed() < PATIENCE,
                "gave up waiting for {what}; screen:\n{contents}"
            );
            thread::sleep(Duration::from_millis(50));
        }
    }

    fn send(&mut self, keys: &[u8]) {
        self.writer.write_all(keys).unwrap();
        self.writer.flush().unwrap();
    }
}

fn contains(hay: &[u8], needle: &[u8]) -> bool {
    hay.windows(needle.len()).any(|w| w == needle)
}

fn last_index(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).rposition(|w| w == needle)
}

/// The colours of every cell in the top-left view region.
fn view_colours(s: &vt100::Screen) -> Vec<(vt100::Color, vt100::Color)> {
    let mut v = Vec::new();
    for row in 0..40 {
        for col in 0..100 {
            let c = s.cell(row, col).unwrap();
            v.push((c.fgcolor(), c.bgcolor()));
        }
    }
    v
}

fn status_line(s: &vt100::Screen) -> String {
    s.contents().lines().last().unwrap_or_default().to_owned()
}

#[test]
fn play_start_walk_quit_restores_the_terminal() {
    let mut s = Session::spawn(&["play", "--fps", "30"]);
    let before = s.cooked.clone();

    s.wait_for("the first whole frame", |sc| {
        let text = sc.contents();
        text.contains("(15,4)")
            && text.contains("sideDistX")
            && text.contains(" map ")
            && status_line(sc).contains("q quit")
    });
    let sc = s.screen();
    let sc = sc.screen();
    // The view: half blocks in 24-bit colour.
    // (The encoder may draw a cell of one colour as a space with that background.)
    let cell = sc.cell(10, 10).unwrap();
    assert!(
        matches!(cell.contents().as_str(), "▀" | "▄" | "█" | " " | ""),
        "{:?}",
        cell.contents()
    );
    assert!(
        matches!(cell.bgcolor(), vt100::Color::Rgb(..)),
        "{:?} {:?}",
        cell.fgcolor(),
        cell.bgcolor()
    );
    let half_blocks = (0..40u16)
        .flat_map(|y| (0..100u16).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let c = sc.cell(y, x).unwrap();
            c.contents() == "▀" && matches!(c.fgcolor(), vt100::Color::Rgb(..))
        })
        .count();
    assert!(
        half_blocks > 1000,
        "only {half_blocks} truecolor ▀ cells in the view"
    );
    // The minimap is half blocks too, inside its bordered pane on the right.
    let text = sc.contents();
    let map_row = text
        .lines()
        .position(|l| l.contains("╭ map"))
        .expect("map pane");
    let map_col = text
        .lines()
        .nth(map_row)
        .unwrap()
        .chars()
        .position(|c| c == '╭')
        .unwrap();
    let inner = sc.cell(map_row as u16 + 3, map_col as u16 + 3).unwrap();
    assert_eq!(inner.contents(), "▀");
    // The debug pane lists the centre ray's steps with cells (x,y).
    assert!(text.contains("  1 (15,4)"), "{text}");
    assert!(text.contains("hit"), "{text}");
    let status = status_line(sc);
    assert!(status.contains("pos 15.50,5.50"), "{status}");
    assert!(status.contains("fps"), "{status}");

    let first_view = view_colours(sc);
    for _ in 0..4 {
        s.send(b"w");
        thread::sleep(Duration::from_millis(60));
    }
    s.wait_for("the view to change after walking", |sc| {
        view_colours(sc) != first_view && !status_line(sc).contains("pos 15.50,5.50")
    });

    s.send(b"q");
    let start = Instant::now();
    let status = loop {
        if let Some(st) = s.child.try_wait().unwrap() {
            break st;
        }
        assert!(start.elapsed() < PATIENCE, "halfcast did not exit after q");
        thread::sleep(Duration::from_millis(20));
    };
    assert!(status.success(), "exit status {status:?}");
    // Let the reader drain what the child wrote last.
    thread::sleep(Duration::from_millis(200));
    let out = s.bytes();
    let entered = last_index(&out, b"\x1b[?1049h").expect("entered the alternate screen");
    let left = last_index(&out, b"\x1b[?1049l").expect("left the alternate screen");
    assert!(left > entered);
    let hidden = last_index(&out, b"\x1b[?25l").expect("hid the cursor");
    let shown = last_index(&out, b"\x1b[?25h").expect("showed the cursor");
    assert!(shown > hidden);
    // Nothing but mode resets after leaving the alternate screen.
    assert!(!contains(&out[left..], "▀".as_bytes()));
    // Raw mode is off again: the line discipline is as it was before the game started.
    let after = s.master.get_termios().expect("termios");
    assert_eq!(before.local_flags, after.local_flags);
    assert_eq!(before.input_flags, after.input_flags);
}

#[test]
fn not_a_terminal_is_a_clear_error_with_exit_code_2() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .arg("play")
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("is not a terminal"), "{err}");
    assert!(out.stdout.is_empty());
}

#[test]
fn sigterm_restores_the_terminal_and_exits() {
    let mut s = Session::spawn(&["play"]);
    let before = s.cooked.clone();
    s.wait_for("the first frame", |sc| sc.contents().contains("sideDistX"));
    let pid = s.child.process_id().expect("pid") as i32;
    nix::sys::signal::kill(
        nix::unistd::Pid::from_raw(pid),
        nix::sys::signal::Signal::SIGTERM,
    )
    .unwrap();
    let start = Instant::now();
    let status = loop {
        if let Some(st) = s.child.try_wait().unwrap() {
            break st;
        }
        assert!(start.elapsed() < PATIENCE, "halfcast ignored SIGTERM");
        thread::sleep(Duration::from_millis(20));
    };
    assert_eq!(status.exit_code(), 128 + 15);
    thread::sleep(Duration::from_millis(200));
    let out = s.bytes();
    assert!(last_index(&out, b"\x1b[?1049l") > last_index(&out, b"\x1b[?1049h"));
    let after = s.master.get_termios().expect("termios");
    assert_eq!(before.local_flags, after.local_flags);
}

fn pos_of(sc: &vt100::Screen) -> String {
    let st = status_line(sc);
    st.split("pos ")
        .nth(1)
        .and_then(|r| r.split_whitespace().next())
        .unwrap_or_default()
        .to_owned()
}

#[test]
fn kitty_keyboard_protocol_holds_until_release() {
    let mut s = Session::spawn(&["play"]);
    s.probe_answer = KITTY;
    s.wait_for("the first frame in kitty mode", |sc| {
        status_line(sc).contains("kitty keys") && status_line(sc).contains("q quit")
    });
    // The game asked for press/repeat/release events with all keys as escape codes.
    let out = s.bytes();
    // 15 = disambiguate | event types | alternate keys | all keys as escape codes.
    assert!(contains(&out, b"\x1b[>15u"), "kitty flags not pushed");
    let start_pos = pos_of(s.screen().screen());
    // Press w (no repeats are sent): the player keeps walking while it is held...
    s.send(b"\x1b[119;1:1u");
    s.wait_for("walking", |sc| pos_of(sc) != start_pos);
    let walking = pos_of(s.screen().screen());
    s.wait_for("still walking", |sc| pos_of(sc) != walking);
    // ...and stops at the release.
    s.send(b"\x1b[119;1:3u");
    let start = Instant::now();
    loop {
        let a = pos_of(s.screen().screen());
        thread::sleep(Duration::from_millis(300));
        if pos_of(s.screen().screen()) == a {
            break;
        }
        assert!(
            start.elapsed() < PATIENCE,
            "still walking after the release"
        );
    }
    s.send(b"\x1b[113;1:1u");
    let start = Instant::now();
    let status = loop {
        if let Some(st) = s.child.try_wait().unwrap() {
            break st;
        }
        assert!(start.elapsed() < PATIENCE, "q (kitty-encoded) did not quit");
        thread::sleep(Duration::from_millis(20));
    };
    assert!(status.success());
    thread::sleep(Duration::from_millis(200));
    // The keyboard mode was popped before leaving.
    assert!(contains(&s.bytes(), b"\x1b[<1u"));
}

/// Debug builds panic after the first frame when HALFCAST_TEST_PANIC is set.
#[cfg(debug_assertions)]
#[test]
fn a_panic_restores_the_terminal_before_the_message() {
    let mut s = Session::spawn_with(&["play"], &[("HALFCAST_TEST_PANIC", "1")]);
    let before = s.cooked.clone();
    let start = Instant::now();
    let status = loop {
        s.answer_probe();
        if let Some(st) = s.child.try_wait().unwrap() {
            break st;
        }
        assert!(start.elapsed() < PATIENCE, "no panic exit");
        thread::sleep(Duration::from_millis(20));
    };
    assert!(!status.success());
    thread::sleep(Duration::from_millis(200));
    let out = s.bytes();
    let left = last_index(&out, b"\x1b[?1049l").expect("left the alternate screen");
    let message = last_index(&out, b"HALFCAST_TEST_PANIC is set").expect("panic message shown");
    assert!(
        left < message,
        "the message must come after the restore, on the main screen"
    );
    assert!(last_index(&out, b"\x1b[?25h") > last_index(&out, b"\x1b[?25l"));
    // The buffered frame that was being drawn is not spilled after the restore.
    assert!(!contains(&out[left..], "\u{2580}".as_bytes()));
    let after = s.master.get_termios().expect("termios");
    assert_eq!(before.local_flags, after.local_flags);
}
