//! Writing to the terminal without ever blocking past a pending signal.
//!
//! A terminal nobody reads (a stalled SSH link, a pty whose owner hung) fills up, and a plain
//! blocking write then never returns: SIGTERM only sets a flag, so the game could not stop. Here
//! the terminal is opened a second time in non-blocking mode (a new open file description, so
//! stdin keeps blocking reads) and a full terminal is waited on in short sleeps, checking the
//! stop flag and a deadline between them.

use std::fs::File;
use std::io::{self, Write};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How long a full terminal is waited on before checking the stop flag again.
const NAP: Duration = Duration::from_millis(2);

/// The terminal's output, written in bounded steps.
#[derive(Debug)]
pub struct TtyOut {
    /// The terminal opened non-blocking; `None` where that is impossible (then plain stdout).
    file: Option<File>,
}

impl TtyOut {
    /// Opens the terminal stdout writes to, non-blocking (falls back to blocking stdout).
    #[must_use]
    pub fn open() -> Self {
        Self {
            file: open_nonblocking(),
        }
    }

    /// Writes all of `bytes`, waiting while the terminal is full. Gives up with
    /// [`io::ErrorKind::Interrupted`] as soon as `stop` holds a signal number, and with
    /// [`io::ErrorKind::TimedOut`] after `patience` (if given).
    ///
    /// # Errors
    /// Those two, or the terminal's own write error.
    pub fn write_all(
        &mut self,
        bytes: &[u8],
        stop: &AtomicUsize,
        patience: Option<Duration>,
    ) -> io::Result<()> {
        let Some(file) = self.file.as_mut() else {
            let mut out = io::stdout().lock();
            out.write_all(bytes)?;
            return out.flush();
        };
        let start = Instant::now();
        let mut rest = bytes;
        while !rest.is_empty() {
            if stop.load(Ordering::SeqCst) != 0 {
                return Err(io::ErrorKind::Interrupted.into());
            }
            match file.write(rest) {
                Ok(0) => return Err(io::ErrorKind::WriteZero.into()),
                Ok(n) => rest = &rest[n..],
                Err(e) if e.kind() == io::ErrorKind::WouldBlock => {
                    if patience.is_some_and(|p| start.elapsed() >= p) {
                        return Err(io::ErrorKind::TimedOut.into());
                    }
                    std::thread::sleep(NAP);
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
        Ok(())
    }
}

/// Writes `bytes` to the terminal, giving up after `patience` if it does not take them (used
/// to restore the terminal, which must not hang on a terminal nobody reads).
pub fn write_within(bytes: &[u8], patience: Duration) {
    let never = Arc::new(AtomicUsize::new(0));
    let _ = TtyOut::open().write_all(bytes, &never, Some(patience));
}

/// A second, non-blocking handle on the terminal behind stdout.
#[cfg(unix)]
fn open_nonblocking() -> Option<File> {
    use std::os::unix::fs::OpenOptionsExt;
    // Linux names the device behind fd 1; elsewhere the controlling terminal is the best guess.
    let path = std::fs::read_link("/proc/self/fd/1")
        .ok()
        .filter(|p| p.starts_with("/dev/"))
        .unwrap_or_else(|| "/dev/tty".into());
    std::fs::OpenOptions::new()
        .write(true)
        .custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY)
        .open(path)
        .ok()
}

#[cfg(not(unix))]
fn open_nonblocking() -> Option<File> {
    None
}
