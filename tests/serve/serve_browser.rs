//! The page in a real browser: Debian's Chromium, headless, driven by Playwright for Python
//! (`browser/page_check.py`). It joins the world beside an SSH player, who sees its name; the
//! view is drawn; a held key turns it and its release stops it; a tap moves it; losing focus lets
//! go of a held key; a larger window
//! is a larger session; and the painter's pixels equal halfcast's own reading of the same frame
//! bytes (`termframe`) cell by cell. Prints a skip notice when Chromium or Playwright is absent
//! (`.ci/run` installs both).

use std::path::{Path, PathBuf};
use std::time::Duration;

use halfcast::encode::glyph_mask::mask_of;
use halfcast::serve::web::WebOptions;
use halfcast::termframe::{from_ansi_sized, CellRgb, TermFrame};
use halfcast::Glyphs;
use halfcast::World;
use serde_json::Value;

use crate::serve_support::{header_has, row_text, server_with, view_rect, Client};

/// Where Debian's `chromium` package puts the browser.
const CHROMIUM: &str = "/usr/bin/chromium";
/// How long after a key's release the view may still change, with room for a loaded 2-core
/// machine running the browser, the server and the tests at once (the measured figure is
/// printed; docs/serving.md has it).
const RELEASE_BOUND_MS: f64 = 1000.0;

fn browser_ready() -> bool {
    Path::new(CHROMIUM).exists()
        && std::process::Command::new("python3")
            .args(["-c", "import playwright"])
            .output()
            .is_ok_and(|o| o.status.success())
}

/// The default map with nothing that moves by itself (creatures, animated sprites, items): only
/// the player's keys change the view, so "the view stopped" can be seen.
fn still_world() -> World {
    crate::serve_support::default_world_keeping(|l| !l.contains("frames="))
}

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/serve/browser/page_check.py")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn chromium_plays_on_the_page() {
    if !browser_ready() {
        eprintln!("skip: no {CHROMIUM} or no Python playwright (apt-get install chromium; pip install playwright)");
        return;
    }
    let (srv, dir) = server_with(
        |c| c.web = Some(WebOptions::new("127.0.0.1:0".parse().unwrap())),
        still_world(),
    )
    .await;
    let web = srv.web_addr().expect("web listener");
    let mut ssh = Client::connect(srv.local_addr(), "sshy", 100, 20, "xterm-256color").await;
    let out = dir.path().join("browser");
    std::fs::create_dir_all(&out).unwrap();
    let child = std::process::Command::new("python3")
        .arg(script())
        .arg(format!("http://{web}/"))
        .arg(&out)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("python3 runs");
    let run = tokio::task::spawn_blocking(move || child.wait_with_output());
    // While the browser plays, the SSH player sees it in the header.
    let seen = ssh.until(|s| header_has(s, "chromey")).await;
    let header = row_text(ssh.screen.screen(), 0);
    ssh.drain_for(Duration::from_millis(300)).await;
    drop(ssh);
    let done = run.await.expect("joined").expect("its output");
    let stdout = String::from_utf8_lossy(&done.stdout);
    assert!(
        done.status.success(),
        "page_check.py failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&done.stderr)
    );
    assert!(
        seen,
        "the SSH player never saw the browser player: {header:?}"
    );
    let figures: Value = serde_json::from_str(stdout.lines().last().unwrap_or("")).expect("JSON");
    println!("browser figures: {figures}");
    check_figures(&figures);
    for (name, cols, rows) in [("small", 80, 24), ("large", 160, 45)] {
        let (compared, wrong) = painter_against_termframe(&out, name);
        println!("{name} ({cols}×{rows}): {compared} view pixels compared, {wrong} differ");
        assert!(
            compared >= cols * rows / 2,
            "{name}: too little view compared"
        );
        assert_eq!(
            wrong, 0,
            "{name}: the painter's pixels differ from termframe's reading"
        );
    }
    let (compared, wrong) = octants_against_termframe(&out);
    println!("octant (160×45): {compared} octant pixels compared, {wrong} differ");
    assert!(compared > 1000, "too few octant cells drawn");
    assert_eq!(
        wrong, 0,
        "the painter's octant cells differ from termframe's reading"
    );
    srv.shutdown().await;
}

fn check_figures(f: &Value) {
    let num = |k: &str| f[k].as_f64().unwrap_or_else(|| panic!("{k} in {f}"));
    assert_eq!(f["page_errors"], Value::Array(vec![]), "{f}");
    assert_eq!(f["grid"], serde_json::json!([80, 24]));
    assert!(
        num("distinct_colours") > 16.0,
        "the view was not drawn: {f}"
    );
    assert!(
        num("turning_fps") > 0.0,
        "holding d never turned the view: {f}"
    );
    assert!(
        num("release_lag_ms") <= RELEASE_BOUND_MS,
        "the view still turned {} ms after the release",
        num("release_lag_ms")
    );
    assert!(
        num("tap_changes") >= 1.0,
        "a tap did not move the view: {f}"
    );
    assert!(num("tap_lag_ms") <= RELEASE_BOUND_MS, "{f}");
    assert!(
        num("blur_turned") >= 1.0,
        "holding d before the blur turned nothing: {f}"
    );
    assert!(
        num("blur_lag_ms") <= RELEASE_BOUND_MS,
        "the view still turned {} ms after the window lost focus",
        num("blur_lag_ms")
    );
    assert_eq!(f["small"], serde_json::json!([80, 24]));
    assert_eq!(
        f["large"],
        serde_json::json!([160, 45]),
        "the resize did not reach the session"
    );
}

/// The snapshot `name`: its JSON and halfcast's reading of the frames it drew (from the last
/// full redraw, the one after the session's last resize).
fn snapshot_and_reading(out: &Path, name: &str) -> (Value, TermFrame) {
    let snap: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join(format!("{name}.json"))).unwrap())
            .unwrap();
    let raw = std::fs::read(out.join(format!("{name}.frames"))).unwrap();
    let mut frames = Vec::new();
    let mut at = 0;
    while at + 4 <= raw.len() {
        let n = u32::from_be_bytes(raw[at..at + 4].try_into().unwrap()) as usize;
        frames.push(&raw[at + 4..at + 4 + n]);
        at += 4 + n;
    }
    assert_eq!(frames.len() as u64, snap["frames"].as_u64().unwrap());
    let start = frames
        .iter()
        .rposition(|f| f.windows(4).any(|w| w == b"\x1b[2J"))
        .unwrap_or(0);
    let bytes: Vec<u8> = frames[start..].concat();
    let cols = snap["cols"].as_u64().unwrap() as u16;
    let rows = snap["rows"].as_u64().unwrap() as u16;
    let tf = from_ansi_sized(&bytes, cols, rows);
    (snap, tf)
}

/// A cell's foreground and background as the page shows them (defaults, reverse video).
fn shown_colours(cell: &halfcast::termframe::TermCell) -> ((u8, u8, u8), (u8, u8, u8)) {
    let rgb = |c: Option<halfcast::color::Rgb>, d: (u8, u8, u8)| c.map_or(d, |c| (c.r, c.g, c.b));
    let fg = rgb(cell.fg_rgb(), (229, 229, 229));
    let bg = rgb(cell.bg_rgb(), (0, 0, 0));
    if cell.modifiers.contains(ratatui::style::Modifier::REVERSED) {
        (bg, fg)
    } else {
        (fg, bg)
    }
}

/// Compares the page's glyph canvas at the middle of each octant pixel with the mask and
/// colours of halfcast's reading of the same frames, over the view's octant cells: (pixels
/// compared, pixels that differ).
fn octants_against_termframe(out: &Path) -> (usize, usize) {
    let (snap, tf) = snapshot_and_reading(out, "octant");
    let samples: Vec<u32> = serde_json::from_value(snap["samples"].clone()).unwrap();
    let (cols, rows) = (tf.cols, tf.rows);
    let view = view_rect(cols as u16, rows as u16);
    let (mut compared, mut wrong) = (0, 0);
    for y in usize::from(view.top())..usize::from(view.bottom()) {
        for x in usize::from(view.left())..usize::from(view.right()) {
            let cell = tf.cell(x, y);
            let ch = cell.glyph.first_char();
            if matches!(ch, ' ' | '▀' | '▄' | '█') {
                continue;
            }
            let Some(mask) = mask_of(Glyphs::Octant, ch) else {
                continue;
            };
            let (fg, bg) = shown_colours(cell);
            for k in 0..8 {
                let (r, g, b) = if mask & (1 << k) != 0 { fg } else { bg };
                let want = (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b);
                compared += 1;
                if samples[(y * cols + x) * 8 + k] != want {
                    wrong += 1;
                }
            }
        }
    }
    (compared, wrong)
}

/// Compares the page's pixel canvas (and which cells it drew as glyphs instead) with halfcast's
/// own reading of the frames the page drew, over the view: (pixels compared, pixels that differ).
fn painter_against_termframe(out: &Path, name: &str) -> (usize, usize) {
    let (snap, tf) = snapshot_and_reading(out, name);
    let (cols, rows) = (tf.cols as u16, tf.rows as u16);
    let pixels: Vec<u8> = serde_json::from_value(snap["pixels"].clone()).unwrap();
    let over: Vec<u8> = serde_json::from_value(snap["over"].clone()).unwrap();
    let (cols_u, rows_u) = (usize::from(cols), usize::from(rows));
    assert_eq!(pixels.len(), cols_u * rows_u * 2 * 4);
    let at_px = |x: usize, y: usize| {
        let i = (y * cols_u + x) * 4;
        (pixels[i], pixels[i + 1], pixels[i + 2])
    };
    let view = view_rect(cols, rows);
    let (mut compared, mut wrong) = (0, 0);
    for y in 0..rows_u {
        for x in 0..cols_u {
            let cell = tf.cell(x, y);
            let ch = cell.glyph.first_char();
            let half = matches!(ch, ' ' | '▀' | '▄' | '█');
            assert_eq!(over[y * cols_u + x] == 0, half, "cell {x},{y} {ch:?}");
            let inside = (view.left()..view.right()).contains(&(x as u16))
                && (view.top()..view.bottom()).contains(&(y as u16));
            if !inside || !half {
                continue;
            }
            let rgb =
                |c: Option<halfcast::color::Rgb>, d: (u8, u8, u8)| c.map_or(d, |c| (c.r, c.g, c.b));
            let mut fg = rgb(cell.fg_rgb(), (229, 229, 229));
            let mut bg = rgb(cell.bg_rgb(), (0, 0, 0));
            if cell.modifiers.contains(ratatui::style::Modifier::REVERSED) {
                std::mem::swap(&mut fg, &mut bg);
            }
            let (top, bottom) = match ch {
                '▀' => (fg, bg),
                '▄' => (bg, fg),
                '█' => (fg, fg),
                _ => (bg, bg),
            };
            for (want, py) in [(top, 2 * y), (bottom, 2 * y + 1)] {
                compared += 1;
                if at_px(x, py) != want {
                    wrong += 1;
                }
            }
        }
    }
    (compared, wrong)
}
