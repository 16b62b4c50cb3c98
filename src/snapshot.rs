//! Pinning frames in tests, two ways for two kinds of frame:
//!
//! - **Text** ([`cells_text`]): any frame — a [`Framebuffer`], a ratatui `Buffer` (widgets, the
//!   whole TUI screen), a `vt100` screen (the real binary in a pseudo-terminal) — as colour-aware
//!   text, one line per row, every cell's glyph, foreground and background. Pin it with
//!   `insta::assert_snapshot!`; a changed frame shows as a readable diff in review.
//! - **Pixels** ([`assert_png_golden`]): a framebuffer against a golden PNG, within a
//!   [`Tolerance`], for frames too large to review as text.
//!
//! Pinning a small frame inline (the test fails if one cell changes colour):
//!
//! ```
//! use halfcast::{Camera, Scene, Vec2, World};
//!
//! let world = World::default_world();
//! let scene = Scene::new(&world, Camera::from_angle(Vec2::new(8.5, 5.5), 30.0, 66.0));
//! insta::assert_snapshot!(scene.to_cells_text(6, 3), @r"
//! halfcast-cells v1 6x3
//! ▀5f5e58/7b7771 ▀84827a/5a5853 ▀7f7c74/797670 ▀797771/7e7b74 ▀86837b/5a5853 ▀5f5e58/76746e
//! ▀4e2626/5d2d26 ▀6a4b33/563d2c ▀573e2a/654630 ▀62442e/5e412c ▀62442d/62442d ▀505762/4c515c
//! ▀4b443e/252424 ▀252323/504a42 ▀4e473f/4e4840 ▀5b534b/62584f ▀252323/696054 ▀60584e/252424
//! ");
//! ```
//!
//! A golden PNG (rewritten instead of compared when `HALFCAST_UPDATE_GOLDEN` is set; on a
//! mismatch the actual frame is saved beside it as `<name>.actual.png`):
//!
//! ```
//! use halfcast::snapshot::{assert_png_golden, Tolerance};
//! use halfcast::{Camera, Scene, World};
//!
//! let world = World::default_world();
//! let start = world.map.start;
//! let fb = Scene::new(&world, Camera::from_angle(start.pos(), start.angle_deg(), 66.0))
//!     .render(120, 40);
//! let golden = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/images/core/default_start.png");
//! assert_png_golden(&fb, golden, Tolerance::default());
//! ```

use std::path::Path;

use crate::render::framebuffer::Framebuffer;
use crate::termframe::{to_cells_text, TermFrame};

/// The text form snapshots pin (`halfcast-cells v1`: a size header, then one line per row of
/// `GLYPH` + fg hex + `/` + bg hex cells, `~~~~~~` = default colour), of anything shown as cells.
#[must_use]
pub fn cells_text(frame: impl Into<TermFrame>) -> String {
    to_cells_text(&frame.into())
}

/// Set this environment variable (to anything) to rewrite golden files instead of comparing.
pub const UPDATE_ENV: &str = "HALFCAST_UPDATE_GOLDEN";

/// How different two frames may be and still count as equal (rounding, not regressions).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// A pixel differs when any channel differs by more than this.
    pub max_channel_delta: u8,
    /// The share of pixels (0..=1) allowed to differ.
    pub max_differing_fraction: f64,
}

impl Default for Tolerance {
    /// Two channel steps per pixel, and half a percent of pixels.
    fn default() -> Self {
        Self {
            max_channel_delta: 2,
            max_differing_fraction: 0.005,
        }
    }
}

/// What differs between two frames of the same size.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameDiff {
    /// Pixels differing by more than the threshold.
    pub differing_pixels: usize,
    /// All pixels compared.
    pub total_pixels: usize,
    /// The largest channel difference seen.
    pub max_channel_delta: u8,
}

/// Compares two frames pixel by pixel; `None` when their sizes differ.
#[must_use]
pub fn diff_frames(a: &Framebuffer, b: &Framebuffer, threshold: u8) -> Option<FrameDiff> {
    if (a.width(), a.height()) != (b.width(), b.height()) {
        return None;
    }
    let mut d = FrameDiff {
        differing_pixels: 0,
        total_pixels: a.pixels().len(),
        max_channel_delta: 0,
    };
    for (p, q) in a.pixels().iter().zip(b.pixels()) {
        let delta =
            p.r.abs_diff(q.r)
                .max(p.g.abs_diff(q.g))
                .max(p.b.abs_diff(q.b));
        d.max_channel_delta = d.max_channel_delta.max(delta);
        if delta > threshold {
            d.differing_pixels += 1;
        }
    }
    Some(d)
}

/// Asserts `fb` matches the PNG at `path` within `tol`; with [`UPDATE_ENV`] set, writes it instead.
///
/// # Panics
/// When the golden file is missing (saying how to create it) or unreadable, the sizes differ, or too many pixels differ
/// (the actual frame is then saved beside the golden as `<name>.actual.png`).
pub fn assert_png_golden(fb: &Framebuffer, path: impl AsRef<Path>, tol: Tolerance) {
    let path = path.as_ref();
    if std::env::var_os(UPDATE_ENV).is_some() {
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).expect("create golden folder");
        }
        std::fs::write(path, fb.to_png().expect("encode PNG")).expect("write golden PNG");
        return;
    }
    if !path.exists() {
        panic!(
            "no golden image at {} yet: run the test once with {UPDATE_ENV}=1 to create it \
             from this frame, look at the PNG, and commit it",
            path.display()
        );
    }
    let golden = std::fs::read(path)
        .map_err(|e| e.to_string())
        .and_then(|bytes| Framebuffer::from_image_bytes(&bytes))
        .unwrap_or_else(|e| {
            panic!(
                "golden {} is not a readable PNG ({e}); run with {UPDATE_ENV}=1 to rewrite it",
                path.display()
            )
        });
    let verdict = diff_frames(fb, &golden, tol.max_channel_delta);
    let ok = verdict.is_some_and(|d| {
        d.differing_pixels as f64 <= tol.max_differing_fraction * d.total_pixels as f64
    });
    if !ok {
        let actual = path.with_extension("actual.png");
        let _ = std::fs::write(&actual, fb.to_png().expect("encode PNG"));
        panic!(
            "frame differs from {} ({verdict:?}); actual saved as {}; if the change is intended run with {UPDATE_ENV}=1",
            path.display(),
            actual.display()
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    #[test]
    fn a_missing_golden_says_how_to_create_it() {
        if std::env::var_os(UPDATE_ENV).is_some() {
            return; // the variable would create the file instead
        }
        let dir = std::env::temp_dir().join(format!("halfcast-golden-{}", std::process::id()));
        let path = dir.join("not_yet.png");
        let fb = Framebuffer::new(2, 2);
        let err = std::panic::catch_unwind(|| assert_png_golden(&fb, &path, Tolerance::default()))
            .expect_err("a missing golden fails");
        let msg = err.downcast_ref::<String>().cloned().unwrap_or_default();
        assert!(
            msg.starts_with("no golden image at ")
                && msg.contains("HALFCAST_UPDATE_GOLDEN=1 to create it"),
            "{msg}"
        );
        assert!(!msg.contains("os error"), "{msg}");
        assert!(!path.exists());
    }

    #[test]
    fn diff_counts_pixels_over_the_threshold() {
        let a = Framebuffer::new(2, 2);
        let mut b = a.clone();
        b.set(0, 0, Rgb::new(3, 0, 0));
        b.set(1, 1, Rgb::new(0, 1, 0));
        let d = diff_frames(&a, &b, 2).unwrap();
        assert_eq!(
            (d.differing_pixels, d.total_pixels, d.max_channel_delta),
            (1, 4, 3)
        );
        assert!(diff_frames(&a, &Framebuffer::new(3, 2), 0).is_none());
    }
}
