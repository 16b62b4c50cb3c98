//! Deterministic recordings: the `.hcr` file format and the fixed-timestep player.

pub mod format;

pub use format::{
    FrameInput, Header, MapSource, Replay, ReplayError, MAX_FRAMES, MAX_REPLAY_BYTES,
};
