//! Terminal round trips: the real binary in a pseudo-terminal of a fixed size, every output byte
//! kept, and the screen it leaves read back through a terminal model (`vt100`).
//!
//! The child is killed when its [`PtyRun`] is dropped, so a failing test leaves no process behind.
#![cfg(unix)]

use std::io::{Read, Write};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread;
use std::time::{Duration, Instant};

use halfcast::termframe::TermFrame;
use portable_pty::{native_pty_system, Child, CommandBuilder, ExitStatus, MasterPty, PtySize};

/// A hang guard only (tests never assert on speed): generous for a loaded CI machine.
pub const PATIENCE: Duration = Duration::from_secs(60);

/// The keyboard probe the game sends at start-up (primary device attributes).
const PROBE: &[u8] = b"\x1b[c";

/// The probe answer of a terminal without the kitty keyboard protocol.
pub const NO_KITTY: &[u8] = b"\x1b[?62;22c";

/// The probe answer of a terminal with it (current flags 0, then device attributes).
pub const KITTY: &[u8] = b"\x1b[?0u\x1b[?62;22c";

/// The start and end of a synchronized frame (DEC private mode 2026).
const SYNC_BEGIN: &[u8] = b"\x1b[?2026h";
const SYNC_END: &[u8] = b"\x1b[?2026l";

/// Leaving the alternate screen: the last thing a session does before it exits.
pub const LEAVE_ALT_SCREEN: &[u8] = b"\x1b[?1049l";

/// One run of the binary in its own pseudo-terminal.
pub struct PtyRun {
    pub master: Box<dyn MasterPty + Send>,
    writer: Box<dyn Write + Send>,
    child: Box<dyn Child + Send + Sync>,
    out: Arc<Mutex<Vec<u8>>>,
    paused: Arc<AtomicBool>,
    reader: Option<thread::JoinHandle<()>>,
    answered: bool,
    /// What the "terminal" answers to the start-up keyboard probe.
    pub probe_answer: &'static [u8],
    parser: vt100::Parser,
    parsed: usize,
}

impl PtyRun {
    /// Starts `halfcast ARGS` from the project root in a `cols` × `rows` terminal that claims
    /// 24-bit colour.
    pub fn spawn(args: &[&str], size: (u16, u16)) -> Self {
        Self::spawn_with(args, size, &[])
    }

    /// [`PtyRun::spawn`] with extra environment variables.
    pub fn spawn_with(args: &[&str], size: (u16, u16), env: &[(&str, &str)]) -> Self {
        let pair = native_pty_system()
            .openpty(PtySize {
                rows: size.1,
                cols: size.0,
                pixel_width: 0,
                pixel_height: 0,
            })
            .expect("openpty");
        let mut cmd = CommandBuilder::new(env!("CARGO_BIN_EXE_halfcast"));
        cmd.args(args);
        cmd.cwd(env!("CARGO_MANIFEST_DIR"));
        cmd.env("TERM", "xterm-256color");
        cmd.env("COLORTERM", "truecolor");
        for (k, v) in env {
            cmd.env(k, v);
        }
        let child = pair.slave.spawn_command(cmd).expect("spawn halfcast");
        drop(pair.slave);
        let mut reader = pair.master.try_clone_reader().expect("pty reader");
        let writer = pair.master.take_writer().expect("pty writer");
        let out = Arc::new(Mutex::new(Vec::new()));
        let paused = Arc::new(AtomicBool::new(false));
        let (sink, hold) = (Arc::clone(&out), Arc::clone(&paused));
        let reader = thread::spawn(move || {
            let mut buf = [0u8; 4096];
            loop {
                while hold.load(Ordering::SeqCst) {
                    thread::sleep(Duration::from_millis(10));
                }
                match reader.read(&mut buf) {
                    Ok(0) | Err(_) => break,
                    Ok(n) => sink.lock().unwrap().extend_from_slice(&buf[..n]),
                }
            }
        });
        Self {
            master: pair.master,
            writer,
            child,
            out,
            paused,
            reader: Some(reader),
            answered: false,
            probe_answer: NO_KITTY,
            parser: vt100::Parser::new(size.1, size.0, 0),
            parsed: 0,
        }
    }

    /// Everything the child wrote so far.
    pub fn bytes(&self) -> Vec<u8> {
        self.out.lock().unwrap().clone()
    }

    /// The child's process id.
    pub fn pid(&self) -> i32 {
        self.child.process_id().expect("pid") as i32
    }

    /// Types `keys` into the terminal.
    pub fn send(&mut self, keys: &[u8]) {
        self.writer.write_all(keys).unwrap();
        self.writer.flush().unwrap();
    }

    /// Stops (or resumes) reading the child's output, like a terminal nobody drains: once the
    /// pty's buffer is full the child's writes block.
    pub fn pause_reading(&self, paused: bool) {
        self.paused.store(paused, Ordering::SeqCst);
    }

    /// Answers the start-up keyboard probe with [`PtyRun::probe_answer`] (by default like a
    /// terminal without the kitty protocol), so the child does not wait for the probe's timeout.
    pub fn answer_probe(&mut self) {
        if !self.answered && contains(&self.bytes(), PROBE) {
            self.send(self.probe_answer);
            self.answered = true;
        }
    }

    /// Polls until `ok` holds for the output so far (answering the probe meanwhile).
    pub fn wait_for(&mut self, what: &str, ok: impl Fn(&[u8]) -> bool) {
        let start = Instant::now();
        loop {
            self.answer_probe();
            if ok(&self.bytes()) {
                return;
            }
            assert!(start.elapsed() < PATIENCE, "gave up waiting for {what}");
            thread::sleep(Duration::from_millis(20));
        }
    }

    /// The terminal model after all output so far (only new output is parsed each time), held
    /// at the last whole frame: a terminal that knows DEC 2026 (`vt100` does not) shows nothing of
    /// a synchronized frame until its end marker, so a read that ends mid-frame is not a screen.
    pub fn screen(&mut self) -> &vt100::Screen {
        let out = self.out.lock().unwrap();
        let new = &out[self.parsed..];
        let whole = match (last_index(new, SYNC_BEGIN), last_index(new, SYNC_END)) {
            (Some(begin), end) if end.is_none_or(|end| end < begin) => begin,
            _ => new.len(),
        };
        self.parser.process(&new[..whole]);
        self.parsed += whole;
        drop(out);
        self.parser.screen()
    }

    /// Polls until `ok` holds for the screen the output draws so far.
    pub fn wait_for_screen(&mut self, what: &str, ok: impl Fn(&vt100::Screen) -> bool) {
        let start = Instant::now();
        loop {
            self.answer_probe();
            let screen = self.screen();
            if ok(screen) {
                return;
            }
            assert!(
                start.elapsed() < PATIENCE,
                "gave up waiting for {what}; screen:\n{}",
                screen.contents()
            );
            thread::sleep(Duration::from_millis(50));
        }
    }

    /// The exit status if the child has exited.
    pub fn try_wait(&mut self) -> Option<ExitStatus> {
        self.child.try_wait().expect("try_wait")
    }

    /// Waits for the child to exit (answering the probe meanwhile), then for its last output.
    pub fn wait_exit(&mut self) -> ExitStatus {
        let start = Instant::now();
        let status = loop {
            self.answer_probe();
            if let Some(st) = self.child.try_wait().expect("try_wait") {
                break st;
            }
            assert!(start.elapsed() < PATIENCE, "halfcast did not exit");
            thread::sleep(Duration::from_millis(20));
        };
        self.pause_reading(false);
        // The reader ends at end of file once the child's side of the pty is closed.
        let reader = self.reader.take().expect("reader joined once");
        let start = Instant::now();
        while !reader.is_finished() && start.elapsed() < Duration::from_secs(5) {
            thread::sleep(Duration::from_millis(10));
        }
        if reader.is_finished() {
            reader.join().expect("reader thread");
        }
        status
    }
}

impl Drop for PtyRun {
    fn drop(&mut self) {
        if matches!(self.child.try_wait(), Ok(None)) {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

/// Whether `needle` occurs in `hay`.
pub fn contains(hay: &[u8], needle: &[u8]) -> bool {
    hay.windows(needle.len()).any(|w| w == needle)
}

/// Where `needle` last occurs in `hay`.
pub fn last_index(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).rposition(|w| w == needle)
}

/// The screen a session showed last: its output up to where it left the alternate screen,
/// through a `cols` × `rows` terminal model.
pub fn final_screen(bytes: &[u8], size: (u16, u16)) -> TermFrame {
    let end = last_index(bytes, LEAVE_ALT_SCREEN).unwrap_or(bytes.len());
    let mut term = vt100::Parser::new(size.1, size.0, 0);
    term.process(&bytes[..end]);
    halfcast::termframe::from_parser(&term)
}

/// The terminal size a replay file was recorded at.
pub fn replay_size(file: &Path) -> (u16, u16) {
    let text = std::fs::read_to_string(file).expect("read replay");
    halfcast::replay::Replay::parse(&file.display().to_string(), &text)
        .expect("valid replay")
        .header
        .size
}

/// Shows `file` on screen (`halfcast replay FILE [--until-frame N]`) in a terminal of the
/// replay's size, lets it run to its end and returns the screen it showed last. Frame pacing
/// cannot change the result: every frame's bytes arrive, in order, whatever the timing.
pub fn replay_on_screen(file: &str, until_frame: Option<usize>) -> TermFrame {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    let size = replay_size(&path);
    let until = until_frame.map(|n| n.to_string());
    let mut args = vec!["replay", file];
    if let Some(n) = &until {
        args.extend(["--until-frame", n.as_str()]);
    }
    let mut run = PtyRun::spawn(&args, size);
    let status = run.wait_exit();
    let bytes = run.bytes();
    assert!(
        status.success(),
        "halfcast {args:?} failed: {status:?}\n{}",
        String::from_utf8_lossy(&bytes)
    );
    assert!(
        contains(&bytes, LEAVE_ALT_SCREEN),
        "the session never restored the terminal"
    );
    final_screen(&bytes, size)
}
