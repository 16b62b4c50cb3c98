//! `halfcast diff`: compares two frames; exit 0 equal, 1 different, 2 error.

use std::path::PathBuf;

use clap::Args;
use halfcast::output::ansi;
use halfcast::termframe;

use super::{write_output, Failure};

#[derive(Args, Debug)]
pub(crate) struct DiffArgs {
    /// The expected frame.
    pub(crate) a: PathBuf,
    /// The actual frame.
    pub(crate) b: PathBuf,
    /// Write a highlighted picture of the differences (PNG if the name ends in .png, else ANSI).
    #[arg(short, long)]
    pub(crate) out: Option<PathBuf>,
}

pub(crate) fn diff(args: &DiffArgs) -> Result<(), Failure> {
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
