//! What a play session is given by its transport, and what it gives back when it ends.

use std::sync::Arc;
use std::time::Duration;

use tokio::sync::watch;

use super::pacing::LinkFigures;
use super::world_port::WorldHandle;
use crate::encode::ColourChoice;
use crate::game::multi::players::PlayerId;
use crate::render::glyphs::Glyphs;
use crate::ui::keys::InputMode;
use crate::ui::octant_support::OctantDropper;
use crate::world::World;

/// Who plays and how a session starts: what the transport learnt of its client before play.
pub struct Setup {
    pub id: PlayerId,
    pub name: String,
    /// Watches a player's view instead of playing.
    pub spectator: bool,
    /// The colour level to start at (the transport's guess or its client's answer).
    pub colour: ColourChoice,
    /// The block characters to start with.
    pub glyphs: Glyphs,
    /// What drops octants from the glyph key's cycle for this client (tmux), and the words that
    /// tell the player how to force them.
    pub octant_dropper: Option<OctantDropper>,
    pub force_octants: &'static str,
    /// How keys arrive: inferred holds (a plain terminal) or true releases.
    pub input_mode: InputMode,
    /// Input the client sent before play began (typed while the transport asked its terminal).
    pub early: Vec<u8>,
    pub world: WorldHandle,
    /// The served world (with the avatar sheet at `avatar_sheet`).
    pub world_data: Arc<World>,
    pub avatar_sheet: usize,
    pub fps: u32,
    /// Players with no input for this long are closed; spectators never are.
    pub idle_timeout: Duration,
    /// A client that takes no frame for this long is dropped (its link is dead or it never
    /// reads).
    pub stall_timeout: Duration,
}

/// What a transport feeds a session while it runs.
pub struct Feeds<I> {
    /// The client's input ([`InputSource`](super::input::InputSource)).
    pub input: I,
    /// The client's latest size in columns and rows.
    pub size: watch::Receiver<(u32, u32)>,
    /// `true` ends the session at once (server shutdown).
    pub shutdown: watch::Receiver<bool>,
    /// A note from the server for every player (a world draining), shown until the session ends.
    pub announce: watch::Receiver<Option<String>>,
}

/// Why a session ended (for the log, and for how the transport says goodbye).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum End {
    Quit,
    ClientGone,
    Idle,
    Stalled,
    Shutdown,
}

/// A finished session's figures, for the transport's log line and counters.
#[derive(Debug, Clone, Copy, Default)]
pub struct Tally {
    pub frames: u64,
    pub bytes: u64,
    /// Frame ticks that passed without a frame: the session was late, or the link held it.
    pub dropped: u64,
    pub link: LinkFigures,
}
