//! The brightness ramp that stands for colour where a terminal shows none: the mono colour level
//! and the plain-text view both shade cells with it.

/// Dark to bright; spaces read as darkness in any terminal or code review.
pub const SHADE_RAMP: &[u8] = b" .:-=+*#%@";

/// The ramp character for a luminance 0..=255.
#[must_use]
pub fn shade_char(luma: u8) -> char {
    let i = usize::from(luma) * SHADE_RAMP.len() / 256;
    char::from(SHADE_RAMP[i])
}
