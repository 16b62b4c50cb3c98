//! What a play session is given before it starts: what its client brought (learnt by the
//! transport) and what the server decides for every session alike.

use std::sync::Arc;
use std::time::Duration;

use tokio::sync::watch;

use super::world_port::WorldHandle;
use crate::encode::ColourChoice;
use crate::game::multi::players::PlayerId;
use crate::render::glyphs::Glyphs;
use crate::ui::keys::InputMode;
use crate::ui::octant_support::OctantDropper;
use crate::world::World;

/// Everything a session starts from: its client's facts and the server's rules.
pub struct Setup {
    pub client: Client,
    pub rules: Rules,
}

/// Who plays and what their client is: what the transport learnt of it before play.
pub struct Client {
    pub id: PlayerId,
    pub name: String,
    /// Watches a player's view instead of playing.
    pub spectator: bool,
    pub facts: Facts,
}

/// What a transport learnt of its client before play (the rest of a session's start is the
/// server's: [`Rules`]).
pub struct Facts {
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
}

impl Facts {
    /// What every browser page brings, asked nothing: true colour (the page draws every
    /// colour), key releases as they happen, the default block characters.
    #[must_use]
    pub fn browser() -> Self {
        Self {
            colour: ColourChoice {
                level: crate::encode::ColorLevel::TrueColor,
                reason: crate::encode::ColourReason::Browser,
            },
            glyphs: Glyphs::default(),
            octant_dropper: None,
            force_octants: "",
            input_mode: InputMode::Released,
            early: Vec::new(),
        }
    }
}

/// What the server decides for every session, whatever carries it.
#[derive(Clone)]
pub struct Rules {
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
