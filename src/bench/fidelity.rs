//! How faithful a reduced-colour frame looks: the figures `colourfidelity.py` checks, in Rust, so
//! `halfcast bench --json` shows the colour/bytes trade-off next to the byte counts.
//!
//! Both frames are box-blurred over 4×4-pixel blocks in linear light (what the eye sees at a normal
//! viewing distance, so mixing two colours in a cell is credited), then compared in OKLab.

use crate::color::{oklab, Linear};
use crate::render::framebuffer::Framebuffer;

/// Side of the blur block, in pixels.
const BLOCK: usize = 4;

/// Blocks whose source chroma is below this carry too little colour to judge hue by.
const MIN_CHROMA: f64 = 0.03;

/// Fewer coloured blocks than this and `chroma_kept` is not judged.
const MIN_BLOCKS: usize = 20;

/// A chroma ratio counts at most this much (one over-saturated block cannot hide grey ones).
const MAX_RATIO: f64 = 2.0;

/// The two fidelity figures of one frame (or a mean of frames).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fidelity {
    /// Mean OKLab distance (×100) between the blurred frames.
    pub oklab_de_blur: f64,
    /// Mean blurred chroma shown / chroma of the source over blocks with source chroma ≥ 0.03
    /// (1 keeps colourfulness, 0 is grey); `None` when fewer than 20 such blocks.
    pub chroma_kept: Option<f64>,
}

/// The 4×4 block means of a frame in linear light, then in OKLab (whole blocks only).
fn blurred(fb: &Framebuffer) -> Vec<[f32; 3]> {
    let (w, h) = (fb.width(), fb.height());
    let mut out = Vec::with_capacity((w / BLOCK) * (h / BLOCK));
    for y0 in (0..h).step_by(BLOCK) {
        if y0 + BLOCK > h {
            break;
        }
        for x0 in (0..w).step_by(BLOCK) {
            if x0 + BLOCK > w {
                break;
            }
            let mut acc = [0.0f64; 3];
            for y in y0..y0 + BLOCK {
                for &p in &fb.row(y)[x0..x0 + BLOCK] {
                    let l = p.linear();
                    for i in 0..3 {
                        acc[i] += f64::from(l[i]);
                    }
                }
            }
            let n = (BLOCK * BLOCK) as f64;
            let mean: Linear = acc.map(|a| (a / n) as f32);
            out.push(oklab(mean));
        }
    }
    out
}

/// Compares what is shown with its source (same size).
#[must_use]
pub fn compare(source: &Framebuffer, shown: &Framebuffer) -> Fidelity {
    let (a, b) = (blurred(source), blurred(shown));
    let mut de = 0.0;
    let mut ratios = Vec::new();
    for (s, o) in a.iter().zip(&b) {
        let d2: f64 = (0..3).map(|i| f64::from(s[i] - o[i]).powi(2)).sum();
        de += d2.sqrt();
        let cs = f64::from(s[1]).hypot(f64::from(s[2]));
        if cs >= MIN_CHROMA {
            let co = f64::from(o[1]).hypot(f64::from(o[2]));
            ratios.push((co / cs).min(MAX_RATIO));
        }
    }
    Fidelity {
        oklab_de_blur: if a.is_empty() {
            0.0
        } else {
            100.0 * de / a.len() as f64
        },
        chroma_kept: (ratios.len() >= MIN_BLOCKS)
            .then(|| ratios.iter().sum::<f64>() / ratios.len() as f64),
    }
}

/// The mean of several frames' figures (chroma over the frames that have one).
#[must_use]
pub fn mean(all: &[Fidelity]) -> Option<Fidelity> {
    if all.is_empty() {
        return None;
    }
    let chroma: Vec<f64> = all.iter().filter_map(|f| f.chroma_kept).collect();
    Some(Fidelity {
        oklab_de_blur: all.iter().map(|f| f.oklab_de_blur).sum::<f64>() / all.len() as f64,
        chroma_kept: (!chroma.is_empty()).then(|| chroma.iter().sum::<f64>() / chroma.len() as f64),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    fn flat(w: usize, h: usize, c: Rgb) -> Framebuffer {
        let mut fb = Framebuffer::new(w, h);
        for y in 0..h {
            fb.row_mut(y).fill(c);
        }
        fb
    }

    #[test]
    fn identical_frames_are_perfect() {
        let fb = flat(20, 16, Rgb::new(150, 60, 40));
        let f = compare(&fb, &fb);
        assert_eq!(f.oklab_de_blur, 0.0);
        assert!((f.chroma_kept.unwrap() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn red_half_dithered_with_black_matches_hand_computed_figures() {
        // Pure red against red/black alternating pixels: every 4×4 block's linear mean is half
        // red, whose LMS responses are halved, so OKLab scales by 0.5^(1/3) = 0.793 70.
        // Red is (0.627 96, 0.224 86, 0.125 85): |red| = 0.678 77, so ΔE = (1 − 0.793 70) · 67.877
        // = 14.003; chroma kept = 0.793 70.
        let red = Rgb::new(255, 0, 0);
        let src = flat(20, 16, red);
        let mut shown = src.clone();
        for y in 0..16 {
            for x in 0..20 {
                if (x + y) % 2 == 1 {
                    shown.set(x, y, Rgb::new(0, 0, 0));
                }
            }
        }
        let f = compare(&src, &shown);
        assert!((f.oklab_de_blur - 14.003).abs() < 0.01, "{f:?}");
        assert!((f.chroma_kept.unwrap() - 0.793_70).abs() < 1e-4, "{f:?}");
    }

    #[test]
    fn grey_source_or_few_blocks_leave_chroma_unjudged() {
        let grey = flat(20, 16, Rgb::new(90, 90, 90));
        assert_eq!(compare(&grey, &grey).chroma_kept, None);
        let small = flat(8, 8, Rgb::new(255, 0, 0));
        let f = compare(&small, &flat(8, 8, Rgb::new(128, 128, 128)));
        assert_eq!(f.chroma_kept, None, "4 blocks are too few");
        assert!(f.oklab_de_blur > 10.0);
    }

    #[test]
    fn grey_output_keeps_no_chroma_and_ratios_cap_at_two() {
        let src = flat(20, 16, Rgb::new(120, 90, 80));
        let f = compare(&src, &flat(20, 16, Rgb::new(95, 95, 95)));
        assert!(f.chroma_kept.unwrap() < 0.01, "{f:?}");
        let f = compare(&src, &flat(20, 16, Rgb::new(255, 0, 0)));
        assert_eq!(f.chroma_kept, Some(2.0));
    }
}
