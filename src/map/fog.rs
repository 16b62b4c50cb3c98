//! The map's `FOG` line: declared by the map, applied by the renderer's light.

use crate::color::Rgb;

/// Fog: colour things fade toward, and how fast (fraction remaining = e^(−density · distance)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fog {
    /// The colour far things become.
    pub colour: Rgb,
    /// Per cell of distance; 0 = no fog.
    pub density: f64,
}
