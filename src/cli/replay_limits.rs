//! `--max-frames` and `--max-output-bytes`: what one replay file may make `halfcast replay`
//! render and write (see `halfcast::replay::limits` for the defaults and why).

use clap::Args;
use halfcast::replay::{default_max_frames, Replay, DEFAULT_MAX_OUTPUT_BYTES};

use super::Failure;

#[derive(Args, Debug, Clone, Copy)]
pub(crate) struct ReplayLimits {
    /// Refuse to write a run longer than N frames (default: one hour at the replay's fps,
    /// the longest `halfcast record` makes; 108000 at 30 fps).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub(crate) max_frames: Option<u64>,
    /// Stop with an error before the written output passes this size (suffixes K, M, G, T;
    /// default 16G). A file output is then removed, never left looking complete.
    #[arg(long, value_name = "SIZE", value_parser = parse_bytes)]
    pub(crate) max_output_bytes: Option<u64>,
}

impl ReplayLimits {
    /// The output cap in bytes.
    pub(crate) fn output_bytes(&self) -> u64 {
        self.max_output_bytes.unwrap_or(DEFAULT_MAX_OUTPUT_BYTES)
    }

    /// The frame cap for `replay`, from the flag or its fps.
    fn frames_for(&self, replay: &Replay) -> u64 {
        self.max_frames
            .unwrap_or(default_max_frames(replay.header.fps) as u64)
    }

    /// Refuses, before anything is rendered, a run that plays `frames` frames of `replay`
    /// (`file` names it in the message).
    ///
    /// # Errors
    /// Over the cap (exit 2), with how to pass it.
    pub(crate) fn check(&self, replay: &Replay, frames: usize, file: &str) -> Result<(), Failure> {
        let cap = self.frames_for(replay);
        if frames as u64 <= cap {
            return Ok(());
        }
        let fps = replay.header.fps.max(1);
        let why = if self.max_frames.is_some() {
            String::new()
        } else {
            format!(" (the default: one hour at its {fps} fps)")
        };
        Err(Failure::input(format!(
            "{file}: the run is {frames} frames ({:.0} s at {fps} fps), more than --max-frames \
             {cap}{why}; nothing was written. Pass --max-frames {frames} if the recording is \
             really that long, or --until-frame to write its start",
            frames as f64 / f64::from(fps)
        )))
    }
}

/// Parses a byte count: digits with an optional K, M, G or T suffix (powers of 1024; `KiB`,
/// `MB`… are read the same way).
///
/// # Errors
/// Not a number, an unknown suffix, zero, or more than 2^64 bytes.
pub(crate) fn parse_bytes(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let digits = t.len() - t.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    let (num, unit) = t.split_at(digits);
    let n: u64 = num
        .parse()
        .map_err(|_| format!("'{s}' is not a size (e.g. 500M, 4G)"))?;
    let shift = match unit.trim().to_ascii_uppercase().as_str() {
        "" | "B" => 0,
        "K" | "KB" | "KIB" => 10,
        "M" | "MB" | "MIB" => 20,
        "G" | "GB" | "GIB" => 30,
        "T" | "TB" | "TIB" => 40,
        _ => return Err(format!("'{s}': unknown size suffix (use K, M, G or T)")),
    };
    let bytes = n
        .checked_mul(1u64 << shift)
        .ok_or_else(|| format!("'{s}' is too large"))?;
    if bytes == 0 {
        return Err("the size must be at least 1 byte".into());
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_with_and_without_suffixes() {
        assert_eq!(parse_bytes("123"), Ok(123));
        assert_eq!(parse_bytes("4K"), Ok(4096));
        assert_eq!(parse_bytes("500M"), Ok(500 << 20));
        assert_eq!(parse_bytes("4G"), Ok(4 << 30));
        assert_eq!(parse_bytes("2gib"), Ok(2 << 30));
        assert_eq!(parse_bytes("1T"), Ok(1 << 40));
        assert!(parse_bytes("").is_err());
        assert!(parse_bytes("0").is_err());
        assert!(parse_bytes("4X").is_err());
        assert!(parse_bytes("-1").is_err());
        assert!(parse_bytes("99999999999T").is_err());
    }
}
