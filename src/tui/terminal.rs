//! The terminal session: raw mode, alternate screen, hidden cursor, kitty keys, mouse — and
//! putting all of it back on every way out (normal return, error, panic, signal).

use std::io::{self, IsTerminal, Read};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Once};
use std::time::{Duration, Instant};

use crossterm::event::{
    DisableFocusChange, DisableMouseCapture, EnableFocusChange, EnableMouseCapture,
    KeyboardEnhancementFlags, PopKeyboardEnhancementFlags, PushKeyboardEnhancementFlags,
};
use crossterm::terminal::{
    disable_raw_mode, enable_raw_mode, Clear, ClearType, EndSynchronizedUpdate,
    EnterAlternateScreen, LeaveAlternateScreen,
};
use crossterm::{cursor, execute, queue, style};

use super::tty_out::{write_within, TtyOut};
use crate::encode::ColourChoice;
use crate::ui::colour_query::{query, rules, ReplyScanner, ANSWERBACK_PATIENCE, QUERY_PATIENCE};
use crate::ui::keys::InputMode;

/// How long restoring the terminal may wait for a terminal that does not take bytes.
const RESTORE_PATIENCE: Duration = Duration::from_millis(300);

/// Whether the terminal is currently in game mode (and frames may be written).
static ACTIVE: AtomicBool = AtomicBool::new(false);
static KITTY: AtomicBool = AtomicBool::new(false);
static MOUSE: AtomicBool = AtomicBool::new(false);

/// Why the game cannot use this terminal.
#[derive(Debug, thiserror::Error)]
pub enum TerminalError {
    #[error("{0} is not a terminal; `halfcast play` needs an interactive terminal (try `halfcast render` for headless output)")]
    NotATerminal(&'static str),
    #[error("terminal: {0}")]
    Io(#[from] io::Error),
}

/// Checks that stdin and stdout are a TTY before touching terminal modes.
///
/// # Errors
/// [`TerminalError::NotATerminal`] naming the stream that is not.
pub fn require_tty() -> Result<(), TerminalError> {
    if !io::stdin().is_terminal() {
        return Err(TerminalError::NotATerminal("standard input"));
    }
    if !io::stdout().is_terminal() {
        return Err(TerminalError::NotATerminal("standard output"));
    }
    Ok(())
}

/// An active game-mode terminal; dropping it restores the user's terminal.
pub struct Session {
    out: TtyOut,
    /// The caught signal's number (0 = none): a frame write waiting on a full terminal stops.
    stop: Arc<AtomicUsize>,
    mode: InputMode,
}

impl Session {
    /// Enters game mode: raw, probe kitty keys (before any frame), alternate screen, no cursor.
    /// Frame writes give up once `stop` holds a signal number.
    ///
    /// # Errors
    /// Any I/O error setting the modes (the terminal is restored before returning it).
    pub fn start(mouse: bool, stop: &Arc<AtomicUsize>) -> Result<Self, TerminalError> {
        install_panic_hook();
        enable_raw_mode()?;
        ACTIVE.store(true, Ordering::SeqCst);
        match Self::enter(mouse, Arc::clone(stop)) {
            Ok(s) => Ok(s),
            Err(e) => {
                restore();
                Err(e.into())
            }
        }
    }

    fn enter(mouse: bool, stop: Arc<AtomicUsize>) -> io::Result<Self> {
        // The probe may wait up to 2 s on a terminal that never answers; it runs once, before
        // the alternate screen and outside any synchronized update (some terminals ignore
        // queries inside one).
        let kitty = matches!(
            crossterm::terminal::supports_keyboard_enhancement(),
            Ok(true)
        );
        let mut out = io::stdout();
        execute!(
            out,
            EnterAlternateScreen,
            Clear(ClearType::All),
            cursor::Hide,
            EnableFocusChange
        )?;
        if mouse {
            MOUSE.store(true, Ordering::SeqCst);
            execute!(out, EnableMouseCapture)?;
        }
        if kitty {
            KITTY.store(true, Ordering::SeqCst);
            execute!(
                out,
                PushKeyboardEnhancementFlags(
                    KeyboardEnhancementFlags::DISAMBIGUATE_ESCAPE_CODES
                        | KeyboardEnhancementFlags::REPORT_EVENT_TYPES
                        | KeyboardEnhancementFlags::REPORT_ALL_KEYS_AS_ESCAPE_CODES
                        | KeyboardEnhancementFlags::REPORT_ALTERNATE_KEYS
                )
            )?;
        }
        Ok(Self {
            out: TtyOut::open(),
            stop,
            mode: if kitty {
                InputMode::Kitty
            } else {
                InputMode::Emulated
            },
        })
    }

    /// How keys will arrive (decided by the start-up probe).
    #[must_use]
    pub fn input_mode(&self) -> InputMode {
        self.mode
    }

    /// Asks the terminal what it draws ([`crate::ui::colour_query`]), before the first frame,
    /// and returns `choice` after its answers ([`rules::decide`]). Waits for the DA1 reply that
    /// ends the answers, at most [`QUERY_PATIENCE`] ([`ANSWERBACK_PATIENCE`] when ENQ went too;
    /// once more when the terminal has begun answering, so an answerback on its way is not
    /// taken for keys); keys typed meanwhile come back as events, in order, for the game.
    pub fn ask_colour(
        &mut self,
        choice: ColourChoice,
    ) -> (ColourChoice, Vec<crossterm::event::Event>) {
        let Some(mut input) = open_input_nonblocking() else {
            return (choice, Vec::new());
        };
        let answerback = choice.worth_an_answerback();
        if self.write_frame(&query(answerback)).is_err() {
            return (choice, Vec::new());
        }
        let patience = if answerback {
            ANSWERBACK_PATIENCE
        } else {
            QUERY_PATIENCE
        };
        let mut deadline = Instant::now() + patience;
        let mut extended = false;
        let mut scanner = ReplyScanner::new(answerback);
        let mut buf = [0u8; 256];
        while !scanner.done() {
            if Instant::now() >= deadline {
                if extended || !scanner.answering() {
                    break;
                }
                extended = true;
                deadline += QUERY_PATIENCE;
            }
            match input.read(&mut buf) {
                // End of input: nothing will ever answer.
                Ok(0) => break,
                Ok(n) => scanner.feed(&buf[..n]),
                Err(e) if e.kind() == io::ErrorKind::WouldBlock => {
                    std::thread::sleep(Duration::from_millis(2));
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(_) => break,
            }
        }
        let (answers, rest) = scanner.finish();
        (rules::decide(choice, &answers), keys_from_bytes(&rest))
    }

    /// The terminal size now, in cells.
    ///
    /// # Errors
    /// The size query's I/O error.
    pub fn size(&self) -> io::Result<ratatui::layout::Size> {
        let (width, height) = crossterm::terminal::size()?;
        Ok(ratatui::layout::Size { width, height })
    }

    /// Writes one frame's bytes (from [`crate::present::Presenter`]), unbuffered. While the
    /// terminal is full it waits, but never past a caught signal.
    ///
    /// # Errors
    /// [`io::ErrorKind::Interrupted`] when a signal arrived first; the terminal's write error
    /// (e.g. it went away).
    pub fn write_frame(&mut self, bytes: &[u8]) -> io::Result<()> {
        // After a restore (a panic unwinding mid-frame), nothing more reaches the user's shell.
        if !ACTIVE.load(Ordering::SeqCst) {
            return Ok(());
        }
        self.out.write_all(bytes, &self.stop, None)
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        restore();
    }
}

/// Puts the terminal back (keys, mouse, cursor, main screen, cooked mode); safe to call twice.
/// The escape sequences get a bounded time (a terminal nobody reads cannot take them); the
/// line discipline is restored in any case.
pub fn restore() {
    if !ACTIVE.swap(false, Ordering::SeqCst) {
        return;
    }
    let mut out = Vec::new();
    if KITTY.swap(false, Ordering::SeqCst) {
        let _ = queue!(out, PopKeyboardEnhancementFlags);
    }
    if MOUSE.swap(false, Ordering::SeqCst) {
        let _ = queue!(out, DisableMouseCapture);
    }
    let _ = queue!(
        out,
        EndSynchronizedUpdate,
        DisableFocusChange,
        style::ResetColor,
        LeaveAlternateScreen,
        cursor::Show
    );
    write_within(&out, RESTORE_PATIENCE);
    let _ = disable_raw_mode();
}

/// Keys in raw terminal bytes, as the crossterm events the game's key map takes.
fn keys_from_bytes(bytes: &[u8]) -> Vec<crossterm::event::Event> {
    use crate::ui::key_bytes::{InputEvent, InputParser};
    use crate::ui::key_route::{route, Routed};
    let mut parsed = Vec::new();
    let mut parser = InputParser::new();
    parser.feed(bytes, &mut parsed);
    parser.flush(&mut parsed);
    parsed
        .into_iter()
        .filter_map(|ev| match ev {
            InputEvent::Key(k) => match route(k) {
                Routed::Tui(ev) => Some(ev),
                _ => None,
            },
            InputEvent::KittyFlags(_) => None,
        })
        .collect()
}

/// A second, non-blocking handle on the terminal behind stdin (stdin itself keeps blocking
/// reads for the input thread that starts later).
#[cfg(unix)]
fn open_input_nonblocking() -> Option<std::fs::File> {
    use std::os::unix::fs::OpenOptionsExt;
    let path = std::fs::read_link("/proc/self/fd/0")
        .ok()
        .filter(|p| p.starts_with("/dev/"))
        .unwrap_or_else(|| "/dev/tty".into());
    std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY)
        .open(path)
        .ok()
}

#[cfg(not(unix))]
fn open_input_nonblocking() -> Option<std::fs::File> {
    None
}

/// Restores the terminal before the default panic message, so the message is readable.
fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            restore();
            previous(info);
        }));
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crossterm::event::{Event, KeyCode};

    #[test]
    fn typed_bytes_become_key_events_in_order() {
        let evs = keys_from_bytes(b"?w\x1b[A");
        let codes: Vec<KeyCode> = evs
            .iter()
            .filter_map(|e| match e {
                Event::Key(k) => Some(k.code),
                _ => None,
            })
            .collect();
        assert_eq!(codes, [KeyCode::Char('?'), KeyCode::Char('w'), KeyCode::Up]);
    }
}
