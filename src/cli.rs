//! Command-line interface: parses flags, loads the world, dispatches to a command.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand, ValueEnum};
use halfcast::camera::{Camera, DEFAULT_FOV_DEG};
use halfcast::door::DoorState;
use halfcast::light::Fog;
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
        Format::Ansi => ansi::to_ansi_truecolor(&fb).into_bytes(),
        Format::Txt => text::to_text(&fb).into_bytes(),
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
