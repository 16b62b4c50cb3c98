//! The local terminal: taking it over and giving it back, its events and output, the config
//! file, and the frame loop. The screen itself (panes, keys, help, results) is `ui`'s, shared
//! with SSH players and replays.
//!
//! The loop keeps its stages apart: `ui::keys` turns events into a game `Input`, `game::step`
//! advances the state, `ui::render` paints the 3D view into a framebuffer, and `ui::screen` lays
//! every pane into a ratatui buffer. Only `terminal` and `app` touch the real terminal.

pub(crate) mod app;
pub mod config;
pub(crate) mod events;
pub(crate) mod figure_key;
pub(crate) mod playback;
pub(crate) mod terminal;
pub(crate) mod tty_out;

use std::sync::atomic::AtomicUsize;
use std::sync::Arc;

use crate::camera::Camera;
use crate::encode::ColourChoice;
use crate::world::World;

pub use crate::ui::stats::FrameStats;
pub use app::{Ending, LoopOptions, Recording};
pub use terminal::TerminalError;

/// What `halfcast play` was asked for.
#[derive(Debug, Clone)]
pub struct PlayOptions {
    /// Pacing, encoding and recording.
    pub looping: LoopOptions,
    /// Capture the mouse so dragging turns the view.
    pub mouse: bool,
    /// The colour level from the flag or the environment; a `TERM` guess is checked with the
    /// terminal itself before the first frame.
    pub colour: ColourChoice,
    /// Key bindings, speeds and the panes shown at start (from the config file and flags).
    pub setup: Setup,
}

/// One level of a campaign: its world, where the player starts, and its name for the results.
#[derive(Debug, Clone)]
pub struct Stage {
    /// The level's world.
    pub world: Arc<World>,
    /// The player's start.
    pub camera: Camera,
    /// The map's name, shown on the results screen.
    pub name: String,
}

/// The player's choices that the loop starts from.
#[derive(Debug, Clone, Default)]
pub struct Setup {
    pub keys: crate::ui::keymap::KeyMap,
    pub speeds: crate::game::Speeds,
    pub toggles: crate::ui::layout::Toggles,
    /// Block characters the view starts with (the U key cycles them).
    pub glyphs: crate::render::glyphs::Glyphs,
}

/// What drops octants between this process and the screen, as its environment (`TERM`,
/// `TMUX`) shows it; `ui::octant_support` holds the rule.
fn octant_dropper_here() -> Option<crate::ui::octant_support::OctantDropper> {
    let var = |k: &str| std::env::var(k).ok();
    let (term, tmux) = (var("TERM"), var("TMUX"));
    crate::ui::octant_support::octant_dropper(crate::ui::octant_support::TermEnv {
        term: term.as_deref(),
        tmux: tmux.as_deref(),
    })
}

/// Registers the signals that end a session (SIGTERM, SIGINT; SIGHUP and SIGQUIT on unix)
/// into one flag holding the signal's number.
fn watch_signals() -> std::io::Result<Arc<AtomicUsize>> {
    let signal = Arc::new(AtomicUsize::new(0));
    let mut signals = vec![signal_hook::consts::SIGTERM, signal_hook::consts::SIGINT];
    #[cfg(unix)]
    signals.extend([signal_hook::consts::SIGHUP, signal_hook::consts::SIGQUIT]);
    for sig in signals {
        signal_hook::flag::register_usize(sig, Arc::clone(&signal), sig as usize)?;
    }
    Ok(signal)
}

/// Plays `stages` in order in this terminal (each level's exit leads to the next; the last one
/// starts again) until the player quits or a signal arrives; the terminal is restored on every
/// way out (including panics, via the session's panic hook). `seed` drives the creatures.
///
/// # Errors
/// Not a terminal, or terminal I/O failing mid-game.
///
/// # Panics
/// If `stages` is empty.
pub fn play(
    stages: Vec<Stage>,
    seed: u64,
    options: PlayOptions,
) -> Result<(Ending, FrameStats, Option<Recording>), TerminalError> {
    assert!(!stages.is_empty(), "a campaign has at least one level");
    terminal::require_tty()?;
    let signal = watch_signals()?;
    let mut session = terminal::Session::start(options.mouse, &signal)?;
    let mut colour = options.colour;
    let mut early_keys = Vec::new();
    if colour.worth_asking() {
        let (asked, keys) = session.ask_colour(colour);
        colour = asked;
        early_keys = keys;
    }
    let mut looping = options.looping;
    looping.encode.level = colour.level;
    looping.colour_reason = colour.reason;
    let result = app::run_loop(
        &mut session,
        app::Campaign { stages, seed },
        looping,
        &options.setup,
        early_keys,
        &signal,
    );
    drop(session);
    Ok(result?)
}

/// Shows a replay in this terminal at its recorded pace (q, Esc or Ctrl-C stop it early);
/// the frames are exactly those `halfcast replay --format cast` writes.
///
/// # Errors
/// Not a terminal, or terminal I/O failing.
pub fn watch(
    world: Arc<World>,
    replay: &crate::replay::Replay,
    encode: crate::encode::EncodeOptions,
) -> Result<Ending, TerminalError> {
    terminal::require_tty()?;
    let signal = watch_signals()?;
    let mut session = terminal::Session::start(false, &signal)?;
    let result = playback::run(&mut session, world, replay, encode, &signal);
    drop(session);
    Ok(result?)
}
