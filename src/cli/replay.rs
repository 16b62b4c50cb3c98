//! `halfcast replay`: a `.hcr` recording on screen, as chosen frame files, or as an asciicast.

use std::path::PathBuf;

use clap::Args;
use halfcast::encode::{ColorLevel, EncodeOptions};
use halfcast::tui;

use super::play::{ending_result, terminal_failure};
use super::{parse_level, Failure};

#[derive(Args, Debug)]
pub(crate) struct ReplayArgs {
    /// The recording (.hcr).
    pub(crate) file: PathBuf,
    /// Frames to write, e.g. `0,10,20` or `0-19` (frame N is drawn after N+1 steps).
    #[arg(long, value_parser = super::replay_frames::parse_frames)]
    pub(crate) frames: Option<std::vec::Vec<usize>>,
    /// What to write: per-frame files, or `cast` (asciicast v2 of the whole run).
    #[arg(long, value_enum)]
    pub(crate) format: Option<super::replay_frames::ReplayFormat>,
    /// Folder for frame files, or the file for `--format cast` (default: standard output).
    #[arg(long)]
    pub(crate) out: Option<PathBuf>,
    /// Colour level of `ansi`, `cast` and on-screen output (default truecolor, the same anywhere).
    #[arg(long, value_parser = parse_level, default_value = "truecolor")]
    pub(crate) colors: ColorLevel,
    /// Play only frames 0..=N (on screen or as `cast`): the run ends showing frame N.
    #[arg(long, value_name = "N")]
    pub(crate) until_frame: Option<usize>,
}

pub(crate) fn replay(args: &ReplayArgs) -> Result<(), Failure> {
    use super::replay_frames::{read_replay, replay_world, write_frames, ReplayFormat};
    let failure = |f: super::replay_frames::ReplayFailure| Failure {
        code: f.code,
        message: f.message,
    };
    let mut replay = read_replay(&args.file).map_err(failure)?;
    if let Some(n) = args.until_frame {
        super::replay_frames::cut_after(&mut replay, n).map_err(failure)?;
    }
    let world = replay_world(&replay, &args.file).map_err(failure)?;
    match (args.format, &args.frames) {
        (Some(ReplayFormat::Cast), _) => write_cast(args, &replay, world),
        (Some(format), Some(frames)) => {
            let dir = args.out.clone().unwrap_or_else(|| PathBuf::from("."));
            write_frames(&replay, world, frames, format, args.colors, &dir).map_err(failure)
        }
        (Some(_), None) => Err(Failure::input(
            "--format needs --frames (or use --format cast)",
        )),
        (None, _) => {
            let ending = tui::watch(world, &replay, EncodeOptions::new(args.colors))
                .map_err(terminal_failure)?;
            ending_result(ending)
        }
    }
}

/// Streams the asciicast to `--out` (or standard output) while the replay renders, so nothing
/// but the current frame is held in memory; a closed pipe ends the run quietly.
fn write_cast(
    args: &ReplayArgs,
    replay: &halfcast::replay::Replay,
    world: std::sync::Arc<halfcast::world::World>,
) -> Result<(), Failure> {
    use std::io::{BufWriter, ErrorKind};
    match &args.out {
        Some(p) => {
            let file = std::fs::File::create(p)
                .map_err(|e| Failure::io(format!("cannot write {}: {e}", p.display())))?;
            super::replay_frames::write_asciicast(
                replay,
                world,
                args.colors,
                &mut BufWriter::new(file),
            )
            .map_err(|e| Failure::io(format!("cannot write {}: {e}", p.display())))
        }
        None => {
            let mut out = BufWriter::new(std::io::stdout().lock());
            match super::replay_frames::write_asciicast(replay, world, args.colors, &mut out) {
                Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(()),
                r => r.map_err(Failure::io),
            }
        }
    }
}
