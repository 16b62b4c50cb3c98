//! How much one recording may make: the frame count an honest recording has, and the output a
//! headless replay may write.
//!
//! A `.hcr` file is tiny whatever it claims (`{"end":1000000}` is 15 bytes), but every frame it
//! claims becomes a rendered frame, and every rendered frame kilobytes of output. An honest
//! recording's frame count is its duration times its fps; `halfcast record` stops recording
//! after [`LONGEST_RECORDING_SECS`], so [`default_max_frames`] covers every recording it makes
//! and refuses claims beyond that before anything is rendered.

use super::format::MAX_FRAMES;

/// The longest stretch `halfcast record` records (one hour), in seconds of game time.
pub const LONGEST_RECORDING_SECS: u32 = 3600;

/// The default `--max-frames` of a replay at `fps`: [`LONGEST_RECORDING_SECS`] at that rate,
/// within the format's [`MAX_FRAMES`] (108 000 frames at 30 fps).
#[must_use]
pub fn default_max_frames(fps: u32) -> usize {
    let frames = u64::from(LONGEST_RECORDING_SECS) * u64::from(fps.max(1));
    usize::try_from(frames).map_or(MAX_FRAMES, |f| f.min(MAX_FRAMES))
}

/// The default `--max-output-bytes` of a headless replay (an asciicast or frame files): 16 GiB.
/// A truecolor cast of constant turning (every frame a full redraw) measured 16 KB a frame at
/// 40×12, 79 KB at 120×36 and 145 KB at 160×48, so an hour of that at 30 fps and 160×48 (14.6
/// GiB) fits; walking measured 9 KB a frame at 120×36. A hostile file (a huge size, a million
/// frames) stops here instead of filling the disk.
pub const DEFAULT_MAX_OUTPUT_BYTES: u64 = 16 << 30;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_hour_at_the_recorded_rate_within_the_format_limit() {
        assert_eq!(default_max_frames(30), 108_000);
        assert_eq!(default_max_frames(1), 3600);
        assert_eq!(default_max_frames(0), 3600);
        assert_eq!(default_max_frames(1000), MAX_FRAMES);
    }
}
