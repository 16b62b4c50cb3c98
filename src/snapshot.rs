//! Pinning frames in tests, two ways for two kinds of frame:
//!
//! - **Text** ([`cells_text`]): any frame — a [`Framebuffer`], a ratatui `Buffer` (widgets, the
//!   whole TUI screen), the bytes a terminal received (`termframe::from_ansi_sized`) — as text: the
//!   glyph grid, then style runs with every colour (as named) and attribute. Pin it with
//!   `insta::assert_snapshot!`; a changed frame shows as a readable diff in review.
//! - **Equality** ([`assert_frames_eq`]): two frames, one assertion, strict (every part of every
//!   cell), the differing cells in the failure message; [`assert_frames_look_same`] compares
//!   only what the screen shows.
//! - **A stored snapshot** ([`assert_cells_snapshot!`](ratatui_cells::assert_cells_snapshot)):
//!   a frame against its insta snapshot of cells text, with the cell diff on failure; insta
//!   names, stores, reviews and accepts it.
//! - **Pixels** ([`assert_png_golden`]): a framebuffer against a golden PNG, within a
//!   [`Tolerance`], for frames too large to review as text; any text frame becomes one with
//!   [`crate::output::screenshot::screenshot`] (compare those with [`Tolerance::EXACT`]).
//!
//! Pinning a small frame inline (the test fails if one cell changes colour):
//!
//! ```
//! use halfcast::{Camera, Scene, Vec2, World};
//!
//! let world = World::default_world();
//! let scene = Scene::new(&world, Camera::from_angle(Vec2::new(8.5, 5.5), 30.0, 66.0));
//! insta::assert_snapshot!(scene.to_cells_text(6, 3), @r#"
//! ratatui-cells v1 6x3
//! "▀▀▀▀▀▀"
//! "▀▀▀▀▀▀"
//! "▀▀▀▀▀▀"
//! styles:
//! y0 x0 fg=#5f5e58 bg=#7b7771
//! y0 x1 fg=#84827a bg=#5a5853
//! y0 x2 fg=#7f7c74 bg=#797670
//! y0 x3 fg=#797771 bg=#7e7b74
//! y0 x4 fg=#86837b bg=#5a5853
//! y0 x5 fg=#5f5e58 bg=#76746e
//! y1 x0 fg=#4e2626 bg=#5d2d26
//! y1 x1 fg=#6a4b33 bg=#563d2c
//! y1 x2 fg=#573e2a bg=#654630
//! y1 x3 fg=#62442e bg=#5e412c
//! y1 x4 fg=#62442d bg=#62442d
//! y1 x5 fg=#505762 bg=#4c515c
//! y2 x0 fg=#4b443e bg=#252424
//! y2 x1 fg=#252323 bg=#504a42
//! y2 x2 fg=#4e473f bg=#4e4840
//! y2 x3 fg=#5b534b bg=#62584f
//! y2 x4 fg=#252323 bg=#696054
//! y2 x5 fg=#60584e bg=#252424
//! "#);
//! ```
//!
//! These are the [`ratatui_cells`] crate's, which works on any ratatui screen; halfcast adds
//! frames of [`Framebuffer`] pixels to what they take.
//!
//! A golden PNG (rewritten instead of compared when insta's switch, `INSTA_UPDATE=always`, is
//! set, the switch that also rewrites stored cells snapshots and every insta snapshot; see
//! [`update_requested`]; on a mismatch the actual frame is saved in the system's temporary
//! folder, never beside the golden, and the failure names it):
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

use std::path::{Path, PathBuf};

pub use ratatui_cells::{
    assert_cells_snapshot, assert_frames_eq, assert_frames_look_same, cells_text,
};

use crate::render::framebuffer::Framebuffer;

/// The one switch that rewrites golden PNGs, as it rewrites stored cells snapshots and every
/// other insta snapshot: insta's own, set to `always` (or insta's `INSTA_FORCE_UPDATE=1`).
pub const UPDATE_ENV: &str = "INSTA_UPDATE";

/// The switch's older names, still honoured for golden PNGs (any value but `0` or empty).
pub const LEGACY_UPDATE_ENVS: [&str; 2] = ["HALFCAST_UPDATE_GOLDEN", "RATATUI_CELLS_UPDATE"];

/// The first of [`LEGACY_UPDATE_ENVS`], the name the goldens' docs and messages gave longest.
pub const LEGACY_UPDATE_ENV: &str = LEGACY_UPDATE_ENVS[0];

/// Whether golden PNGs are to be written instead of compared: `INSTA_UPDATE=always` (the one
/// switch for PNG goldens and insta snapshots alike), `INSTA_FORCE_UPDATE=1`, or one of
/// [`LEGACY_UPDATE_ENVS`].
#[must_use]
pub fn update_requested() -> bool {
    let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty() && v != "0");
    std::env::var_os(UPDATE_ENV).is_some_and(|v| v == "always")
        || set("INSTA_FORCE_UPDATE")
        || LEGACY_UPDATE_ENVS.into_iter().any(set)
}

/// How different two frames may be and still count as equal (rounding, not regressions).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// A pixel differs when any channel differs by more than this.
    pub max_channel_delta: u8,
    /// The share of pixels (0..=1) allowed to differ.
    pub max_differing_fraction: f64,
}

impl Tolerance {
    /// Every pixel equal: for screenshots of text frames
    /// ([`crate::output::screenshot::screenshot`]), where one changed character is a few dozen
    /// pixels of a large picture and would pass [`Tolerance::default`].
    pub const EXACT: Tolerance = Tolerance {
        max_channel_delta: 0,
        max_differing_fraction: 0.0,
    };
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

/// Asserts `fb` matches the PNG at `path` within `tol`; when [`update_requested`], writes it instead.
///
/// # Panics
/// When the golden file is missing (saying how to create it) or unreadable, the sizes differ, or
/// too many pixels differ (the actual frame is then saved under the system's temporary folder,
/// never in the source tree, and the message names the file); the panic points at the caller.
#[track_caller]
pub fn assert_png_golden(fb: &Framebuffer, path: impl AsRef<Path>, tol: Tolerance) {
    let path = path.as_ref();
    if update_requested() {
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).expect("create golden folder");
        }
        std::fs::write(path, fb.to_png().expect("encode PNG")).expect("write golden PNG");
        return;
    }
    if !path.exists() {
        panic!(
            "no golden image at {} yet: run the test once with {UPDATE_ENV}=always or \
             {LEGACY_UPDATE_ENV}=1 to create it from this frame, look at the PNG, and commit it",
            path.display()
        );
    }
    let golden = std::fs::read(path)
        .map_err(|e| e.to_string())
        .and_then(|bytes| Framebuffer::from_image_bytes(&bytes))
        .unwrap_or_else(|e| {
            panic!(
                "golden {} is not a readable PNG ({e}); run with {UPDATE_ENV}=always to rewrite it",
                path.display()
            )
        });
    let verdict = diff_frames(fb, &golden, tol.max_channel_delta);
    let ok = verdict.is_some_and(|d| {
        d.differing_pixels as f64 <= tol.max_differing_fraction * d.total_pixels as f64
    });
    if !ok {
        let actual = actual_path(path);
        let saved = actual
            .parent()
            .map(std::fs::create_dir_all)
            .unwrap_or(Ok(()))
            .and_then(|()| std::fs::write(&actual, fb.to_png().expect("encode PNG")));
        if let Err(e) = saved {
            panic!(
                "frame differs from {} ({verdict:?}); the actual frame could not be saved as {} ({e})",
                path.display(),
                actual.display()
            );
        }
        panic!(
            "frame differs from {} ({verdict:?}); actual saved as {}; if the change is intended run with {UPDATE_ENV}=always",
            path.display(),
            actual.display()
        );
    }
}

/// Where a failing frame is saved: the system's temporary folder, under a name made of the
/// golden's whole path (so two goldens of one name in different folders do not collide).
fn actual_path(golden: &Path) -> PathBuf {
    let name: String = golden
        .with_extension("actual.png")
        .to_string_lossy()
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '.' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    std::env::temp_dir()
        .join("halfcast-actual")
        .join(name.trim_start_matches('_'))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    #[test]
    fn a_missing_golden_says_how_to_create_it() {
        if update_requested() {
            return; // the variable would create the file instead
        }
        let dir = std::env::temp_dir().join(format!("halfcast-golden-{}", std::process::id()));
        let path = dir.join("not_yet.png");
        let fb = Framebuffer::new(2, 2);
        let (msg, at) = panic_of(|| assert_png_golden(&fb, &path, Tolerance::default()));
        // #[track_caller]: the panic names this line, not the helper's.
        assert_eq!(at, Some((file!().to_string(), line!() - 2)));
        assert!(
            msg.starts_with("no golden image at ")
                && msg.contains("HALFCAST_UPDATE_GOLDEN=1 to create it"),
            "{msg}"
        );
        assert!(!msg.contains("os error"), "{msg}");
        assert!(!path.exists());
    }

    #[test]
    fn a_failing_golden_saves_the_actual_frame_outside_the_source_tree() {
        if update_requested() {
            return; // the variable would rewrite the golden instead
        }
        let dir = std::env::temp_dir().join(format!("halfcast-golden-src-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let golden = dir.join("frame.png");
        std::fs::write(&golden, Framebuffer::new(2, 2).to_png().unwrap()).unwrap();
        let mut fb = Framebuffer::new(2, 2);
        fb.set(0, 0, Rgb::new(255, 255, 255));
        let (msg, _) = panic_of(|| assert_png_golden(&fb, &golden, Tolerance::EXACT));
        let saved = actual_path(&golden);
        assert!(msg.contains(&saved.display().to_string()), "{msg}");
        assert!(saved.starts_with(std::env::temp_dir().join("halfcast-actual")));
        assert_eq!(
            Framebuffer::from_image_bytes(&std::fs::read(&saved).unwrap()).unwrap(),
            fb
        );
        let beside: Vec<_> = std::fs::read_dir(&dir).unwrap().flatten().collect();
        assert_eq!(beside.len(), 1, "only the golden is in its folder");
        std::fs::remove_dir_all(&dir).unwrap();
        std::fs::remove_file(saved).unwrap();
    }

    #[test]
    fn frames_that_differ_fail_at_the_caller_with_the_cell_diff() {
        use crate::termframe::{Glyph, TermCell, TermFrame};
        use ratatui::style::Modifier;
        let a = TermFrame {
            cols: 2,
            rows: 1,
            cells: vec![TermCell::default(); 2],
        };
        let mut b = a.clone();
        b.cells[1].glyph = Glyph::from('x');
        b.cells[1].modifiers = Modifier::REVERSED;
        assert_frames_eq(a.clone(), a.clone());
        let (msg, at) = panic_of(|| assert_frames_eq(a.clone(), b.clone()));
        assert_eq!(at, Some((file!().to_string(), line!() - 1)));
        assert_eq!(
            msg,
            "frames differ (expected -> actual):\n2x1 cells, 1 differ (50.00%), max colour delta 0\n  \
             cell (1,0) glyph, attributes: \" \" -> \"x\" reversed\n"
        );
    }

    /// Runs `f`, which must panic: its message and the location the panic names (seen by a
    /// panic hook that watches this thread only and passes other threads' panics on).
    fn panic_of(f: impl FnOnce() + std::panic::UnwindSafe) -> (String, Option<(String, u32)>) {
        use std::sync::{Arc, Mutex};
        let seen = Arc::new(Mutex::new(None));
        let me = std::thread::current().id();
        let previous = Arc::new(std::panic::take_hook());
        let (record, pass_on) = (seen.clone(), previous.clone());
        std::panic::set_hook(Box::new(move |info| {
            if std::thread::current().id() == me {
                *record.lock().unwrap() = info.location().map(|l| (l.file().to_string(), l.line()));
            } else {
                pass_on(info);
            }
        }));
        let outcome = std::panic::catch_unwind(f);
        let _ = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| previous(info)));
        let payload = outcome.expect_err("the call panics");
        let msg = payload
            .downcast_ref::<String>()
            .cloned()
            .unwrap_or_default();
        let at = seen.lock().unwrap().clone();
        (msg, at)
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
