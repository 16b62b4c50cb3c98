//! Command-line interface: parses flags, loads the world, dispatches to a command.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

use clap::{Args, Parser, Subcommand, ValueEnum};
use halfcast::camera::{Camera, DEFAULT_FOV_DEG};
use halfcast::door::DoorState;
use halfcast::encode::{full_frame, ColorLevel, EncodeOptions};
use halfcast::light::Fog;
use halfcast::output::{ansi, json::RayReport, text};
use halfcast::termframe;
use halfcast::tui::{self, Ending, LoopOptions, PlayOptions, TerminalError};
use halfcast::world::World;
use halfcast::{Framebuffer, Scene, Vec2};

/// Largest view `render` accepts, in cells (columns × rows).
const MAX_RENDER: (u16, u16) = (4000, 2000);

#[derive(Parser, Debug)]
#[command(
    name = "halfcast",
    version,
    about = "A raycasting 3D engine that lives in the terminal"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
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
    Serve(ServeArgs),
    /// Compare two frames (PNG, ANSI, cells text or plain text): exit 0 equal, 1 different, 2 error.
    Diff(DiffArgs),
}

#[derive(Args, Debug)]
struct ServeArgs {
    #[command(flatten)]
    map: MapArgs,
    /// Address to listen on (port 0 picks a free one; the log says which).
    #[arg(long, default_value = "127.0.0.1:2222")]
    listen: std::net::SocketAddr,
    /// Ed25519 host key: read if it exists, else generated there with mode 0600.
    #[arg(long, default_value = "halfcast_host_ed25519")]
    host_key: PathBuf,
    /// Require this password (default: no authentication).
    #[arg(long, conflicts_with = "authorized_keys")]
    password: Option<String>,
    /// Accept only the public keys in this OpenSSH authorized_keys file.
    #[arg(long)]
    authorized_keys: Option<PathBuf>,
    /// Most concurrent connections.
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    max_sessions: u32,
    /// Most concurrent connections from one IP address.
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    max_per_ip: u32,
    /// Close a connection after this many seconds without a keystroke.
    #[arg(long, default_value_t = 600, value_parser = clap::value_parser!(u64).range(1..=86_400))]
    idle_timeout: u64,
    /// Frames per second per session (slow links get fewer).
    #[arg(long, default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..=240))]
    fps: u32,
    /// No connect/disconnect log on stderr.
    #[arg(long)]
    quiet: bool,
}

#[derive(Args, Debug)]
struct ReplayArgs {
    /// The recording (.hcr).
    file: PathBuf,
    /// Frames to write, e.g. `0,10,20` or `0-19` (frame N is drawn after N+1 steps).
    #[arg(long, value_parser = crate::replay_cli::parse_frames)]
    frames: Option<std::vec::Vec<usize>>,
    /// What to write: per-frame files, or `cast` (asciicast v2 of the whole run).
    #[arg(long, value_enum)]
    format: Option<crate::replay_cli::ReplayFormat>,
    /// Folder for frame files, or the file for `--format cast` (default: standard output).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Colour level of `ansi`, `cast` and on-screen output (default truecolor, the same anywhere).
    #[arg(long, value_parser = parse_level, default_value = "truecolor")]
    colors: ColorLevel,
    /// Play only frames 0..=N (on screen or as `cast`): the run ends showing frame N.
    #[arg(long, value_name = "N")]
    until_frame: Option<usize>,
}

#[derive(Args, Debug)]
struct DiffArgs {
    /// The expected frame.
    a: PathBuf,
    /// The actual frame.
    b: PathBuf,
    /// Write a highlighted picture of the differences (PNG if the name ends in .png, else ANSI).
    #[arg(short, long)]
    out: Option<PathBuf>,
}

#[derive(Args, Debug)]
struct BenchArgs {
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
    /// Encode this directory of PNG frames (sorted by name; each W×2H px = W×H cells) instead.
    #[arg(long, value_name = "DIR")]
    frames: Option<PathBuf>,
    /// Write each encoded frame as OUT/frame-NNN.ansi (with --frames).
    #[arg(long, value_name = "OUT", requires = "frames")]
    dump: Option<PathBuf>,
    /// Colour level (default: all four; with --frames: truecolor).
    #[arg(long, value_parser = parse_level)]
    colors: Option<ColorLevel>,
    /// Frames per replayed path after the first one.
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u16).range(1..=5000))]
    frame_count: u16,
    /// Ordered dithering at 256 and 16 colours.
    #[arg(long)]
    dither: bool,
    /// Lossy: don't resend cells whose colours moved less than N (0–255).
    #[arg(long, value_name = "N")]
    delta: Option<u8>,
    /// Row-planner beam width (1 = greedy), for comparing planner settings.
    #[arg(long, hide = true)]
    beam: Option<usize>,
}

fn parse_level(s: &str) -> Result<ColorLevel, String> {
    s.parse()
}

/// The colour level the environment asks for (`COLORTERM`, `TERM`, `NO_COLOR`).
fn detect_level() -> ColorLevel {
    let var = |k: &str| std::env::var(k).ok();
    ColorLevel::detect(
        var("COLORTERM").as_deref(),
        var("TERM").as_deref(),
        var("NO_COLOR").as_deref(),
    )
}

#[derive(Args, Debug)]
struct MapArgs {
    /// A .cub map file (default: the embedded map).
    map: Option<PathBuf>,
    /// Treat a missing or unreadable texture as an error instead of a warning.
    #[arg(long)]
    strict: bool,
}

#[derive(Args, Debug)]
struct PoseArgs {
    /// Camera position X,Y in cells (default: the map's start).
    #[arg(long, value_parser = parse_pos, allow_hyphen_values = true)]
    pos: Option<Vec2>,
    /// Facing in degrees: 0 = east, 90 = north (default: the map's start).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_finite)]
    angle: Option<f64>,
    /// Horizontal field of view in degrees (0 < FOV < 180).
    #[arg(long, default_value_t = DEFAULT_FOV_DEG, value_parser = parse_fov)]
    fov: f64,
}

#[derive(Args, Debug)]
struct RenderArgs {
    #[command(flatten)]
    map: MapArgs,
    #[command(flatten)]
    pose: PoseArgs,
    /// View size in terminal cells, COLSxROWS (the PNG is COLS × 2·ROWS pixels).
    #[arg(long, default_value = "120x40", value_parser = parse_size)]
    size: (u16, u16),
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Png)]
    format: Format,
    /// Write here instead of standard output.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Colour level for `--format ansi` (default: detected from COLORTERM, TERM, NO_COLOR).
    #[arg(long, value_parser = parse_level)]
    colors: Option<ColorLevel>,
    /// Ordered dithering at 256 and 16 colours (`--format ansi`).
    #[arg(long)]
    dither: bool,
    #[command(flatten)]
    world: WorldArgs,
}

/// View, light, time and door options (world features).
#[derive(Args, Debug)]
struct WorldArgs {
    /// Look up (+) or down (-), in degrees (-45 to 45); shifts the horizon.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_pitch)]
    pitch: f64,
    /// Eye height in wall heights: 0.5 standing, lower crouches, higher jumps (0.05 to 0.95).
    #[arg(long, default_value_t = halfcast::view::STANDING_EYE, value_parser = parse_eye)]
    z: f64,
    /// Fog colour and density R,G,B,DENSITY (replaces the map's FOG line).
    #[arg(long, value_parser = parse_fog)]
    fog: Option<Fog>,
    /// Night: dark, with the view lit near the player.
    #[arg(long)]
    night: bool,
    /// Game time in seconds, which picks animated sprites' frames.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_finite)]
    time: f64,
    /// How far every door is open, 0 (shut) to 1 (open).
    #[arg(long, default_value_t = 0.0, value_parser = parse_unit)]
    door_open: f64,
}

#[derive(Args, Debug)]
struct PlayArgs {
    #[command(flatten)]
    map: MapArgs,
    #[command(flatten)]
    pose: PoseArgs,
    /// Target frames per second (1 to 1000).
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u32).range(1..=1000))]
    fps: u32,
    /// Do not capture the mouse (keeps the terminal's own text selection working).
    #[arg(long)]
    no_mouse: bool,
    /// Print frame-time statistics (fps, render and draw ms) to stderr on exit.
    #[arg(long)]
    frame_stats: bool,
    /// Colour level (default: detected from COLORTERM, TERM, NO_COLOR).
    #[arg(long, value_parser = parse_level)]
    colors: Option<ColorLevel>,
    /// Ordered dithering at 256 and 16 colours, so walls don't band.
    #[arg(long)]
    dither: bool,
    /// Lossy: don't resend a cell whose colours moved less than N (0-255) since it was sent.
    #[arg(long, value_name = "N")]
    delta: Option<u8>,
    /// Cap the output rate (e.g. 2mbit, 500kbit, 1MB): the frame rate drops to fit.
    #[arg(long, value_name = "RATE", value_parser = halfcast::encode::parse_rate)]
    max_bandwidth: Option<u64>,
    /// With --max-bandwidth: also step down the colour level when the cap allows under 12 fps.
    #[arg(long, requires = "max_bandwidth")]
    adapt_colors: bool,
}

#[derive(Args, Debug)]
struct RecordArgs {
    #[command(flatten)]
    play: PlayArgs,
    /// Where to write the recording (.hcr).
    #[arg(short, long)]
    output: PathBuf,
}

impl PlayArgs {
    /// `halfcast` with no command: the embedded map, default pose and pacing.
    fn defaults() -> Self {
        Self {
            map: MapArgs {
                map: None,
                strict: false,
            },
            pose: PoseArgs {
                pos: None,
                angle: None,
                fov: DEFAULT_FOV_DEG,
            },
            fps: 60,
            no_mouse: false,
            frame_stats: false,
            colors: None,
            dither: false,
            delta: None,
            max_bandwidth: None,
            adapt_colors: false,
        }
    }
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    /// The framebuffer, COLS × 2·ROWS pixels.
    Png,
    /// The half-block frame as the terminal receives it (full redraw).
    Ansi,
    /// Plain ASCII shade ramp, one character per cell.
    Txt,
    /// Colour-aware text for code review: every cell's glyph, fg and bg, one line per row.
    Cells,
    /// The ray data: camera, per-column hits, the centre ray's DDA trace.
    Json,
}

fn parse_finite(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("'{s}' is not a finite number"))
    }
}

fn parse_pos(s: &str) -> Result<Vec2, String> {
    let (x, y) = s
        .split_once(',')
        .ok_or_else(|| format!("'{s}' is not X,Y"))?;
    Ok(Vec2::new(parse_finite(x)?, parse_finite(y)?))
}

fn parse_fov(s: &str) -> Result<f64, String> {
    let v = parse_finite(s)?;
    if v > 0.0 && v < 180.0 {
        Ok(v)
    } else {
        Err(format!(
            "field of view {v} must be between 0 and 180 degrees (exclusive)"
        ))
    }
}

fn parse_pitch(s: &str) -> Result<f64, String> {
    use halfcast::view::MAX_PITCH_DEG;
    let v = parse_finite(s)?;
    if v.abs() <= MAX_PITCH_DEG {
        Ok(v)
    } else {
        Err(format!(
            "pitch {v} must be between -{MAX_PITCH_DEG} and {MAX_PITCH_DEG} degrees"
        ))
    }
}

fn parse_eye(s: &str) -> Result<f64, String> {
    use halfcast::view::EYE_RANGE;
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

fn parse_unit(s: &str) -> Result<f64, String> {
    let v = parse_finite(s)?;
    if (0.0..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{v} must be between 0 and 1"))
    }
}

fn parse_fog(s: &str) -> Result<Fog, String> {
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

fn parse_size(s: &str) -> Result<(u16, u16), String> {
    let (c, r) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("'{s}' is not COLSxROWS"))?;
    let num = |t: &str| {
        t.trim()
            .parse::<u16>()
            .map_err(|_| format!("'{s}' is not COLSxROWS"))
    };
    let (c, r) = (num(c)?, num(r)?);
    if c == 0 || r == 0 || c > MAX_RENDER.0 || r > MAX_RENDER.1 {
        return Err(format!(
            "size {c}x{r} is out of range (1x1 to {}x{})",
            MAX_RENDER.0, MAX_RENDER.1
        ));
    }
    Ok((c, r))
}

/// An error that ends the program with a message and an exit code.
struct Failure {
    code: u8,
    message: String,
}

impl Failure {
    fn input(e: impl std::fmt::Display) -> Self {
        Self {
            code: 2,
            message: e.to_string(),
        }
    }

    fn io(e: impl std::fmt::Display) -> Self {
        Self {
            code: 1,
            message: e.to_string(),
        }
    }
}

/// Parses the command line and runs; the process exit code comes from here.
pub fn run() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Some(Command::Render(args)) => render(&args),
        Some(Command::Diff(args)) => diff(&args),
        Some(Command::Replay(args)) => replay(&args),
        Some(Command::Play(args)) => play(&args, None),
        Some(Command::Record(args)) => play(&args.play, Some(&args.output)),
        Some(Command::Bench(args)) => bench(&args),
        Some(Command::Serve(args)) => serve(args),
        None => play(&PlayArgs::defaults(), None),
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

fn load_world(args: &MapArgs) -> Result<World, Failure> {
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

fn camera_for(world: &World, pose: &PoseArgs) -> Camera {
    let start = world.map.start;
    let pos = pose.pos.unwrap_or_else(|| start.pos());
    let angle = pose.angle.unwrap_or_else(|| start.angle_deg());
    Camera::from_angle(pos, angle, pose.fov)
}

fn play(args: &PlayArgs, record: Option<&PathBuf>) -> Result<(), Failure> {
    let world = load_world(&args.map)?;
    let camera = camera_for(&world, &args.pose);
    if !world.map.is_walkable(camera.pos) {
        return Err(Failure::input(format!(
            "--pos {},{} is not on a floor cell of {}",
            camera.pos.x, camera.pos.y, world.map.name
        )));
    }
    let mut encode = EncodeOptions::new(args.colors.unwrap_or_else(detect_level));
    encode.dither = args.dither;
    encode.delta = args.delta;
    let options = PlayOptions {
        looping: LoopOptions {
            fps: args.fps,
            encode,
            max_bandwidth: args.max_bandwidth,
            adapt_colours: args.adapt_colors,
            record: record.is_some(),
        },
        mouse: !args.no_mouse,
    };
    let (ending, stats, recording) =
        tui::play(Arc::new(world), camera, options).map_err(terminal_failure)?;
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
            seed: 0,
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
    }
    ending_result(ending)
}

fn terminal_failure(e: TerminalError) -> Failure {
    match e {
        TerminalError::NotATerminal(_) => Failure::input(e),
        TerminalError::Io(_) => Failure::io(e),
    }
}

fn ending_result(ending: Ending) -> Result<(), Failure> {
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

fn render(args: &RenderArgs) -> Result<(), Failure> {
    let world = load_world(&args.map)?;
    let camera = camera_for(&world, &args.pose);
    let (cols, rows) = args.size;
    let mut fb = Framebuffer::for_cells(cols, rows);
    let opts = &args.world;
    let mut doors = DoorState::new(&world.map);
    for cell in doors.cells().to_vec() {
        doors.set_open(cell, opts.door_open);
    }
    let mut scene = Scene::new(&world, camera)
        .with_view(halfcast::View::new(opts.pitch, opts.z))
        .with_doors(&doors)
        .at_time(opts.time);
    if let Some(fog) = opts.fog {
        scene.light.fog = Some(fog);
    }
    scene.light.night |= opts.night;
    let frame = scene.render_frame(&mut fb, Some(usize::from(cols) / 2));
    let cast = frame.cast;
    let bytes = match args.format {
        Format::Png => fb.to_png().map_err(Failure::io)?,
        Format::Ansi => {
            let mut opts = EncodeOptions::new(args.colors.unwrap_or_else(detect_level));
            opts.dither = args.dither;
            full_frame(&fb, &opts)
        }
        Format::Txt => text::to_text(&fb).into_bytes(),
        Format::Cells => {
            termframe::to_cells_text(&termframe::TermFrame::from_framebuffer(&fb)).into_bytes()
        }
        Format::Json => {
            let mut s = RayReport::new(&camera, &cast, usize::from(rows))
                .with_sprites(&world, &camera, &frame.sprites)
                .to_json();
            s.push('\n');
            s.into_bytes()
        }
    };
    write_output(args.output.as_ref(), &bytes)
}

fn replay(args: &ReplayArgs) -> Result<(), Failure> {
    use crate::replay_cli::{asciicast, read_replay, replay_world, write_frames, ReplayFormat};
    let failure = |f: crate::replay_cli::ReplayFailure| Failure {
        code: f.code,
        message: f.message,
    };
    let mut replay = read_replay(&args.file).map_err(failure)?;
    if let Some(n) = args.until_frame {
        crate::replay_cli::cut_after(&mut replay, n).map_err(failure)?;
    }
    let world = replay_world(&replay, &args.file).map_err(failure)?;
    match (args.format, &args.frames) {
        (Some(ReplayFormat::Cast), _) => write_output(
            args.out.as_ref(),
            asciicast(&replay, world, args.colors).as_bytes(),
        ),
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

fn diff(args: &DiffArgs) -> Result<(), Failure> {
    let (a, _) = termframe::load(&args.a).map_err(Failure::input)?;
    let (b, _) = termframe::load(&args.b).map_err(Failure::input)?;
    let report = termframe::diff(&a, &b);
    print!("{}", report.summary());
    if let Some(out) = &args.out {
        let picture = report.highlight(&a, &b);
        let bytes = if out
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("png"))
        {
            picture.to_png().map_err(Failure::io)?
        } else {
            ansi::to_ansi_truecolor(&picture).into_bytes()
        };
        write_output(Some(out), &bytes)?;
    }
    if report.is_equal() {
        Ok(())
    } else {
        Err(Failure {
            code: 1,
            message: String::new(),
        })
    }
}

fn serve(args: ServeArgs) -> Result<(), Failure> {
    use halfcast::serve::{auth::AuthMode, run_until_signal, ServeConfig};
    let world = load_world(&args.map)?;
    let auth = match (args.password, &args.authorized_keys) {
        (Some(p), _) if p.is_empty() => return Err(Failure::input("--password must not be empty")),
        (Some(p), _) => AuthMode::Password(p),
        (None, Some(path)) => AuthMode::from_authorized_keys(path).map_err(Failure::input)?,
        (None, None) => AuthMode::None,
    };
    let mut config = ServeConfig::local(args.listen, args.host_key);
    config.auth = auth;
    config.max_sessions = args.max_sessions as usize;
    config.max_per_ip = args.max_per_ip as usize;
    config.idle_timeout = std::time::Duration::from_secs(args.idle_timeout);
    config.fps = args.fps;
    config.quiet = args.quiet;
    run_until_signal(config, world).map_err(Failure::input)
}

fn write_output(path: Option<&PathBuf>, bytes: &[u8]) -> Result<(), Failure> {
    match path {
        Some(p) => std::fs::write(p, bytes)
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

fn bench(args: &BenchArgs) -> Result<(), Failure> {
    use crate::bench_cli::{run_default, run_frames, table, BenchPlan};
    let plan = BenchPlan {
        frames: usize::from(args.frame_count),
        levels: args.colors.into_iter().collect(),
        dither: args.dither,
        delta: args.delta,
        beam: args.beam,
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
    } else {
        table(&report)
    };
    write_output(None, text.as_bytes())
}
