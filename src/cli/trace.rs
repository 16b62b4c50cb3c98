//! `halfcast trace`: a figure of one column's DDA traversal, as SVG or PNG (see
//! `halfcast::output::figure`). Takes `render`'s map, pose and size flags.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use halfcast::output::figure::ColumnCast;
use halfcast::world::door::DoorState;

use super::options::{parse_eye, parse_pitch, parse_unit, MapArgs, PoseArgs};
use super::pose_check::{check_pos, PoseUse};
use super::render::parse_size;
use super::{camera_for, load_world, write_output, Failure};

#[derive(Args, Debug)]
pub(crate) struct TraceArgs {
    #[command(flatten)]
    pub(crate) map: MapArgs,
    #[command(flatten)]
    pub(crate) pose: PoseArgs,
    /// View size in terminal cells, COLSxROWS (the column's ray depends on COLS; heights on ROWS).
    #[arg(long, default_value = "120x40", allow_hyphen_values = true, value_parser = parse_size)]
    pub(crate) size: (u16, u16),
    /// The screen column whose ray is drawn, 0 (left) to COLS−1.
    #[arg(long)]
    pub(crate) column: usize,
    /// Figure format (default: from the output file's extension, else svg).
    #[arg(long, value_enum)]
    pub(crate) format: Option<FigureFormat>,
    /// Write here instead of standard output.
    #[arg(short, long)]
    pub(crate) output: Option<PathBuf>,
    /// Look up (+) or down (-), in degrees (-45 to 45): moves the window of rows on `Hz` maps.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_pitch)]
    pub(crate) pitch: f64,
    /// Eye height in wall heights above the floor (0.05 to 0.95).
    #[arg(long, default_value_t = halfcast::render::view::STANDING_EYE, value_parser = parse_eye)]
    pub(crate) z: f64,
    /// How far every door is open, 0 (shut) to 1 (open).
    #[arg(long, default_value_t = 0.0, value_parser = parse_unit)]
    pub(crate) door_open: f64,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum FigureFormat {
    /// Plain SVG: shapes and text, no embedded raster.
    Svg,
    /// The same drawing painted into a PNG.
    Png,
}

impl TraceArgs {
    fn figure_format(&self) -> FigureFormat {
        self.format.unwrap_or_else(|| {
            let png = self
                .output
                .as_ref()
                .and_then(|p| p.extension())
                .is_some_and(|e| e.eq_ignore_ascii_case("png"));
            if png {
                FigureFormat::Png
            } else {
                FigureFormat::Svg
            }
        })
    }
}

pub(crate) fn trace(args: &TraceArgs) -> Result<(), Failure> {
    let world = load_world(&args.map)?;
    let map = &world.map;
    let camera = camera_for(&world, &args.pose);
    let (cols, rows) = (usize::from(args.size.0), usize::from(args.size.1));
    if args.column >= cols {
        return Err(Failure::input(format!(
            "column {} is out of range: a {cols}-column view has columns 0 to {}",
            args.column,
            cols - 1
        )));
    }
    check_pos(map, camera.pos, PoseUse::View)?;
    let (i, j) = (camera.pos.x.floor() as i64, camera.pos.y.floor() as i64);
    if map.has_heights() {
        halfcast::game::pose::still_eye(map, camera.pos, args.z).map_err(Failure::input)?;
    }
    let mut doors = DoorState::new(map);
    for cell in doors.cells().to_vec() {
        doors.set_open(cell, args.door_open);
    }
    let view = halfcast::View::new(args.pitch, args.z).on_ground(map.floor_height(i, j));
    let column = ColumnCast::new(map, &doors, &camera, &view, (cols, rows), args.column);
    let figure = column.figure(map, &camera, cols);
    let bytes = match args.figure_format() {
        FigureFormat::Svg => figure.to_svg().into_bytes(),
        FigureFormat::Png => figure.to_framebuffer().to_png().map_err(Failure::io)?,
    };
    write_output(args.output.as_ref(), &bytes)
}
