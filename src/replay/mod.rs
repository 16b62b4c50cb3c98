//! Deterministic recordings: the `.hcr` file format and the fixed-timestep player.

pub(crate) mod format;
pub mod limits;

pub use format::{
    FrameInput, Header, MapSource, Replay, ReplayError, MAX_FRAMES, MAX_REPLAY_BYTES,
};
pub use limits::{default_max_frames, DEFAULT_MAX_OUTPUT_BYTES, LONGEST_RECORDING_SECS};
