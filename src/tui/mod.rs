//! The interactive terminal game: session lifecycle, key handling, layout and the frame loop.
//!
//! The loop keeps its stages apart: [`keys`] turns events into a game `Input`, `game::step`
//! advances the state, [`render`] paints the 3D view into a framebuffer, and [`screen`] lays
//! every pane into a ratatui buffer. Only [`terminal`] and [`app`] touch the real terminal.

pub mod app;
pub mod help;
pub mod keys;
pub mod layout;
pub mod render;
pub mod repeat;
pub mod screen;
pub mod stats;
pub mod status;
pub mod terminal;

use std::sync::atomic::AtomicUsize;
use std::sync::Arc;

use crate::camera::Camera;
use crate::world::World;

pub use app::Ending;
pub use stats::FrameStats;
pub use terminal::TerminalError;

/// What `halfcast play` was asked for.
#[derive(Debug, Clone, Copy)]
pub struct PlayOptions {
    /// Target frames per second.
    pub fps: u32,
    /// Capture the mouse so dragging turns the view.
    pub mouse: bool,
}

/// Plays in this terminal until the player quits or a signal arrives; the terminal is
/// restored on every way out (including panics, via the session's panic hook).
///
/// # Errors
/// Not a terminal, or terminal I/O failing mid-game.
pub fn play(
    world: Arc<World>,
    camera: Camera,
    options: PlayOptions,
) -> Result<(Ending, FrameStats), TerminalError> {
    terminal::require_tty()?;
    let signal = Arc::new(AtomicUsize::new(0));
    let mut signals = vec![signal_hook::consts::SIGTERM, signal_hook::consts::SIGINT];
    #[cfg(unix)]
    signals.extend([signal_hook::consts::SIGHUP, signal_hook::consts::SIGQUIT]);
    for sig in signals {
        signal_hook::flag::register_usize(sig, Arc::clone(&signal), sig as usize)?;
    }
    let mut session = terminal::Session::start(options.mouse)?;
    let state = crate::game::GameState::new(world, camera, 0);
    let result = app::run_loop(&mut session, state, options.fps, &signal);
    drop(session);
    Ok(result?)
}
