//! Deterministic recordings: the `.hcr` file format and the fixed-timestep player.

pub mod format;
#[cfg(feature = "tui")]
pub mod player;

pub use format::{
    FrameInput, Header, MapSource, Replay, ReplayError, MAX_FRAMES, MAX_REPLAY_BYTES,
};
