//! `halfcast diff`: compares two frames; exit 0 equal, 1 different, 2 error.

use std::path::PathBuf;

use clap::Args;
use halfcast::output::{ansi, screenshot};
use halfcast::termframe::{self, FrameFormat};

use super::{write_output, Failure};

#[derive(Args, Debug)]
pub(crate) struct DiffArgs {
    /// The expected frame.
    pub(crate) a: PathBuf,
    /// The actual frame.
    pub(crate) b: PathBuf,
    /// Write a highlighted picture of the differences (PNG if the name ends in .png, else ANSI):
    /// pixels when either frame is a PNG, else a screenshot of the second frame's text.
    #[arg(short, long)]
    pub(crate) out: Option<PathBuf>,
}

pub(crate) fn diff(args: &DiffArgs) -> Result<(), Failure> {
    let (a, format_a) = termframe::load(&args.a).map_err(Failure::input)?;
    let (b, format_b) = termframe::load(&args.b).map_err(Failure::input)?;
    let report = termframe::diff(&a, &b);
    print!("{}", report.summary());
    if let Some(out) = &args.out {
        let pixels = format_a == FrameFormat::Png || format_b == FrameFormat::Png;
        let picture = if pixels {
            termframe::highlight(&report, &a, &b)
        } else {
            let base = if report.size_a == report.size_b {
                &b
            } else {
                &a
            };
            screenshot::marked(base, report.differing.iter().map(|d| (d.x, d.y)))
        };
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
