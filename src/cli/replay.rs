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
    #[command(flatten)]
    pub(crate) limits: super::replay_limits::ReplayLimits,
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
    let file = args.file.display().to_string();
    // What one file may make is bounded before anything is loaded or rendered.
    match (args.format, &args.frames) {
        (Some(ReplayFormat::Cast), _) => args.limits.check(&replay, replay.frames.len(), &file)?,
        (Some(_), Some(frames)) => {
            let last = frames.last().map_or(0, |f| f + 1);
            args.limits.check(&replay, last, &file)?;
        }
        _ => {}
    }
    let world = replay_world(&replay, &args.file).map_err(failure)?;
    match (args.format, &args.frames) {
        (Some(ReplayFormat::Cast), _) => write_cast(args, &replay, world),
        (Some(format), Some(frames)) => {
            let dir = args.out.clone().unwrap_or_else(|| PathBuf::from("."));
            let cap = args.limits.output_bytes();
            write_frames(&replay, world, frames, format, args.colors, &dir, cap).map_err(failure)
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
///
/// A file appears only when the cast is complete (see `output_file`); on an error or the output
/// limit nothing is left. Standard output cannot be taken back: at the limit the stream ends
/// with a last event saying the cast is incomplete (after whole events only), the error goes to
/// standard error, and the exit code is 2.
fn write_cast(
    args: &ReplayArgs,
    replay: &halfcast::replay::Replay,
    world: std::sync::Arc<halfcast::world::World>,
) -> Result<(), Failure> {
    use super::replay_frames::{cast_cut_notice, write_asciicast, CastStop};
    use std::io::{BufWriter, ErrorKind, Write};
    let cap = args.limits.output_bytes();
    let limit = |frame: usize, cap: u64, what: &str| {
        Failure::input(format!(
            "{what}: stopped at frame {frame} of {}: the cast would pass --max-output-bytes {cap}",
            replay.frames.len()
        ))
    };
    match &args.out {
        Some(p) => {
            let cannot =
                |e: std::io::Error| Failure::io(format!("cannot write {}: {e}", p.display()));
            let mut file = super::output_file::OutputFile::create(p).map_err(cannot)?;
            match write_asciicast(replay, world, args.colors, cap, &mut file) {
                Ok(()) => file.commit().map_err(cannot),
                Err(CastStop::Io(e)) => Err(cannot(e)),
                Err(CastStop::OutputLimit { frame, cap, .. }) => {
                    Err(limit(frame, cap, &format!("{} (not written)", p.display())))
                }
            }
        }
        None => {
            let mut out = BufWriter::new(std::io::stdout().lock());
            match write_asciicast(replay, world, args.colors, cap, &mut out) {
                Ok(()) => Ok(()),
                Err(CastStop::Io(e)) if e.kind() == ErrorKind::BrokenPipe => Ok(()),
                Err(CastStop::Io(e)) => Err(Failure::io(e)),
                Err(CastStop::OutputLimit { frame, at, cap }) => {
                    let why = format!("cut at frame {frame}, --max-output-bytes {cap}");
                    let _ = writeln!(out, "{}", cast_cut_notice(at, &why));
                    let _ = out.flush();
                    Err(limit(frame, cap, "standard output (incomplete)"))
                }
            }
        }
    }
}
