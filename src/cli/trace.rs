//! `halfcast trace`: a figure of one column's DDA traversal, as SVG or PNG (see
//! `halfcast::output::figure`). Takes `render`'s map, pose and size flags; the checks and the
//! cast are `halfcast::trace_query`'s, which the browser's `/trace.*` routes share.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use halfcast::trace_query::TraceQuery;

use super::options::{parse_eye, parse_pitch, parse_unit, MapArgs, PoseArgs};
use super::render::parse_size;
use super::{load_world, write_output, Failure};

#[derive(Args, Debug)]
pub(crate) struct TraceArgs {
    #[command(flatten)]
    pub(crate) map: MapArgs,
    #[command(flatten)]
    pub(crate) pose: PoseArgs,
    /// View size in terminal cells, COLSxROWS (the column's ray depends on COLS; heights on ROWS).
    #[arg(long, default_value = "120x40", value_parser = parse_size)]
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
    let query = TraceQuery {
        pos: args.pose.pos,
        angle: args.pose.angle,
        fov: args.pose.fov,
        size: args.size,
        column: args.column,
        pitch: args.pitch,
        z: args.z,
        door_open: args.door_open,
    };
    let ray = query.trace(&world).map_err(Failure::input)?;
    let bytes = match args.figure_format() {
        FigureFormat::Svg => ray.svg(&world.map).into_bytes(),
        FigureFormat::Png => ray.png(&world.map).map_err(Failure::io)?,
    };
    write_output(args.output.as_ref(), &bytes)
}
