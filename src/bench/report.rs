//! The JSON `halfcast bench --json` prints (shape fixed by issue 5; extra keys allowed).

use serde::Serialize;

/// The whole report: one run per scene × size × colour level.
#[derive(Debug, Serialize, Default)]
pub struct Report {
    pub runs: Vec<Run>,
}

/// One replayed sequence.
#[derive(Debug, Serialize)]
pub struct Run {
    pub scene: String,
    pub cols: u16,
    pub rows: u16,
    pub colors: String,
    pub frames: usize,
    pub halfcast: HalfcastFigures,
    pub ratatui: RatatuiFigures,
    /// halfcast diff-frame bytes / stock ratatui truecolor diff-frame bytes on the same frames.
    pub ratio_vs_ratatui_truecolor: f64,
    /// Mean S-CIELAB ΔE at 4.5 pixels per degree of what the terminal shows against the frame
    /// (every 10th frame; see `bench::scielab`); `null` in mono.
    pub scielab_45: Option<f64>,
    /// The same at 9 pixels per degree (small fonts or a farther seat).
    pub scielab_9: Option<f64>,
    /// Mean blurred chroma kept (1 = as colourful as the frame, 0 = grey); `null` in mono or
    /// when the frames carry too little colour to judge.
    pub chroma_kept: Option<f64>,
    /// Mean hue error in degrees over the frame's coloured 4×4 blocks; `null` as `chroma_kept`.
    pub hue_error: Option<f64>,
    /// The same figures for each pixel's nearest palette colour (no dither), on the same frames;
    /// `null` at truecolor and mono.
    pub nearest: Option<ColourFigures>,
    /// The same figures for Floyd–Steinberg to the palette, on the same frames; `null` at
    /// truecolor and mono.
    pub floyd_steinberg: Option<ColourFigures>,
}

/// halfcast's encoder on the sequence.
#[derive(Debug, Serialize)]
pub struct HalfcastFigures {
    /// Mean bytes of the frames after the first.
    pub bytes_per_frame: f64,
    pub first_frame_bytes: usize,
    /// Mean bytes per frame (after the first) through one zlib stream with a sync flush per frame.
    pub zlib_bytes_per_frame: f64,
    /// Mean time to encode a frame after the first, in milliseconds (fastest of a few repeats).
    pub encode_ms: f64,
    /// Mean time to render a frame (cast + rasterize), in milliseconds.
    pub render_ms: f64,
}

/// Stock ratatui + crossterm drawing the same cells at the same colour level.
#[derive(Debug, Serialize)]
pub struct RatatuiFigures {
    pub bytes_per_frame: f64,
    pub first_frame_bytes: usize,
    /// Mean time of `Terminal::draw` after the first frame, in milliseconds.
    pub draw_ms: f64,
}

/// How a way of showing the frames looks (see `bench::scielab`): a baseline's four figures.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ColourFigures {
    /// Mean S-CIELAB ΔE at 4.5 pixels per degree.
    pub scielab_45: f64,
    /// Mean S-CIELAB ΔE at 9 pixels per degree.
    pub scielab_9: f64,
    /// Mean blurred chroma kept (`null` when the frames carry too little colour).
    pub chroma_kept: Option<f64>,
    /// Mean hue error in degrees (`null` as `chroma_kept`).
    pub hue_error: Option<f64>,
}

impl From<crate::bench::scielab::Figures> for ColourFigures {
    fn from(f: crate::bench::scielab::Figures) -> Self {
        Self {
            scielab_45: f.scielab_45,
            scielab_9: f.scielab_9,
            chroma_kept: f.chroma_kept,
            hue_error: f.hue_error,
        }
    }
}
