//! How a lamp's light fades with distance, and the scale it is stored in: the flat bake, the
//! 3-D lamp reach and the game's moving lights all use the one curve.

/// Full brightness in the stored levels (256ths, like [`crate::render::light::Shade`]).
pub const FULL: u16 = 256;

/// How much of a light of `radius` reaches `d` cells away: full at the lamp, smoothly nothing
/// at the radius.
#[must_use]
pub fn falloff(d: f64, radius: f64) -> f64 {
    let t = (d / radius).clamp(0.0, 1.0);
    (1.0 - t * t).powi(2)
}
