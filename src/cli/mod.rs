//! Command-line interface: parses flags, loads the world, dispatches to a command (one file per
//! command; shared option groups in `options`).

mod bench;
mod bench_glyphs;
mod bench_run;
mod diff;
mod glyphs;
mod options;
mod output_file;
mod play;
mod pose_check;
mod render;
mod replay;
mod replay_frames;
mod replay_limits;
mod scores;
mod serve;
mod trace;
mod unknown_word;

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use halfcast::camera::Camera;
use halfcast::encode::{ColorLevel, ColourChoice};
use halfcast::world::World;

use bench::BenchArgs;
use diff::DiffArgs;
use options::{MapArgs, PoseArgs};
use play::{PlayArgs, RecordArgs};
use render::RenderArgs;
use replay::ReplayArgs;
use scores::ScoresArgs;
use serve::ServeArgs;
use trace::TraceArgs;

/// `halfcast [MAP] [PLAY FLAGS]` plays (the default command); `halfcast COMMAND …` runs another.
#[derive(Parser, Debug)]
#[command(
    name = "halfcast",
    version,
    about = "A raycasting 3D engine that lives in the terminal",
    override_usage = "halfcast [MAP.cub] [PLAY OPTIONS]   (play, the default)\n       halfcast <COMMAND> [ARGS]",
    args_conflicts_with_subcommands = true,
    subcommand_negates_reqs = true
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// With no command: `halfcast play`'s map and flags.
    #[command(flatten)]
    play: PlayArgs,
}

/// The keys, for `--help` (from the same table as the in-game `?` help).
fn keys_help() -> String {
    use halfcast::ui::help::HelpOverlay;
    use halfcast::ui::keymap::KeyMap;
    let keys = KeyMap::default();
    let help = HelpOverlay {
        mode: halfcast::ui::keys::InputMode::Emulated,
        keys: &keys,
    };
    let mut out = String::from("Keys while playing (defaults; a config file can rebind them):\n");
    let rows = help.rows();
    let width = rows.iter().map(|(k, _)| k.len()).max().unwrap_or(0);
    for (keys, what) in rows {
        if what.is_empty() {
            out.push('\n');
        } else if keys.is_empty() {
            out.push_str(&format!("  {what}\n"));
        } else {
            out.push_str(&format!("    {keys:<width$}  {what}\n"));
        }
    }
    out.push_str("\nExamples:\n    halfcast maps/x.cub --fps 60\n    halfcast render maps/x.cub -o frame.png\n    halfcast serve maps/x.cub   (then: ssh -p 2222 localhost)");
    out
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render one frame headlessly (PNG, ANSI, text or ray JSON).
    #[command(args_override_self = true)]
    Render(RenderArgs),
    /// Play in this terminal (the default when no command is given).
    Play(PlayArgs),
    /// Measure the terminal encoder: bytes per frame and encode time vs stock ratatui.
    Bench(BenchArgs),
    /// Play and record the input into a `.hcr` file (fixed timestep, replayable exactly).
    Record(RecordArgs),
    /// Play back a `.hcr` recording: write chosen frames, or an asciicast of the whole run.
    Replay(ReplayArgs),
    /// Run an SSH server where everyone connected plays in one world (`ssh -p 2222 host`).
    Serve(Box<ServeArgs>),
    /// Print a server's lasting leaderboard (the SQLite file `serve --db` writes).
    Scores(ScoresArgs),
    /// Draw one column's DDA traversal as a figure (SVG or PNG), in Lode's names.
    Trace(TraceArgs),
    /// Compare two frames (PNG, ANSI, cells text, plain text, a ratatui Buffer's Debug, or an
    /// insta .snap of one): exit 0 equal, 1 different, 2 error.
    Diff(DiffArgs),
    /// A test card of the block characters (half, quadrant, sextant, octant): which ones this
    /// terminal draws.
    Glyphs(glyphs::GlyphsArgs),
}

pub(crate) fn parse_level(s: &str) -> Result<ColorLevel, String> {
    s.parse()
}

/// The colour level the environment asks for (`COLORTERM`, `TERM`, `NO_COLOR`).
pub(crate) fn detect_level() -> ColorLevel {
    detect_colours().level
}

/// The colour level the environment asks for, and which variable decided it (the same rule
/// as the server's, [`halfcast::ui::colour_query::rules::guess`]).
pub(crate) fn detect_colours() -> ColourChoice {
    let var = |k: &str| std::env::var(k).ok();
    halfcast::ui::colour_query::rules::guess(
        var("COLORTERM").as_deref(),
        var("TERM").as_deref(),
        var("NO_COLOR").as_deref(),
    )
}

/// An error that ends the program with a message and an exit code.
pub(crate) struct Failure {
    pub(crate) code: u8,
    pub(crate) message: String,
}

impl Failure {
    pub(crate) fn input(e: impl std::fmt::Display) -> Self {
        Self {
            code: 2,
            message: e.to_string(),
        }
    }

    pub(crate) fn io(e: impl std::fmt::Display) -> Self {
        Self {
            code: 1,
            message: e.to_string(),
        }
    }
}

/// Parses the command line and runs; the process exit code comes from here.
pub fn run() -> ExitCode {
    use clap::{CommandFactory, FromArgMatches};
    let keys = keys_help();
    let matches = Cli::command()
        .after_help(keys.clone())
        .mut_subcommand("play", |c| c.after_help(keys.clone()))
        .try_get_matches()
        .unwrap_or_else(|e| serve::flag_error(&e));
    let cli = match Cli::from_arg_matches(&matches) {
        Ok(c) => c,
        Err(e) => e.exit(),
    };
    let result = match cli.command {
        Some(Command::Render(args)) => render::render(&args),
        Some(Command::Diff(args)) => diff::diff(&args),
        Some(Command::Glyphs(args)) => glyphs::glyphs(&args),
        Some(Command::Trace(args)) => trace::trace(&args),
        Some(Command::Replay(args)) => replay::replay(&args),
        Some(Command::Play(args)) => play::play(&args, None),
        Some(Command::Record(args)) => play::play(&args.play, Some(&args.output)),
        Some(Command::Bench(args)) => bench::bench(&args),
        Some(Command::Serve(args)) => serve::serve(*args),
        Some(Command::Scores(args)) => scores::scores(&args),
        None => unknown_word::not_a_command(&Cli::command(), cli.play.map.map.as_deref())
            .and_then(|()| play::play(&cli.play, None)),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            if !f.message.is_empty() {
                eprintln!("error: {}", f.message);
            }
            ExitCode::from(f.code)
        }
    }
}

pub(crate) fn load_world(args: &MapArgs) -> Result<World, Failure> {
    match &args.map {
        None => Ok(World::default_world()),
        Some(path) => {
            let (world, warnings) = World::from_file(path, args.strict).map_err(Failure::input)?;
            for w in warnings {
                eprintln!("{w}");
            }
            Ok(world)
        }
    }
}

pub(crate) fn camera_for(world: &World, pose: &PoseArgs) -> Camera {
    let start = world.map.start;
    let pos = pose.pos.unwrap_or_else(|| start.pos());
    let angle = pose.angle.unwrap_or_else(|| start.angle_deg());
    Camera::from_angle(pos, angle, pose.fov)
}

pub(crate) fn write_output(path: Option<&PathBuf>, bytes: &[u8]) -> Result<(), Failure> {
    match path {
        Some(p) => output_file::write_whole(p, bytes)
            .map_err(|e| Failure::io(format!("cannot write {}: {e}", p.display()))),
        None => {
            let mut out = std::io::stdout().lock();
            out.write_all(bytes)
                .and_then(|()| out.flush())
                .or_else(|e| {
                    if e.kind() == std::io::ErrorKind::BrokenPipe {
                        Ok(())
                    } else {
                        Err(Failure::io(e))
                    }
                })
        }
    }
}
