//! 256 and 16 colours as a person at a terminal sees them (issue 20): the Rust S-CIELAB figures
//! agree with `../shared/tools/scielab.py`, a still camera sends nothing after its first frame,
//! and the mixes' patterns lie on the surfaces.

use crate::common;

use std::process::Command;

use halfcast::bench::scielab::{self, Figures, Source};
use halfcast::encode::palette::{xterm_rgb, ANSI16};
use halfcast::encode::{ColorLevel, EncodeOptions, Encoder};
use halfcast::{Camera, Framebuffer, Rgb, Scene, World};

/// Whether python3 with numpy, pyte and Pillow can run the tool (else a printed notice).
fn python_ready() -> bool {
    let ok = Command::new("python3")
        .args(["-c", "import numpy, pyte, PIL"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        eprintln!("skipped: python3 with numpy, pyte and Pillow is not available");
    }
    ok
}

/// The figures the tool computes for (source, shown) PNG pairs: per pair halfcast's, nearest's
/// and Floyd–Steinberg's, each `[plain, 4.5 ppd, 9 ppd, chroma, hue]` (NaN for "none").
fn tool_figures(tools: &std::path::Path, pairs: &[(String, String, &str)]) -> Vec<[[f64; 5]; 3]> {
    let script = r#"
import sys, json
sys.path.insert(0, sys.argv[1])
import numpy as np
from PIL import Image
import scielab as S
out = []
for src, shown, colors in json.loads(sys.argv[2]):
    a = np.array(Image.open(src).convert("RGB"), dtype=np.float64)
    b = np.array(Image.open(shown).convert("RGB"), dtype=np.float64)
    pal = S.xterm256() if colors == "256" else S.xterm16()
    rows = []
    for img in (b, S.nearest(a, pal), S.fs(a, pal)):
        rows.append([float("nan") if v is None else float(v) for v in S.figures(a, img)])
    out.append(rows)
print(json.dumps(out).replace("NaN", "null"))
"#;
    let arg = serde_json::to_string(pairs).unwrap();
    let out = Command::new("python3")
        .args(["-c", script, tools.to_str().unwrap(), &arg])
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Vec<Vec<Vec<Option<f64>>>> = serde_json::from_slice(&out.stdout).unwrap();
    v.into_iter()
        .map(|pair| {
            let row = |i: usize| {
                let r = &pair[i];
                [0, 1, 2, 3, 4].map(|k| r[k].unwrap_or(f64::NAN))
            };
            [row(0), row(1), row(2)]
        })
        .collect()
}

fn as_row(f: Figures) -> [f64; 5] {
    [
        f.plain_de,
        f.scielab_45,
        f.scielab_9,
        f.chroma_kept.unwrap_or(f64::NAN),
        f.hue_error.unwrap_or(f64::NAN),
    ]
}

/// What the encoder shows for `fb` at `level`, as pixels.
fn shown(level: ColorLevel, fb: &Framebuffer) -> Framebuffer {
    let mut enc = Encoder::new(EncodeOptions::new(level));
    let _ = enc.encode(fb, 0, 0);
    enc.shown_frame().expect("a colour level")
}

#[test]
fn rust_figures_match_the_python_tool() {
    let Some(shared) = common::shared_dir("the S-CIELAB tool") else {
        return;
    };
    let tools = shared.join("tools");
    if !tools.join("scielab.py").is_file() || !python_ready() {
        eprintln!("skipped: ../shared/tools/scielab.py cannot run here");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let world = World::default_world();
    let mut pairs = Vec::new();
    let mut ours = Vec::new();
    for (i, (x, y, a, level)) in [
        (15.5, 5.5, 90.0, ColorLevel::Ansi256),
        (12.5, 9.5, 160.0, ColorLevel::Ansi256),
        (15.5, 5.5, 125.0, ColorLevel::Ansi16),
    ]
    .into_iter()
    .enumerate()
    {
        let cam = Camera::from_angle(halfcast::Vec2::new(x, y), a, 66.0);
        let fb = Scene::new(&world, cam).render(48, 16);
        let seen = shown(level, &fb);
        let (src, out) = (
            dir.path().join(format!("src{i}.png")),
            dir.path().join(format!("shown{i}.png")),
        );
        std::fs::write(&src, fb.to_png().unwrap()).unwrap();
        std::fs::write(&out, seen.to_png().unwrap()).unwrap();
        let palette: Vec<Rgb> = if level == ColorLevel::Ansi256 {
            (16..=255).map(xterm_rgb).collect()
        } else {
            ANSI16.to_vec()
        };
        let source = Source::new(&fb);
        let (n, f) = source.baselines(&palette);
        ours.push([as_row(source.compare(&seen)), as_row(n), as_row(f)]);
        let colors = if level == ColorLevel::Ansi256 {
            "256"
        } else {
            "16"
        };
        pairs.push((
            src.to_string_lossy().into_owned(),
            out.to_string_lossy().into_owned(),
            colors,
        ));
    }
    let theirs = tool_figures(&tools, &pairs);
    let names = ["halfcast", "nearest", "floyd-steinberg"];
    for (i, (o, t)) in ours.iter().zip(&theirs).enumerate() {
        for m in 0..3 {
            for k in 0..5 {
                let (a, b) = (o[m][k], t[m][k]);
                assert!(
                    (a.is_nan() && b.is_nan()) || (a - b).abs() <= 1e-6 * b.abs().max(1.0),
                    "frame {i}, {}: figure {k} is {a} in Rust, {b} in the tool",
                    names[m]
                );
            }
        }
    }
}

#[test]
fn a_still_camera_sends_nothing_after_its_first_frame() {
    // Patterns depend on the surfaces and the pixels only: the same frame encodes to the same
    // cells, so the diff is empty, at every level.
    let world = World::default_world();
    let cam = Camera::from_angle(halfcast::Vec2::new(15.5, 5.5), 125.0, 66.0);
    for level in ColorLevel::ALL {
        let mut enc = Encoder::new(EncodeOptions::new(level));
        let first = enc
            .encode(&Scene::new(&world, cam).render(80, 24), 0, 0)
            .len();
        assert!(first > 0, "{level}: the first frame draws");
        for _ in 0..3 {
            let fb = Scene::new(&world, cam).render(80, 24);
            assert_eq!(enc.encode(&fb, 0, 0).len(), 0, "{level}: a still frame");
        }
    }
}

#[test]
fn the_figures_of_an_exact_copy_are_zero_and_its_colour_kept() {
    let world = World::default_world();
    let cam = Camera::from_angle(halfcast::Vec2::new(15.5, 5.5), 90.0, 66.0);
    let fb = Scene::new(&world, cam).render(80, 24);
    let f = Source::new(&fb).compare(&fb);
    assert_eq!((f.plain_de, f.scielab_45, f.scielab_9), (0.0, 0.0, 0.0));
    assert!((f.chroma_kept.unwrap() - 1.0).abs() < 1e-12);
    assert!(f.hue_error.unwrap() < 1e-3);
    assert!(scielab::mean(&[]).is_none());
}
