//! `halfcast play` and `halfcast record`: the interactive game, optionally recording its input.

use std::path::PathBuf;
use std::sync::Arc;

use clap::Args;
use halfcast::camera::Camera;
use halfcast::encode::{ColorLevel, ColourChoice, EncodeOptions};
use halfcast::game::Speeds;
use halfcast::tui::config::Config;
use halfcast::tui::{self, Ending, LoopOptions, PlayOptions, Setup, Stage, TerminalError};
use halfcast::ui::layout::Toggles;

use super::options::{MapArgs, PoseArgs};
use super::pose_check::{check_pos, PoseUse};
use super::{camera_for, detect_colours, load_world, parse_level, write_output, Failure};

#[derive(Args, Debug)]
pub(crate) struct PlayArgs {
    #[command(flatten)]
    pub(crate) map: MapArgs,
    /// Maps played after the first, in order (a campaign): each level's exit leads to the next.
    #[arg(value_name = "NEXT_MAP")]
    pub(crate) then: Vec<PathBuf>,
    #[command(flatten)]
    pub(crate) pose: PoseArgs,
    /// Seed for the creatures' random choices (default: a new one each run; recordings keep it).
    #[arg(long, value_name = "N")]
    pub(crate) seed: Option<u64>,
    /// Target frames per second (1 to 1000).
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub(crate) fps: u32,
    /// Do not capture the mouse (keeps the terminal's own text selection working).
    #[arg(long)]
    pub(crate) no_mouse: bool,
    /// Print frame-time statistics (fps, render and draw ms) to stderr on exit.
    #[arg(long)]
    pub(crate) frame_stats: bool,
    /// Colour level (default: NO_COLOR, COLORTERM, else ask the terminal, else the TERM rule).
    #[arg(long, value_parser = parse_level)]
    pub(crate) colors: Option<ColorLevel>,
    /// Block characters for the view: half (default), quadrant, sextant or octant (the U key
    /// cycles them, skipping octant inside tmux, which drops those characters, unless you start
    /// at octant; `halfcast glyphs` shows which your terminal draws).
    #[arg(long, value_parser = super::render::parse_glyphs)]
    pub(crate) glyphs: Option<halfcast::Glyphs>,
    /// Lossy: don't resend a cell whose colours moved less than N (0-255) since it was sent.
    #[arg(long, value_name = "N")]
    pub(crate) delta: Option<u8>,
    /// Cap the output rate (e.g. 2mbit, 500kbit, 1MB): the frame rate drops to fit.
    #[arg(long, value_name = "RATE", value_parser = halfcast::encode::parse_rate)]
    pub(crate) max_bandwidth: Option<u64>,
    /// With --max-bandwidth: also step down the colour level when the cap allows under 12 fps.
    #[arg(long, requires = "max_bandwidth")]
    pub(crate) adapt_colors: bool,
    /// Turning speed in degrees per second (default 2.6 rad/s, about 149; also `turn` in the config file).
    #[arg(long, value_name = "DEG_PER_S")]
    pub(crate) turn_speed: Option<f64>,
    /// Walking speed in cells per second (default 3; also `move` in the config file).
    #[arg(long, value_name = "CELLS_PER_S")]
    pub(crate) move_speed: Option<f64>,
    /// Config file (default: $XDG_CONFIG_HOME/halfcast/config.toml, if it exists).
    #[arg(long, value_name = "FILE")]
    pub(crate) config: Option<PathBuf>,
    /// Print the default config file (keys, speeds, colours, panes) and exit.
    #[arg(long)]
    pub(crate) print_config: bool,
}

#[derive(Args, Debug)]
pub(crate) struct RecordArgs {
    #[command(flatten)]
    pub(crate) play: PlayArgs,
    /// Where to write the recording (.hcr).
    #[arg(short, long)]
    pub(crate) output: PathBuf,
}

/// The config file (`--config`, or the default path if that exists) with the flags applied.
fn settings(args: &PlayArgs) -> Result<Config, Failure> {
    let mut config = match (&args.config, Config::default_path()) {
        (Some(path), _) => Config::load(path, true),
        (None, Some(path)) => Config::load(&path, false),
        (None, None) => Ok(Config::default()),
    }
    .map_err(Failure::input)?;
    if let Some(walk) = args.move_speed {
        config.speeds = Speeds::new(walk, config.speeds.turn_deg())
            .map_err(|m| Failure::input(format!("--move-speed: {m}")))?;
    }
    if let Some(turn) = args.turn_speed {
        config.speeds = Speeds::new(config.speeds.move_cells, turn)
            .map_err(|m| Failure::input(format!("--turn-speed: {m}")))?;
    }
    Ok(config)
}

pub(crate) fn play(args: &PlayArgs, record: Option<&PathBuf>) -> Result<(), Failure> {
    if args.print_config {
        print!("{}", Config::default().to_toml());
        return Ok(());
    }
    let config = settings(args)?;
    if record.is_some() && !args.then.is_empty() {
        return Err(Failure::input(format!(
            "record plays one map, got {}",
            1 + args.then.len()
        )));
    }
    let stages = stages(args)?;
    let seed = args.seed.unwrap_or_else(fresh_seed);
    let colour = match (args.colors, config.colors) {
        (Some(level), _) => ColourChoice::flag(level),
        (None, Some(level)) => ColourChoice::config(level),
        (None, None) => detect_colours(),
    };
    let mut encode = EncodeOptions::new(colour.level);
    encode.delta = args.delta;
    let options = PlayOptions {
        looping: LoopOptions {
            fps: args.fps,
            encode,
            max_bandwidth: args.max_bandwidth,
            adapt_colours: args.adapt_colors,
            record: record.is_some(),
            colour_reason: colour.reason,
        },
        mouse: !args.no_mouse,
        setup: Setup {
            keys: config.keys.clone(),
            speeds: config.speeds,
            glyphs: args.glyphs.unwrap_or(config.glyphs),
            toggles: Toggles {
                minimap: config.minimap,
                debug: config.ray_pane,
                help: false,
            },
        },
        colour,
    };
    let camera = stages[0].camera;
    let (ending, stats, recording) = tui::play(stages, seed, options).map_err(terminal_failure)?;
    if args.frame_stats {
        eprintln!("halfcast: {}", stats.summary());
    }
    if let (Some(path), Some(rec)) = (record, recording) {
        let header = halfcast::replay::Header {
            map: args
                .map
                .map
                .as_ref()
                .map_or(halfcast::replay::MapSource::Embedded, |p| {
                    halfcast::replay::MapSource::File(p.display().to_string())
                }),
            pos: camera.pos,
            angle_deg: camera.angle_deg(),
            fov_deg: camera.fov_deg(),
            size: rec.size,
            fps: args.fps,
            seed,
            speeds: config.speeds,
            glyphs: args.glyphs.unwrap_or(config.glyphs),
        };
        let replay = halfcast::replay::Replay {
            header,
            frames: rec.frames,
        };
        write_output(Some(path), replay.to_jsonl().as_bytes())?;
        eprintln!(
            "halfcast: recorded {} frames into {}",
            replay.frames.len(),
            path.display()
        );
        if replay.frames.len() >= halfcast::replay::default_max_frames(args.fps) {
            eprintln!(
                "halfcast: the recording stopped at its limit ({} s at {} fps); the rest of the \
                 game was not recorded",
                halfcast::replay::LONGEST_RECORDING_SECS,
                args.fps
            );
        }
    }
    ending_result(ending)
}

/// Every map of the campaign loaded and checked before the terminal is taken over, so a bad
/// third level is an error now rather than a crash mid-game. `--pos`/`--angle` place the first.
fn stages(args: &PlayArgs) -> Result<Vec<Stage>, Failure> {
    let mut out = Vec::new();
    let paths = std::iter::once(args.map.map.clone()).chain(args.then.iter().cloned().map(Some));
    for (i, map) in paths.enumerate() {
        let map_args = MapArgs {
            map,
            strict: args.map.strict,
        };
        let world = load_world(&map_args)?;
        let camera = if i == 0 {
            camera_for(&world, &args.pose)
        } else {
            let start = world.map.start;
            Camera::from_angle(start.pos(), start.angle_deg(), args.pose.fov)
        };
        check_pos(&world.map, camera.pos, PoseUse::Player)?;
        halfcast::game::pose::player_start(&world.map, camera.pos, "--pos")
            .map_err(Failure::input)?;
        out.push(Stage {
            name: world.map.name.clone(),
            world: Arc::new(world),
            camera,
        });
    }
    Ok(out)
}

/// A seed that differs from run to run (the clock's nanoseconds), for creatures that wander
/// differently each game; `--seed` and recordings pin it.
fn fresh_seed() -> u64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos() as u64)
}

pub(crate) fn terminal_failure(e: TerminalError) -> Failure {
    match e {
        TerminalError::NotATerminal(_) => Failure::input(e),
        TerminalError::Io(_) => Failure::io(e),
    }
}

pub(crate) fn ending_result(ending: Ending) -> Result<(), Failure> {
    match ending {
        Ending::Quit => Ok(()),
        // Silent, like a shell's own signal exits: the terminal may be one nobody reads, and
        // a message on it could block forever. The exit code (128 + n) says what happened.
        Ending::Signal(sig) => Err(Failure {
            code: 128u8.saturating_add(u8::try_from(sig).unwrap_or(0)),
            message: String::new(),
        }),
    }
}
