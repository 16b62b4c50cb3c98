//! Option groups several commands share (map, pose, world features) and their value parsers.

use std::path::PathBuf;

use clap::Args;
use halfcast::camera::DEFAULT_FOV_DEG;
use halfcast::render::light::Fog;
pub(crate) use halfcast::trace_query::values::{parse_finite, parse_fov, parse_pos};
use halfcast::Vec2;

#[derive(Args, Debug)]
pub(crate) struct MapArgs {
    /// A .cub map file (default: the embedded map).
    pub(crate) map: Option<PathBuf>,
    /// Treat a missing or unreadable texture as an error instead of a warning.
    #[arg(long)]
    pub(crate) strict: bool,
}

#[derive(Args, Debug)]
pub(crate) struct PoseArgs {
    /// Camera position X,Y in cells (default: the map's start).
    #[arg(long, value_parser = parse_pos, allow_hyphen_values = true)]
    pub(crate) pos: Option<Vec2>,
    /// Facing in degrees: 0 = east, 90 = north (default: the map's start).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_finite)]
    pub(crate) angle: Option<f64>,
    /// Horizontal field of view in degrees (0 < FOV < 180).
    #[arg(long, default_value_t = DEFAULT_FOV_DEG, value_parser = parse_fov)]
    pub(crate) fov: f64,
}

/// View, light, time and door options (world features).
#[derive(Args, Debug)]
pub(crate) struct WorldArgs {
    /// Look up (+) or down (-), in degrees (-45 to 45); shifts the horizon.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_pitch)]
    pub(crate) pitch: f64,
    /// Eye height in wall heights: 0.5 standing, lower crouches, higher jumps (0.05 to 0.95).
    #[arg(long, default_value_t = halfcast::render::view::STANDING_EYE, value_parser = parse_eye)]
    pub(crate) z: f64,
    /// Fog colour and density R,G,B,DENSITY (replaces the map's FOG line).
    #[arg(long, value_parser = parse_fog)]
    pub(crate) fog: Option<Fog>,
    /// Night: dark, with the view lit near the player.
    #[arg(long)]
    pub(crate) night: bool,
    /// Game time in seconds, which picks animated sprites' frames.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_finite)]
    pub(crate) time: f64,
    /// How far every door is open, 0 (shut) to 1 (open).
    #[arg(long, default_value_t = 0.0, value_parser = parse_unit)]
    pub(crate) door_open: f64,
}

pub(crate) fn parse_pitch(s: &str) -> Result<f64, String> {
    use halfcast::render::view::MAX_PITCH_DEG;
    let v = parse_finite(s)?;
    if v.abs() <= MAX_PITCH_DEG {
        Ok(v)
    } else {
        Err(format!(
            "pitch {v} must be between -{MAX_PITCH_DEG} and {MAX_PITCH_DEG} degrees"
        ))
    }
}

pub(crate) fn parse_eye(s: &str) -> Result<f64, String> {
    use halfcast::render::view::EYE_RANGE;
    let v = parse_finite(s)?;
    if (EYE_RANGE.0..=EYE_RANGE.1).contains(&v) {
        Ok(v)
    } else {
        Err(format!(
            "eye height {v} must be between {} and {}",
            EYE_RANGE.0, EYE_RANGE.1
        ))
    }
}

pub(crate) fn parse_unit(s: &str) -> Result<f64, String> {
    let v = parse_finite(s)?;
    if (0.0..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{v} must be between 0 and 1"))
    }
}

pub(crate) fn parse_fog(s: &str) -> Result<Fog, String> {
    let bad = || format!("'{s}' is not R,G,B,DENSITY (channels 0-255, density >= 0)");
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [r, g, b, d] = parts[..] else {
        return Err(bad());
    };
    let ch = |t: &str| t.parse::<u8>().map_err(|_| bad());
    let density = parse_finite(d).map_err(|_| bad())?;
    if density < 0.0 {
        return Err(bad());
    }
    Ok(Fog {
        colour: halfcast::Rgb::new(ch(r)?, ch(g)?, ch(b)?),
        density,
    })
}
