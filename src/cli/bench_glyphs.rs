//! `halfcast bench --glyphs`: the glyph ladder measured in one run. For each view size and
//! setting, the walk path is rendered at the setting's sub-grid and encoded; what the terminal
//! then shows is judged by S-CIELAB against a reference render of the same camera at the octant
//! grid, and bytes and render + encode time are set against half-blocks'.

use std::fmt::Write as _;
use std::time::Instant;

use halfcast::bench::glyph_grid::{at_octant_grid, GlyphRun, OCTANT_PPDS};
use halfcast::bench::scielab::{self, Source};
use halfcast::bench::{camera_path, BenchScene};
use halfcast::encode::{ColorLevel, EncodeOptions, Encoder};
use halfcast::world::World;
use halfcast::{Framebuffer, Glyphs, Scene};

/// View sizes of the glyph figures, in cells: the two.
pub const GLYPH_SIZES: [(u16, u16); 2] = [(80, 24), (240, 68)];

/// Every this many frames the picture is judged (S-CIELAB at the octant grid is the slow part).
const FIDELITY_EVERY: usize = 10;

/// Timing passes over the path; each frame keeps its fastest (the machine may be shared).
const REPEATS: usize = 7;

/// One setting's measurements at one size: per frame its fastest render and encode, and from
/// the first pass the bytes sent and the judged pictures' figures.
struct Timed {
    render: Vec<f64>,
    encode: Vec<f64>,
    bytes: Vec<f64>,
    figures: Vec<scielab::Figures>,
}

impl Timed {
    fn new(frames: usize) -> Self {
        Self {
            render: vec![f64::MAX; frames],
            encode: vec![f64::MAX; frames],
            bytes: Vec::new(),
            figures: Vec::new(),
        }
    }
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1000.0
}

/// Runs the glyph figures: `frames` poses of the walk path after the first, at `level`.
pub fn run_glyphs(frames: usize, level: ColorLevel) -> Vec<GlyphRun> {
    let world = World::default_world();
    let cams = camera_path(&world.map, BenchScene::Walk, frames + 1);
    let mut runs = Vec::new();
    for (cols, rows) in GLYPH_SIZES {
        // The reference: each judged pose rendered at the octant grid, prepared once.
        let sources: Vec<Source> = cams
            .iter()
            .step_by(FIDELITY_EVERY)
            .map(|&cam| {
                let mut fb = Framebuffer::for_glyphs(cols, rows, Glyphs::Octant);
                Scene::new(&world, cam).render_into(&mut fb, None);
                Source::at_ppds(&fb, OCTANT_PPDS)
            })
            .collect();
        // Each pass times every setting in turn, so a burst of other work on the machine
        // lands on one pass of each at most, and each frame keeps its fastest time.
        let mut timed: Vec<Timed> = Glyphs::ALL.iter().map(|_| Timed::new(cams.len())).collect();
        for pass in 0..REPEATS {
            for (glyphs, t) in Glyphs::ALL.into_iter().zip(&mut timed) {
                let mut enc = Encoder::new(EncodeOptions::new(level));
                let mut fb = Framebuffer::for_glyphs(cols, rows, glyphs);
                // As the game and the server do: phases only where the level reads them.
                fb.set_phases_wanted(level.mixes());
                for (i, &cam) in cams.iter().enumerate() {
                    let start = Instant::now();
                    Scene::new(&world, cam).render_into(&mut fb, None);
                    t.render[i] = t.render[i].min(ms(start));
                    let start = Instant::now();
                    let n = enc.encode(&fb, 0, 0).len();
                    t.encode[i] = t.encode[i].min(ms(start));
                    if pass > 0 {
                        continue;
                    }
                    if i > 0 {
                        t.bytes.push(n as f64);
                    }
                    if i % FIDELITY_EVERY == 0 {
                        if let Some(shown) = enc.shown_frame() {
                            let shown = at_octant_grid(&with_glyphs(shown, glyphs));
                            t.figures.push(sources[i / FIDELITY_EVERY].compare(&shown));
                        }
                    }
                }
            }
        }
        let mut half: Option<GlyphRun> = None;
        for (glyphs, t) in Glyphs::ALL.into_iter().zip(timed) {
            let Timed {
                render,
                encode,
                bytes,
                figures,
            } = t;
            let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
            let fid = scielab::mean(&figures).unwrap_or_default();
            let (render_ms, encode_ms) = (mean(&render[1..]), mean(&encode[1..]));
            let mut run = GlyphRun {
                glyphs: glyphs.name().to_owned(),
                cols,
                rows,
                colors: level.name().to_owned(),
                frames: cams.len(),
                scielab_9: fid.scielab_45,
                scielab_18: fid.scielab_9,
                bytes_per_frame: mean(&bytes),
                render_ms,
                encode_ms,
                fps: 1000.0 / (render_ms + encode_ms).max(1e-9),
                ..GlyphRun::default()
            };
            let base = half.get_or_insert_with(|| run.clone());
            run.error_vs_half = run.scielab_9 / base.scielab_9.max(1e-9);
            run.bytes_vs_half = run.bytes_per_frame / base.bytes_per_frame.max(1e-9);
            run.time_vs_half =
                (run.render_ms + run.encode_ms) / (base.render_ms + base.encode_ms).max(1e-9);
            runs.push(run);
        }
    }
    runs
}

/// The encoder's shown picture (sized like its frames) marked with the setting it is at.
fn with_glyphs(shown: Framebuffer, glyphs: Glyphs) -> Framebuffer {
    if shown.glyphs() == glyphs {
        return shown;
    }
    let (cw, ch) = glyphs.cell_size();
    let (cols, rows) = (shown.width() / cw, shown.height() / ch);
    let mut fb = Framebuffer::for_glyphs(cols as u16, rows as u16, glyphs);
    for y in 0..fb.height() {
        for x in 0..fb.width() {
            fb.set(x, y, shown.get(x, y));
        }
    }
    fb
}

/// The glyph figures as a table.
#[must_use]
pub fn glyph_table(runs: &[GlyphRun]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<9} {:>7} {:>9} | {:>8} {:>8} {:>7} | {:>8} {:>7} | {:>7} {:>7} {:>7} {:>6}",
        "glyphs",
        "size",
        "colors",
        "SC 9ppd",
        "SC 18ppd",
        "vs half",
        "B/frame",
        "vs half",
        "rnd ms",
        "enc ms",
        "vs half",
        "fps"
    );
    for r in runs {
        let _ = writeln!(
            s,
            "{:<9} {:>7} {:>9} | {:>8.3} {:>8.3} {:>7.2} | {:>8.0} {:>7.2} | {:>7.2} {:>7.2} {:>7.2} {:>6.0}",
            r.glyphs,
            format!("{}x{}", r.cols, r.rows),
            r.colors,
            r.scielab_9,
            r.scielab_18,
            r.error_vs_half,
            r.bytes_per_frame,
            r.bytes_vs_half,
            r.render_ms,
            r.encode_ms,
            r.time_vs_half,
            r.fps
        );
    }
    s.push_str(
        "Walk path on the default map. SC: mean S-CIELAB dE of what the terminal shows against a \
         render at the octant grid (2W x 4H), at 9 and 18 pixels per degree of that grid (every \
         10th frame); B/frame: mean bytes after the first frame; rnd/enc ms: fastest of 3 passes, \
         mean per frame; vs half: the ratio to half-blocks at the same size; fps = 1000 / (rnd + enc)\n",
    );
    s
}
