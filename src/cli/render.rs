//! `halfcast render`: one frame, headless, as PNG, ANSI, text, cells text or ray JSON.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use halfcast::encode::{full_frame, ColorLevel, EncodeOptions};
use halfcast::output::{json::RayReport, text};
use halfcast::termframe;
use halfcast::world::door::DoorState;
use halfcast::{Framebuffer, Glyphs, Scene};

use super::options::{MapArgs, PoseArgs, WorldArgs};
use super::{camera_for, detect_level, load_world, parse_level, write_output, Failure};
/// `COLSxROWS`, 1×1 to the largest frame `diff` reads (shared with the web's ray addresses).
pub(crate) use halfcast::trace_query::values::parse_size;

#[derive(Args, Debug)]
pub(crate) struct RenderArgs {
    #[command(flatten)]
    pub(crate) map: MapArgs,
    #[command(flatten)]
    pub(crate) pose: PoseArgs,
    /// View size in terminal cells, COLSxROWS (the PNG is COLS × 2·ROWS pixels).
    #[arg(long, default_value = "120x40", value_parser = parse_size)]
    pub(crate) size: (u16, u16),
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Png)]
    pub(crate) format: Format,
    /// Write here instead of standard output.
    #[arg(short, long)]
    pub(crate) output: Option<PathBuf>,
    /// Colour level for `--format ansi` (default: detected from COLORTERM, TERM, NO_COLOR).
    #[arg(long, value_parser = parse_level)]
    pub(crate) colors: Option<ColorLevel>,
    /// Block characters for the view: half (1×2 pixels a cell), quadrant (2×2), sextant (2×3)
    /// or octant (2×4). PNG then shows each cell's mask in its two colours; JSON stays per cell.
    #[arg(long, default_value = "half", value_parser = parse_glyphs)]
    pub(crate) glyphs: Glyphs,
    #[command(flatten)]
    pub(crate) world: WorldArgs,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Format {
    /// The framebuffer, COLS × 2·ROWS pixels.
    Png,
    /// The half-block frame as the terminal receives it (full redraw).
    Ansi,
    /// Plain ASCII shade ramp, one character per cell.
    Txt,
    /// Text for code review: the glyph grid, then style runs (every colour and attribute).
    Cells,
    /// The ray data: camera, per-column hits, the centre ray's DDA trace.
    Json,
}

pub(crate) fn parse_glyphs(s: &str) -> Result<Glyphs, String> {
    s.parse()
}

pub(crate) fn render(args: &RenderArgs) -> Result<(), Failure> {
    let world = load_world(&args.map)?;
    let camera = camera_for(&world, &args.pose);
    if world.map.has_heights() {
        // Flat maps keep accepting every --z they always did (up to 0.95).
        halfcast::game::pose::still_eye(&world.map, camera.pos, args.world.z)
            .map_err(Failure::input)?;
    }
    let (cols, rows) = args.size;
    // The ray report stays one ray per cell column; the pictures are at the glyphs' sub-grid.
    let glyphs = if args.format == Format::Json {
        Glyphs::Half
    } else {
        args.glyphs
    };
    let mut fb = Framebuffer::for_glyphs(cols, rows, glyphs);
    let opts = &args.world;
    let mut doors = DoorState::new(&world.map);
    for cell in doors.cells().to_vec() {
        doors.set_open(cell, opts.door_open);
    }
    let ground = world
        .map
        .floor_height(camera.pos.x.floor() as i64, camera.pos.y.floor() as i64);
    // The game's items and creatures as the level starts (what a player sees on the first frame).
    let level_sprites = halfcast::game::Level::new(&world.map, 0).sprites(&world);
    let mut scene = Scene::new(&world, camera)
        // `--z` is the eye's height above the floor of the camera's cell.
        .with_view(halfcast::View::new(opts.pitch, opts.z).on_ground(ground))
        .with_doors(&doors)
        .with_sprites(&level_sprites)
        .at_time(opts.time);
    if let Some(fog) = opts.fog {
        scene.light.fog = Some(fog);
    }
    scene.light.night |= opts.night;
    // The traced column: the centre cell's (its left sub-column when cells are two wide).
    let traced = usize::from(cols) / 2 * glyphs.cell_size().0;
    let frame = scene.render_frame(&mut fb, Some(traced));
    let cast = frame.cast;
    let bytes = match args.format {
        Format::Png => halfcast::output::glyph_picture::shown_picture(&fb)
            .to_png()
            .map_err(Failure::io)?,
        Format::Ansi => {
            let opts = EncodeOptions::new(args.colors.unwrap_or_else(detect_level));
            full_frame(&fb, &opts)
        }
        Format::Txt => {
            text::to_text(&halfcast::encode::glyph_frame::as_half_blocks(&fb)).into_bytes()
        }
        Format::Cells => termframe::to_cells_text(&termframe::TermFrame::from(&fb)).into_bytes(),
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
