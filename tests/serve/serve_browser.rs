//! The page in a real browser: Debian's Chromium, headless, driven by Playwright for Python
//! (`browser/page_check.py`). It joins the world beside an SSH player, who sees its name; the
//! view is drawn; a held key turns it and its release stops it; a tap moves it, and taps of 0 ms
//! and 20 ms each turn it by one tap's step; losing focus lets go of a held key; Escape never
//! ends the game; a larger window is a larger session; and the painter's pixels equal
//! halfcast's own reading of the same frame bytes (`termframe`) cell by cell. A touch phone fits
//! the page and plays by touch (`browser/phone_check.py`), and an open page plays again by itself
//! after its server drains and restarts (`browser/restart_check.py`), and a page on a fast link
//! turns in truecolor with raw frames, its Quit bar out of the header's way while the mouse
//! rests (`browser/levels_check.py`). Prints a skip notice when
//! Chromium or Playwright is absent (`.ci/run` installs both).

use std::path::Path;
use std::time::Duration;

use halfcast::encode::glyph_mask::mask_of;
use halfcast::serve::web::WebOptions;
use halfcast::termframe::{from_ansi_sized, CellRgb, TermFrame};
use halfcast::Glyphs;
use halfcast::World;
use serde_json::Value;

use crate::serve_support::browser;
use crate::serve_support::{header_has, row_text, server_with, view_rect, Client};

/// How long after a key's release the view may still change, with room for a loaded 2-core
/// machine running the browser, the server and the tests at once (the measured figure is
/// printed; docs/serving.md has it).
const RELEASE_BOUND_MS: f64 = 1000.0;

/// The default map with nothing that moves by itself (creatures, animated sprites, items): only
/// the player's keys change the view, so "the view stopped" can be seen.
fn still_world() -> World {
    crate::serve_support::default_world_keeping(|l| !l.contains("frames="))
}

/// One tap's step of turn over SSH (`ui::keys::TAP_TURN_DEG`); the status line shows the angle to
/// a tenth of a degree.
const TAP_DEGREES: f64 = 8.0;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn chromium_plays_on_the_page() {
    if !browser::ready() {
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
    let url = format!("http://{web}/");
    let child = browser::start("page_check.py", &[url.as_ref(), out.as_os_str()]);
    let run = tokio::task::spawn_blocking(move || browser::finish("page_check.py", child));
    // While the browser plays, the SSH player sees it in the header.
    let seen = ssh.until(|s| header_has(s, "chromey")).await;
    let header = row_text(ssh.screen.screen(), 0);
    ssh.drain_for(Duration::from_millis(300)).await;
    drop(ssh);
    let figures = joined(run.await);
    assert!(
        seen,
        "the SSH player never saw the browser player: {header:?}"
    );
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
    // A press and its release in one task (0 ms) reach the world together: exactly one tap's
    // step. A 20 ms hold may be seen by two of the world's ticks on a loaded machine, and then
    // moves by the ticks that saw it (the tap rule): never less than one tap's step.
    for ms in [0, 20] {
        let steps = &f[format!("tap_{ms}ms_degrees")];
        let moved = &f[format!("tap_{ms}ms_view_moved")];
        for (step, moved) in steps
            .as_array()
            .unwrap()
            .iter()
            .zip(moved.as_array().unwrap())
        {
            let step = step
                .as_f64()
                .unwrap_or_else(|| panic!("no angle on the status line: {f}"))
                .abs();
            assert!(
                step >= TAP_DEGREES - 0.15,
                "a {ms} ms tap of d turned {step}°, less than one tap's {TAP_DEGREES}°: {f}"
            );
            if ms == 0 {
                assert!(
                    step <= TAP_DEGREES + 0.15,
                    "a 0 ms tap of d turned {step}°, not one tap's {TAP_DEGREES}°: {f}"
                );
            }
            assert_eq!(
                moved,
                &Value::Bool(true),
                "a {ms} ms tap left the view: {f}"
            );
        }
    }
    let help = |down| serde_json::json!(["?", down]);
    assert_eq!(
        f["escape_sent"],
        Value::Array(vec![help(true), help(false), help(true), help(false)]),
        "Escape is never sent; with the help shown it closes it (the help key again)"
    );
    assert_eq!(
        f["escape_playing"],
        Value::Bool(true),
        "Escape ended the game: {f}"
    );
    assert_eq!(f["escape_form_hidden"], Value::Bool(true), "{f}");
    assert_eq!(f["escape_then_turned"], Value::Bool(true), "{f}");
    assert_eq!(
        f["inflate_order"],
        serde_json::json!(["one", "two", "probe 1", "three…10000", "four"]),
        "frames inflated and handed on in the order they came, text messages in between"
    );
    assert_eq!(f["quit_said"], "you left the game", "{f}");
    assert_eq!(f["spectate_button"], "Watch", "{f}");
    assert_eq!(f["spectate_name_shown"], Value::Bool(false), "{f}");
    assert_eq!(f["keys_help_shown"], Value::Bool(true), "{f}");
    assert_eq!(f["fullscreen_button"], Value::Bool(true), "{f}");
    assert_eq!(f["enter_watches"], Value::Bool(true), "{f}");
    let world = f["info"]["world"]
        .as_str()
        .expect("/info.json names the world");
    let players = f["info"]["players"]
        .as_u64()
        .expect("and counts the players");
    assert!(players >= 1, "chromey plays: {f}");
    let title = f["title"].as_str().unwrap_or("");
    assert!(
        title.starts_with(&format!("{world} · ")) && title.contains(" playing"),
        "the title names the world and the player count: {title:?}"
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

/// Runs `browser/NAME URL OUTDIR` to its end, off the test's runtime: its last line's JSON.
async fn run_check(name: &'static str, url: String, out: &Path) -> Value {
    let out = out.to_owned();
    let run =
        tokio::task::spawn_blocking(move || browser::run(name, &[url.as_ref(), out.as_os_str()]));
    joined(run.await)
}

/// A blocking task's result, its panic (a failed check, with what it printed) passed on as is.
fn joined<T>(done: Result<T, tokio::task::JoinError>) -> T {
    done.unwrap_or_else(|e| std::panic::resume_unwind(e.into_panic()))
}

/// Whether the box `[left, top, right, bottom]` lies within a `w` × `h` screen.
fn inside(b: &Value, (w, h): (i64, i64)) -> bool {
    let n: Vec<i64> = serde_json::from_value(b.clone()).unwrap();
    n[0] >= 0 && n[1] >= 0 && n[2] <= w && n[3] <= h && n[0] < n[2] && n[1] < n[3]
}

/// A layout from phone_check.py fits its screen: nothing wider than it, the grid (and, while
/// playing, the touch controls) wholly on it.
fn fits(f: &Value, what: &str, playing: bool) {
    let l = &f[what];
    let inner: (i64, i64) = serde_json::from_value(l["inner"].clone()).unwrap();
    let scroll: (i64, i64) = serde_json::from_value(l["scroll"].clone()).unwrap();
    assert!(
        scroll.0 <= inner.0,
        "{what}: the page is wider than the screen: {l}"
    );
    assert!(
        scroll.1 <= inner.1,
        "{what}: the page is taller than the screen: {l}"
    );
    assert!(
        inside(&l["grid_box"], inner),
        "{what}: the grid is not all on screen: {l}"
    );
    if playing {
        assert_eq!(l["form_shown"], Value::Bool(false), "{l}");
        assert!(
            inside(&l["pad_box"], inner),
            "{what}: the stick is off screen: {l}"
        );
        assert!(
            inside(&l["buttons_box"], inner),
            "{what}: buttons off screen: {l}"
        );
    } else {
        assert!(
            inside(&l["form_box"], inner),
            "{what}: the form is cut: {l}"
        );
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_page_on_a_fast_link_turns_in_truecolor_raw() {
    let Some(f) = check_on_still_world("levels_check.py").await else {
        return;
    };
    println!("fast link figures: {f}");
    assert_eq!(f["page_errors"], Value::Array(vec![]), "{f}");
    // The page paints and acks each frame itself, sometimes late (a busy moment of the page
    // once is no slow link): the level stays, and frames go as they are (but for a compressed
    // spell after a long busy moment: in 1 run of 5 here, half the turn).
    let status = f["status"].as_str().unwrap_or_default();
    assert!(status.contains("truecolor (browser)"), "{f}");
    let (frames, compressed) = (
        f["turn_frames"].as_u64().unwrap(),
        f["compressed"].as_u64().unwrap(),
    );
    assert!(frames > 0, "the view turned: {f}");
    assert!(compressed < frames, "raw frames on loopback: {f}");
    // Quit and Fullscreen sit over the header's end: hidden while the mouse rests, back on a move.
    assert_eq!(f["bar_opacity_still"].as_f64(), Some(0.0), "{f}");
    assert!(f["bar_opacity_moved"].as_f64() > Some(0.5), "{f}");
}

/// Runs `browser/NAME` against a server of the still world with its web edge on (stopped once
/// the check ends): the check's figures, or `None` with a notice where Chromium or Playwright
/// is absent.
async fn check_on_still_world(name: &'static str) -> Option<Value> {
    if !browser::ready() {
        return None;
    }
    let (srv, dir) = server_with(
        |c| c.web = Some(WebOptions::new("127.0.0.1:0".parse().unwrap())),
        still_world(),
    )
    .await;
    let web = srv.web_addr().expect("web listener");
    let out = dir.path().join(name.trim_end_matches(".py"));
    std::fs::create_dir_all(&out).unwrap();
    let f = run_check(name, format!("http://{web}/"), &out).await;
    srv.shutdown().await;
    Some(f)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_touch_phone_fits_the_screen_and_plays_by_touch() {
    let Some(f) = check_on_still_world("phone_check.py").await else {
        return;
    };
    println!("phone figures: {f}");
    assert_eq!(f["page_errors"], Value::Array(vec![]), "{f}");
    assert_eq!(f["touch_help_shown"], Value::Bool(true), "{f}");
    fits(&f, "landing", false);
    fits(&f, "portrait", true);
    fits(&f, "landscape", true);
    let keys = |k: &str| -> Vec<(String, bool)> { serde_json::from_value(f[k].clone()).unwrap() };
    let walk = keys("walk_keys");
    assert!(
        walk.first() == Some(&("w".into(), true)) && walk.contains(&("w".into(), false)),
        "the stick pushed up did not walk forward: {walk:?}"
    );
    assert_eq!(
        f["walk_moved"],
        Value::Bool(true),
        "walking by touch left the view: {f}"
    );
    let turn = keys("turn_keys");
    let taps = turn
        .iter()
        .filter(|k| **k == ("d".to_owned(), true))
        .count();
    assert!(
        taps >= 3,
        "a 90 px drag right made {taps} taps of d: {turn:?}"
    );
    assert_eq!(turn.len(), 2 * taps, "every tap let go: {turn:?}");
    assert_eq!(
        f["turn_moved"],
        Value::Bool(true),
        "a drag left the view: {f}"
    );
    assert_eq!(f["other_messages"], Value::Array(vec![]), "{f}");
    let landscape: (u64, u64) = serde_json::from_value(f["landscape"]["grid"].clone()).unwrap();
    let portrait: (u64, u64) = serde_json::from_value(f["portrait"]["grid"].clone()).unwrap();
    assert!(landscape.0 > portrait.0 && landscape.1 < portrait.1, "{f}");
    let sent: Vec<(u64, u64)> = serde_json::from_value(f["sizes_sent"].clone()).unwrap();
    assert_eq!(
        sent.last(),
        Some(&landscape),
        "the turned phone's grid was not sent"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_restarted_server_gets_the_open_page_playing_again_by_itself() {
    use std::io::BufRead;
    if !browser::ready() {
        return;
    }
    let web_on = |addr: std::net::SocketAddr| {
        move |c: &mut halfcast::serve::ServeConfig| {
            c.web = Some(WebOptions::new(addr));
        }
    };
    let (srv, dir) = server_with(web_on("127.0.0.1:0".parse().unwrap()), still_world()).await;
    let web = srv.web_addr().expect("web listener");
    let out = dir.path().join("restart");
    std::fs::create_dir_all(&out).unwrap();
    let url = format!("http://{web}/");
    let mut child = browser::start("restart_check.py", &[url.as_ref(), out.as_os_str()]);
    let mut lines = std::io::BufReader::new(child.stdout.take().unwrap()).lines();
    let (first, mut lines) = tokio::task::spawn_blocking(move || (lines.next(), lines))
        .await
        .unwrap();
    let first = first.and_then(Result::ok);
    assert_eq!(first.as_deref(), Some("playing"), "the page never played");
    // systemd's restart: drain, stop, start again on the same port.
    srv.drain(Duration::from_secs(1)).await;
    srv.shutdown_restarting().await;
    let (again, _dir2) = server_with(web_on(web), still_world()).await;
    // The page waits the restart's spread wait (2-15 s) and plays again, then reports.
    let last = tokio::task::spawn_blocking(move || lines.next().and_then(Result::ok))
        .await
        .unwrap();
    let mut ssh = Client::connect(again.local_addr(), "sshy", 100, 20, "xterm-256color").await;
    let seen = ssh.until(|s| header_has(s, "chromey")).await;
    let header = row_text(ssh.screen.screen(), 0);
    drop(ssh);
    drop(child.stdin.take());
    let done = tokio::task::spawn_blocking(move || child.wait_with_output())
        .await
        .unwrap()
        .expect("its output");
    assert!(
        done.status.success(),
        "restart_check.py failed:\n{}",
        String::from_utf8_lossy(&done.stderr)
    );
    let f: Value = serde_json::from_str(&last.unwrap_or_default()).expect("JSON");
    println!("restart figures: {f}");
    assert_eq!(f["page_errors"], Value::Array(vec![]), "{f}");
    assert_eq!(
        f["form_instead"],
        Value::Null,
        "the page went back to its form instead of reconnecting (contract 2: a restart closes \
         with 1012 and `reconnect to continue in N s`): {f}"
    );
    assert!(
        seen,
        "the restarted world never saw chromey again: {header:?}"
    );
    let notice = f["notices"][0].as_str().unwrap_or("");
    assert!(
        notice.contains("reconnecting as chromey"),
        "the page did not say it reconnects: {f}"
    );
    let sockets = f["sockets"].as_array().unwrap();
    assert!(sockets.len() >= 2, "{f}");
    assert!(
        sockets
            .iter()
            .all(|u| u.as_str().unwrap().contains("name=chromey")),
        "every connection under the same name: {f}"
    );
    assert_eq!(f["form_shown"], Value::Bool(false), "{f}");
    assert_eq!(f["notice_after"], Value::Null, "{f}");
    again.shutdown().await;
}
