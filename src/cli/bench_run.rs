//! `halfcast bench`: replays camera paths (or a directory of PNG frames) through the encoder and
//! stock ratatui, timing and counting bytes. The clock lives here, at the binary's edge.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use halfcast::bench::scielab::{self, Figures};
use halfcast::bench::{
    camera_path, BenchScene, HalfcastFigures, RatatuiFigures, RatatuiReference, Report, Run,
    ZlibMeter,
};
use halfcast::encode::{ColorLevel, EncodeOptions, Encoder};
use halfcast::input_file::read_regular_capped;
use halfcast::termframe::{MAX_FRAME, MAX_FRAME_BYTES};
use halfcast::texture::decode::decode_within;
use halfcast::world::World;
use halfcast::{Framebuffer, Scene};

/// Every this many frames (from the first) the colour figures are measured.
const FIDELITY_EVERY: usize = 10;

/// The RGBs of a level's palette as the terminal shows them (what the baselines quantise to);
/// empty at truecolor and mono, which have no baselines.
fn palette_rgbs(level: ColorLevel) -> Vec<halfcast::Rgb> {
    use halfcast::encode::palette::{xterm_rgb, ANSI16};
    match level {
        ColorLevel::Ansi256 => (16..=255).map(xterm_rgb).collect(),
        ColorLevel::Ansi16 => ANSI16.to_vec(),
        ColorLevel::TrueColor | ColorLevel::Mono => Vec::new(),
    }
}

/// How often each sequence is re-encoded for timing (the minimum per frame is kept).
const TIMING_REPEATS: usize = 10;

/// View sizes the default bench replays, in cells.
pub const SIZES: [(u16, u16); 2] = [(240, 68), (160, 48)];

/// A bench failure: exit code and message.
#[derive(Debug)]
pub struct BenchError {
    pub code: u8,
    pub message: String,
}

fn input(message: String) -> BenchError {
    BenchError { code: 2, message }
}

/// What to run.
#[derive(Debug, Clone)]
pub struct BenchPlan {
    /// Frames per run after the first (full) frame.
    pub frames: usize,
    /// Colour levels (all when empty).
    pub levels: Vec<ColorLevel>,
    pub delta: Option<u8>,
    /// Row-planner beam width (None = the encoder's default).
    pub beam: Option<usize>,
    /// Count bytes only: no timing re-runs, no colour figures (`--bytes-only`).
    pub bytes_only: bool,
}

impl BenchPlan {
    fn options(&self, level: ColorLevel) -> EncodeOptions {
        let mut o = EncodeOptions::new(level);
        o.delta = self.delta;
        if let Some(b) = self.beam {
            o.beam = b;
        }
        o
    }

    fn levels(&self) -> Vec<ColorLevel> {
        if self.levels.is_empty() {
            ColorLevel::ALL.to_vec()
        } else {
            self.levels.clone()
        }
    }
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1000.0
}

fn mean(v: &[usize]) -> f64 {
    if v.is_empty() {
        0.0
    } else {
        v.iter().sum::<usize>() as f64 / v.len() as f64
    }
}

/// The encoder's time on `frames` after the first, summing each frame's fastest of
/// [`TIMING_REPEATS`] runs (the machine may be shared).
fn fastest_encode_ms(frames: &[Framebuffer], opts: EncodeOptions) -> f64 {
    let mut best: Vec<f64> = vec![f64::MAX; frames.len()];
    for _ in 0..TIMING_REPEATS {
        let mut enc = Encoder::new(opts);
        for (i, fb) in frames.iter().enumerate() {
            let t = Instant::now();
            let n = enc.encode(fb, 0, 0).len();
            best[i] = best[i].min(ms(t));
            std::hint::black_box(n);
        }
    }
    best.iter().skip(1).sum()
}

/// Encodes `frames` at one level; `dump` receives each frame's bytes. `bytes_only` skips the
/// colour figures and the timing re-runs.
fn measure(
    name: &str,
    frames: &[Framebuffer],
    opts: EncodeOptions,
    (render_ms, truecolor_ratatui): (f64, f64),
    bytes_only: bool,
    mut dump: impl FnMut(usize, &[u8]) -> Result<(), BenchError>,
) -> Result<Run, BenchError> {
    let (cols, rows) = (frames[0].width() as u16, frames[0].cell_rows() as u16);
    let mut enc = Encoder::new(opts);
    let mut zlib = ZlibMeter::new();
    let mut reference = RatatuiReference::new(cols, rows, opts.level);
    let (mut bytes, mut zbytes, mut rbytes) = (Vec::new(), Vec::new(), Vec::new());
    let (mut first, mut rfirst) = (0, 0);
    let (mut enc_ms, mut draw_ms) = (0.0, 0.0);
    let mut fidelities: Vec<Figures> = Vec::new();
    let (mut nearest, mut fs): (Vec<Figures>, Vec<Figures>) = (Vec::new(), Vec::new());
    let palette = palette_rgbs(opts.level);
    for (i, fb) in frames.iter().enumerate() {
        let t = Instant::now();
        let out = enc.encode(fb, 0, 0);
        let dt = ms(t);
        let z = zlib.frame(out);
        dump(i, out)?;
        let n = out.len();
        if !bytes_only && i % FIDELITY_EVERY == 0 {
            if let Some(shown) = enc.shown_frame() {
                let source = scielab::Source::new(fb);
                fidelities.push(source.compare(&shown));
                if !palette.is_empty() {
                    let (n, f) = source.baselines(&palette);
                    nearest.push(n);
                    fs.push(f);
                }
            }
        }
        let t = Instant::now();
        let r = reference.draw(fb).len();
        let rt = ms(t);
        if i == 0 {
            first = n;
            rfirst = r;
        } else {
            bytes.push(n);
            zbytes.push(z);
            rbytes.push(r);
            enc_ms += dt;
            draw_ms += rt;
        }
    }
    if !bytes_only {
        enc_ms = enc_ms.min(fastest_encode_ms(frames, opts));
    }
    let diff_frames = frames.len().saturating_sub(1).max(1) as f64;
    let fidelity = scielab::mean(&fidelities);
    let bytes_per_frame = mean(&bytes);
    let ratatui_bpf = mean(&rbytes);
    let baseline = if opts.level == ColorLevel::TrueColor || truecolor_ratatui <= 0.0 {
        ratatui_bpf
    } else {
        truecolor_ratatui
    };
    Ok(Run {
        scene: name.to_string(),
        cols,
        rows,
        colors: opts.level.name().to_string(),
        frames: frames.len(),
        halfcast: HalfcastFigures {
            bytes_per_frame,
            first_frame_bytes: first,
            zlib_bytes_per_frame: mean(&zbytes),
            encode_ms: enc_ms / diff_frames,
            render_ms,
        },
        ratatui: RatatuiFigures {
            bytes_per_frame: ratatui_bpf,
            first_frame_bytes: rfirst,
            draw_ms: draw_ms / diff_frames,
        },
        ratio_vs_ratatui_truecolor: if baseline > 0.0 {
            bytes_per_frame / baseline
        } else {
            0.0
        },
        scielab_45: fidelity.map(|f| f.scielab_45),
        scielab_9: fidelity.map(|f| f.scielab_9),
        chroma_kept: fidelity.and_then(|f| f.chroma_kept),
        hue_error: fidelity.and_then(|f| f.hue_error),
        nearest: scielab::mean(&nearest).map(Into::into),
        floyd_steinberg: scielab::mean(&fs).map(Into::into),
    })
}

/// Stock ratatui truecolor bytes per diff frame on `frames` (the baseline of every ratio).
fn ratatui_truecolor(frames: &[Framebuffer]) -> f64 {
    let mut r = RatatuiReference::new(
        frames[0].width() as u16,
        frames[0].cell_rows() as u16,
        ColorLevel::TrueColor,
    );
    let sizes: Vec<usize> = frames.iter().map(|fb| r.draw(fb).len()).skip(1).collect();
    mean(&sizes)
}

/// Replays every scene at every size and level on the default map.
///
/// # Errors
/// None in practice (kept fallible like the frames bench).
pub fn run_default(plan: &BenchPlan) -> Result<Report, BenchError> {
    let world = World::default_world();
    let mut report = Report::default();
    for scene in BenchScene::ALL {
        for (cols, rows) in SIZES {
            let cams = camera_path(&world.map, scene, plan.frames + 1);
            let mut frames = Vec::with_capacity(cams.len());
            let t = Instant::now();
            for cam in cams {
                let mut fb = Framebuffer::for_cells(cols, rows);
                Scene::new(&world, cam).render_into(&mut fb, None);
                frames.push(fb);
            }
            let render_ms = ms(t) / frames.len() as f64;
            let levels = plan.levels();
            let mut baseline = 0.0;
            if !levels.contains(&ColorLevel::TrueColor) {
                baseline = ratatui_truecolor(&frames);
            }
            for level in levels {
                let run = measure(
                    scene.name(),
                    &frames,
                    plan.options(level),
                    (render_ms, baseline),
                    plan.bytes_only,
                    |_, _| Ok(()),
                )?;
                if level == ColorLevel::TrueColor {
                    baseline = run.ratatui.bytes_per_frame;
                }
                report.runs.push(run);
            }
        }
    }
    fix_ratios(&mut report);
    Ok(report)
}

/// Ratios against ratatui truecolor for runs measured before their truecolor sibling.
fn fix_ratios(report: &mut Report) {
    let base: Vec<((String, u16, u16), f64)> = report
        .runs
        .iter()
        .filter(|r| r.colors == "truecolor")
        .map(|r| ((r.scene.clone(), r.cols, r.rows), r.ratatui.bytes_per_frame))
        .collect();
    for run in &mut report.runs {
        let key = (run.scene.clone(), run.cols, run.rows);
        if let Some((_, b)) = base.iter().find(|(k, _)| *k == key) {
            if *b > 0.0 {
                run.ratio_vs_ratatui_truecolor = run.halfcast.bytes_per_frame / b;
            }
        }
    }
}

/// Most pixels all the frames of `bench --frames` may hold together (about 200 MB decoded):
/// a directory of small, highly compressible PNGs cannot make the bench hold gigabytes.
pub const MAX_BENCH_PIXELS: usize = 1 << 26;

/// Loads a directory of PNG frames sorted by file name; all must be the same size. Each is a
/// regular file within the frame-file byte cap and decoded within the frame size limit, and all
/// together hold at most [`MAX_BENCH_PIXELS`].
///
/// # Errors
/// Exit-2 errors for a missing directory, a FIFO or device, a file that is not a PNG, mismatched
/// sizes, an odd height, frames over the limits, or an empty directory.
pub fn load_frames(dir: &Path) -> Result<Vec<Framebuffer>, BenchError> {
    let entries = std::fs::read_dir(dir).map_err(|e| {
        input(format!(
            "cannot read frames directory {}: {e}",
            dir.display()
        ))
    })?;
    // Subdirectories are skipped; anything else that is not a regular file is refused on reading.
    let mut paths: Vec<PathBuf> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| !p.is_dir())
        .collect();
    paths.sort();
    if paths.is_empty() {
        return Err(input(format!("no PNG frames in {}", dir.display())));
    }
    let mut frames: Vec<Framebuffer> = Vec::new();
    let (max_cols, max_rows) = MAX_FRAME;
    for p in &paths {
        let bytes = read_regular_capped(p, MAX_FRAME_BYTES)
            .map_err(|e| input(format!("cannot read {}: {e}", p.display())))?;
        if !bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            return Err(input(format!("{} is not a PNG image", p.display())));
        }
        if frames.is_empty() {
            // All frames must share the first one's size, so its header says what all of them
            // will hold: refuse before decoding any.
            let (w, h) = image::ImageReader::new(std::io::Cursor::new(&bytes))
                .with_guessed_format()
                .ok()
                .and_then(|r| r.into_dimensions().ok())
                .unwrap_or((0, 0));
            let pixels = (w as usize)
                .saturating_mul(h as usize)
                .saturating_mul(paths.len());
            if pixels > MAX_BENCH_PIXELS {
                return Err(input(format!(
                    "{}: {} frames of {w}x{h} pixels hold more than {MAX_BENCH_PIXELS} pixels \
                     (the limit); use fewer or smaller frames",
                    dir.display(),
                    paths.len()
                )));
            }
        }
        let img = decode_within(&bytes, max_cols as u32, 2 * max_rows as u32)
            .map_err(|e| input(format!("{} is not a readable PNG: {e}", p.display())))?;
        let fb = Framebuffer::from_image(&img.to_rgb8());
        if !fb.height().is_multiple_of(2) || fb.width() == 0 || fb.height() == 0 {
            return Err(input(format!(
                "{} is {}x{} pixels; frames need an even height (two pixel rows per cell)",
                p.display(),
                fb.width(),
                fb.height()
            )));
        }
        if fb.width() > usize::from(u16::MAX) || fb.cell_rows() > usize::from(u16::MAX) {
            return Err(input(format!("{} is too large", p.display())));
        }
        if let Some(f0) = frames.first() {
            if (f0.width(), f0.height()) != (fb.width(), fb.height()) {
                return Err(input(format!(
                    "{} is {}x{} pixels but {} is {}x{}; all frames must be the same size",
                    p.display(),
                    fb.width(),
                    fb.height(),
                    paths[0].display(),
                    f0.width(),
                    f0.height()
                )));
            }
        }
        frames.push(fb);
    }
    Ok(frames)
}

/// Encodes a PNG sequence as the TUI would send it; writes `frame-NNN.ansi` files into `dump`.
///
/// # Errors
/// The frame-loading errors (exit 2), or exit 1 when the dump directory cannot be written.
pub fn run_frames(
    dir: &Path,
    level: ColorLevel,
    plan: &BenchPlan,
    dump: Option<&Path>,
) -> Result<Report, BenchError> {
    let frames = load_frames(dir)?;
    if let Some(out) = dump {
        std::fs::create_dir_all(out).map_err(|e| BenchError {
            code: 1,
            message: format!("cannot create {}: {e}", out.display()),
        })?;
    }
    let width = frames.len().saturating_sub(1).to_string().len().max(3);
    let name = dir.file_name().map_or_else(
        || "frames".to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let baseline = if level == ColorLevel::TrueColor {
        0.0
    } else {
        ratatui_truecolor(&frames)
    };
    let run = measure(
        &name,
        &frames,
        plan.options(level),
        (0.0, baseline),
        plan.bytes_only,
        |i, bytes| {
            if let Some(out) = dump {
                let path = out.join(format!("frame-{i:0width$}.ansi"));
                std::fs::write(&path, bytes).map_err(|e| BenchError {
                    code: 1,
                    message: format!("cannot write {}: {e}", path.display()),
                })?;
            }
            Ok(())
        },
    )?;
    Ok(Report { runs: vec![run] })
}

/// The report as a readable table.
#[must_use]
pub fn table(report: &Report) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<6} {:>7} {:>9} {:>6} | {:>9} {:>9} {:>8} {:>7} {:>6} | {:>9} {:>9} {:>7} | {:>7} {:>7} | {:>11} {:>6} {:>5} | {:>11} {:>11}",
        "scene",
        "size",
        "colors",
        "frames",
        "B/frame",
        "first",
        "zlib B/f",
        "enc ms",
        "rnd ms",
        "rat B/f",
        "rat first",
        "rat ms",
        "vs rat",
        "vs rtc",
        "S-CIELAB",
        "chroma",
        "hue",
        "nearest",
        "FS"
    );
    for r in &report.runs {
        let same = if r.ratatui.bytes_per_frame > 0.0 {
            100.0 * r.halfcast.bytes_per_frame / r.ratatui.bytes_per_frame
        } else {
            0.0
        };
        let _ = writeln!(
            s,
            "{:<6} {:>7} {:>9} {:>6} | {:>9.0} {:>9} {:>8.0} {:>7.3} {:>6.2} | {:>9.0} {:>9} {:>7.3} | {:>6.1}% {:>6.1}% | {:>11} {:>6} {:>5} | {:>11} {:>11}",
            r.scene,
            format!("{}x{}", r.cols, r.rows),
            r.colors,
            r.frames,
            r.halfcast.bytes_per_frame,
            r.halfcast.first_frame_bytes,
            r.halfcast.zlib_bytes_per_frame,
            r.halfcast.encode_ms,
            r.halfcast.render_ms,
            r.ratatui.bytes_per_frame,
            r.ratatui.first_frame_bytes,
            r.ratatui.draw_ms,
            same,
            100.0 * r.ratio_vs_ratatui_truecolor,
            pair(r.scielab_45.zip(r.scielab_9)),
            figure(r.chroma_kept, 2),
            figure(r.hue_error, 1),
            pair(r.nearest.map(|f| (f.scielab_45, f.scielab_9))),
            pair(r.floyd_steinberg.map(|f| (f.scielab_45, f.scielab_9))),
        );
    }
    s.push_str(
        "B/frame, zlib, enc ms: mean over frames after the first; vs rat: halfcast / stock ratatui \
         at the same level; vs rtc: halfcast / stock ratatui truecolor; S-CIELAB: mean S-CIELAB \
         dE at 4.5/9 pixels per degree of what the terminal shows (every 10th frame), chroma kept \
         and hue error (degrees); nearest, FS: S-CIELAB of the nearest palette colour and of \
         Floyd-Steinberg on the same frames\n",
    );
    s
}

/// The report of a `--bytes-only` run: bytes alone, with no timing columns (it times nothing
/// twice, so its one-pass times are not figures to print) and no colour figures (none measured).
#[must_use]
pub fn bytes_table(report: &Report) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<6} {:>7} {:>9} {:>6} | {:>9} {:>9} {:>8} | {:>9} {:>9} | {:>7} {:>7}",
        "scene",
        "size",
        "colors",
        "frames",
        "B/frame",
        "first",
        "zlib B/f",
        "rat B/f",
        "rat first",
        "vs rat",
        "vs rtc"
    );
    for r in &report.runs {
        let same = if r.ratatui.bytes_per_frame > 0.0 {
            100.0 * r.halfcast.bytes_per_frame / r.ratatui.bytes_per_frame
        } else {
            0.0
        };
        let _ = writeln!(
            s,
            "{:<6} {:>7} {:>9} {:>6} | {:>9.0} {:>9} {:>8.0} | {:>9.0} {:>9} | {:>6.1}% {:>6.1}%",
            r.scene,
            format!("{}x{}", r.cols, r.rows),
            r.colors,
            r.frames,
            r.halfcast.bytes_per_frame,
            r.halfcast.first_frame_bytes,
            r.halfcast.zlib_bytes_per_frame,
            r.ratatui.bytes_per_frame,
            r.ratatui.first_frame_bytes,
            same,
            100.0 * r.ratio_vs_ratatui_truecolor,
        );
    }
    s.push_str(
        "Bytes only. B/frame, zlib: mean over frames after the first; vs rat: halfcast / stock \
         ratatui at the same level; vs rtc: halfcast / stock ratatui truecolor\n",
    );
    s
}

/// A colour figure for the table with `digits` decimals (`-` when not measured).
fn figure(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "-".to_string(), |v| format!("{v:.digits$}"))
}

/// S-CIELAB at 4.5 and 9 ppd as `a/b` (`-` when not measured).
fn pair(v: Option<(f64, f64)>) -> String {
    v.map_or_else(|| "-".to_string(), |(a, b)| format!("{a:.2}/{b:.2}"))
}
