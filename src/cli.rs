//! Command-line interface: parses flags, loads the world, dispatches to a command.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand, ValueEnum};
use halfcast::camera::{Camera, DEFAULT_FOV_DEG};
use halfcast::output::{ansi, json::RayReport, text};
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
    Render(RenderArgs),
    /// Run an SSH server where everyone connected plays in one world (`ssh -p 2222 host`).
    Serve(ServeArgs),
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
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Png,
    Ansi,
    Txt,
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
        Some(Command::Serve(args)) => serve(args),
        None => Err(Failure::input(
            "the interactive view is not built yet; try `halfcast render`",
        )),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("error: {}", f.message);
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

fn render(args: &RenderArgs) -> Result<(), Failure> {
    let world = load_world(&args.map)?;
    let camera = camera_for(&world, &args.pose);
    let (cols, rows) = args.size;
    let mut fb = Framebuffer::for_cells(cols, rows);
    let cast = Scene::new(&world, camera).render_into(&mut fb, Some(usize::from(cols) / 2));
    let bytes = match args.format {
        Format::Png => fb.to_png().map_err(Failure::io)?,
        Format::Ansi => ansi::to_ansi_truecolor(&fb).into_bytes(),
        Format::Txt => text::to_text(&fb).into_bytes(),
        Format::Json => {
            let mut s = RayReport::new(&camera, &cast, usize::from(rows)).to_json();
            s.push('\n');
            s.into_bytes()
        }
    };
    write_output(args.output.as_ref(), &bytes)
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
