//! Terminal input on its own thread, so the game loop only ever waits on a channel.
//!
//! crossterm's reader loops forever, at full CPU, once the terminal hangs up (a read returning
//! end-of-file is never treated as the end). If the game loop called it directly, a closed
//! terminal window would leave the game spinning with the hang-up signal unseen. Here that can
//! only happen to the reader thread, which the process takes down when the loop ends.

use std::io;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::thread;
use std::time::Duration;

use crossterm::event::{self, Event};

/// Events read by a background thread, taken with a timeout.
#[derive(Debug)]
pub struct Events {
    rx: Receiver<io::Result<Event>>,
}

impl Events {
    /// Starts the reader thread (call once the terminal is set up: the start-up probe reads too).
    ///
    /// # Errors
    /// The thread could not be started.
    pub fn spawn() -> io::Result<Self> {
        let (tx, rx) = mpsc::sync_channel(256);
        thread::Builder::new()
            .name("halfcast-input".into())
            .spawn(move || loop {
                let ev = event::read();
                let failed = ev.is_err();
                if tx.send(ev).is_err() || failed {
                    break;
                }
            })?;
        Ok(Self { rx })
    }

    /// The next event if one arrives within `timeout`, `None` when the time is up.
    ///
    /// # Errors
    /// The terminal's read error, or `BrokenPipe` once the reader has stopped.
    pub fn next_within(&self, timeout: Duration) -> io::Result<Option<Event>> {
        match self.rx.recv_timeout(timeout) {
            Ok(ev) => ev.map(Some),
            Err(RecvTimeoutError::Timeout) => Ok(None),
            Err(RecvTimeoutError::Disconnected) => Err(io::Error::new(
                io::ErrorKind::BrokenPipe,
                "terminal input closed",
            )),
        }
    }
}
