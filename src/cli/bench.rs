//! `halfcast bench`: the encoder's figures (bytes per frame, encode time) against stock ratatui.

use std::path::PathBuf;

use clap::Args;
use halfcast::encode::ColorLevel;

use super::{parse_level, write_output, Failure};

#[derive(Args, Debug)]
pub(crate) struct BenchArgs {
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub(crate) json: bool,
    /// Encode this directory of PNG frames (sorted by name; each W×2H px = W×H cells) instead.
    #[arg(long, value_name = "DIR")]
    pub(crate) frames: Option<PathBuf>,
    /// Write each encoded frame as OUT/frame-NNN.ansi (with --frames).
    #[arg(long, value_name = "OUT", requires = "frames")]
    pub(crate) dump: Option<PathBuf>,
    /// Colour level (default: all four; with --frames: truecolor).
    #[arg(long, value_parser = parse_level)]
    pub(crate) colors: Option<ColorLevel>,
    /// Frames per replayed path after the first one.
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u16).range(1..=5000))]
    pub(crate) frame_count: u16,
    /// Lossy: don't resend cells whose colours moved less than N (0–255).
    #[arg(long, value_name = "N")]
    pub(crate) delta: Option<u8>,
    /// Bytes only: encode each frame once, without the timing re-runs and the colour figures
    /// (fast even in a debug build, so the docs' byte figures can be checked by a test); the
    /// table then has no timing columns.
    #[arg(long, conflicts_with = "glyphs")]
    pub(crate) bytes_only: bool,
    /// Row-planner beam width (1 = greedy), for comparing planner settings.
    #[arg(long, hide = true)]
    pub(crate) beam: Option<usize>,
    /// The glyph ladder instead: each block-character setting at 80x24 and 240x68 (S-CIELAB
    /// against an octant-grid render, bytes and render + encode time against half-blocks).
    #[arg(long, conflicts_with = "frames")]
    pub(crate) glyphs: bool,
}

pub(crate) fn bench(args: &BenchArgs) -> Result<(), Failure> {
    use super::bench_run::{bytes_table, run_default, run_frames, table, BenchPlan};
    if args.glyphs {
        use super::bench_glyphs::{glyph_table, run_glyphs};
        let level = args.colors.unwrap_or(ColorLevel::TrueColor);
        let runs = run_glyphs(usize::from(args.frame_count), level);
        let text = if args.json {
            let mut s = serde_json::to_string(&runs).map_err(Failure::io)?;
            s.push('\n');
            s
        } else {
            glyph_table(&runs)
        };
        return write_output(None, text.as_bytes());
    }
    let plan = BenchPlan {
        frames: usize::from(args.frame_count),
        levels: args.colors.into_iter().collect(),
        delta: args.delta,
        beam: args.beam,
        bytes_only: args.bytes_only,
    };
    let report = match &args.frames {
        Some(dir) => run_frames(
            dir,
            args.colors.unwrap_or(ColorLevel::TrueColor),
            &plan,
            args.dump.as_deref(),
        ),
        None => run_default(&plan),
    }
    .map_err(|e| Failure {
        code: e.code,
        message: e.message,
    })?;
    let text = if args.json {
        let mut s = serde_json::to_string(&report).map_err(Failure::io)?;
        s.push('\n');
        s
    } else if args.bytes_only {
        bytes_table(&report)
    } else {
        table(&report)
    };
    write_output(None, text.as_bytes())
}
