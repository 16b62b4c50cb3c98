//! Catching a panic on this thread without the panic hook printing it, so an assertion can
//! fail again at its caller's line with a message of its own instead of twice.

use std::cell::Cell;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Once;

thread_local! {
    /// Whether this thread is inside [`catch_quietly`].
    static QUIET: Cell<bool> = const { Cell::new(false) };
}

/// Installs, once per process, a panic hook that stays silent on a thread inside
/// [`catch_quietly`] and passes every other panic to the hook that was there before.
fn install_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info);
            }
        }));
    });
}

/// Runs `f`, returning its panic's message instead of printing it.
pub(crate) fn catch_quietly(f: impl FnOnce()) -> Result<(), String> {
    install_hook();
    let was = QUIET.with(|q| q.replace(true));
    let outcome = catch_unwind(AssertUnwindSafe(f));
    QUIET.with(|q| q.set(was));
    outcome.map_err(|payload| {
        payload
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| payload.downcast_ref::<&str>().map(|s| (*s).to_string()))
            .unwrap_or_else(|| "a panic without a message".to_string())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_message_comes_back_and_the_thread_is_loud_again() {
        assert_eq!(catch_quietly(|| {}), Ok(()));
        assert_eq!(catch_quietly(|| panic!("no {}", 1)), Err("no 1".into()));
        assert_eq!(catch_quietly(|| panic!("static")), Err("static".into()));
        assert!(!QUIET.with(Cell::get));
    }
}
