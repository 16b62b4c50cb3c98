//! A player on a slow link sees the newest frame, not a queue of old ones: on a shaped loopback
//! (512 kbit/s token bucket with a 200 ms queue, MTU 1500, in a network namespace of its own, as
//! `../shared/tools/linklag.py` builds it), a held turn key is released and only the frames drawn
//! while the key still counted as held, plus two, arrive after the last key byte. Before frames
//! were paced by the link, seconds of queued frames (hundreds of kB) arrived after the release.
//!
//! A browser page on 3 Mbit/s gets truecolor at 80×24 while turning: its frames go compressed
//! rather than the colour level dropping.
//!
//! Each test re-runs itself under `unshare -rn` (a user and network namespace) to shape the
//! namespace's own loopback; it skips with a notice where `unshare`, `ip` or `tc` are missing or
//! namespaces are not allowed.

use crate::serve_support::web::open;
use crate::serve_support::{header_has, row_text, server, Client};

use std::process::Command;
use std::time::{Duration, Instant};

use russh::ChannelMsg;

/// Set in the re-run inside the namespace.
const INSIDE: &str = "HALFCAST_SLOW_LINK_INSIDE";
/// The link the SSH test shapes.
const RATE: &str = "512kbit";
/// The end of every frame (each is one synchronized update).
const FRAME_END: &[u8] = b"\x1b[?2026l";

fn tool(name: &str) -> bool {
    Command::new(name)
        .arg("-V")
        .output()
        .is_ok_and(|o| o.status.success())
        || Command::new("sh")
            .args(["-c", &format!("command -v {name}")])
            .output()
            .is_ok_and(|o| o.status.success())
}

#[test]
fn after_a_held_key_is_released_only_the_newest_frames_arrive() {
    in_namespace(
        "after_a_held_key_is_released_only_the_newest_frames_arrive",
        "slow link:",
        inside,
    );
}

#[test]
fn a_page_on_three_megabits_turns_in_truecolor_compressed() {
    in_namespace(
        "a_page_on_three_megabits_turns_in_truecolor_compressed",
        "page link:",
        page_inside,
    );
}

/// Runs `test` (this file's test of that name) again inside a network namespace of its own,
/// where it calls `inside`; outside, checks it ran there and printed `said`.
fn in_namespace(test: &str, said: &str, inside: fn()) {
    if std::env::var_os(INSIDE).is_some() {
        inside();
        return;
    }
    for t in ["unshare", "ip", "tc"] {
        if !tool(t) {
            println!("SKIPPED: `{t}` is not installed (apt-get install util-linux iproute2)");
            return;
        }
    }
    let exe = std::env::current_exe().expect("test binary");
    let out = Command::new("unshare")
        .arg("-rn")
        .arg(&exe)
        .args([
            "--exact",
            &format!("serve_slow_link::{test}"),
            "--nocapture",
            "--test-threads=1",
        ])
        .env(INSIDE, "1")
        .output()
        .expect("run unshare");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() && stderr.contains("unshare failed") {
        println!(
            "SKIPPED: network namespaces are not allowed here ({})",
            stderr.trim()
        );
        return;
    }
    println!("{stdout}");
    assert!(
        out.status.success(),
        "inside the namespace:\n{stdout}\n{stderr}"
    );
    assert!(stdout.contains(said), "the test ran inside:\n{stdout}");
}

/// Shapes the namespace's loopback to a `rate` token bucket with a 200 ms queue.
fn shape(rate: &str) {
    let sh = |args: &[&str]| {
        let out = Command::new(args[0])
            .args(&args[1..])
            .output()
            .expect("run");
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    sh(&["ip", "link", "set", "lo", "up", "mtu", "1500"]);
    sh(&[
        "tc", "qdisc", "add", "dev", "lo", "root", "tbf", "rate", rate, "burst", "16kb", "latency",
        "200ms",
    ]);
}

/// In the namespace: shape loopback, serve, hold a key, release it, count what still comes.
fn inside() {
    shape(RATE);
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    rt.block_on(async {
        let (srv, _dir) = server(|_| {}).await;
        let mut c = Client::connect(srv.local_addr(), "slow", 80, 24, "xterm-256color").await;
        assert!(c.until(|s| header_has(s, "you are slow")).await);
        c.drain_for(Duration::from_secs(1)).await;
        // Hold `d` (turn) for 3 s, the key repeated every 33 ms as a terminal's auto-repeat
        // sends it, reading all the while.
        let mut log: Vec<(Instant, usize, usize)> = Vec::new();
        let started = Instant::now();
        let mut next_key = started;
        let mut last_key = started;
        while started.elapsed() < Duration::from_secs(3) {
            if Instant::now() >= next_key {
                c.keys(b"d").await;
                last_key = Instant::now();
                next_key += Duration::from_millis(33);
            }
            let until = tokio::time::Instant::from_std(next_key);
            while let Ok(Some(msg)) = tokio::time::timeout_at(until, c.wait()).await {
                if let ChannelMsg::Data { data } = msg {
                    log.push((Instant::now(), data.len(), frames_in(&data)));
                    c.screen.process(&data);
                }
            }
        }
        // Released: read for 3 s more.
        let end = tokio::time::Instant::now() + Duration::from_secs(3);
        while let Ok(Some(msg)) = tokio::time::timeout_at(end, c.wait()).await {
            if let ChannelMsg::Data { data } = msg {
                log.push((Instant::now(), data.len(), frames_in(&data)));
                c.screen.process(&data);
            }
        }
        let held: Vec<_> = log.iter().filter(|e| e.0 <= last_key).collect();
        let after: Vec<_> = log.iter().filter(|e| e.0 > last_key).collect();
        let held_bytes: usize = held.iter().map(|e| e.1).sum();
        let held_frames: usize = held.iter().map(|e| e.2).sum();
        let after_bytes: usize = after.iter().map(|e| e.1).sum();
        let after_frames: usize = after.iter().map(|e| e.2).sum();
        let frame = held_bytes / held_frames.max(1);
        let settled = after
            .iter()
            .filter(|e| e.1 > 1500)
            .map(|e| e.0.duration_since(last_key))
            .max()
            .unwrap_or_default();
        println!(
            "slow link: {RATE}, 80x24, starting at 256 colours: {held_frames} frames in the 3 s hold \
             ({:.1}/s, {frame} bytes each on average); after the release {after_frames} frames, \
             {after_bytes} bytes, the last frame-sized read {} ms after the last key",
            held_frames as f64 / 3.0,
            settled.as_millis()
        );
        println!("header: {}", crate::serve_support::row_text(c.screen.screen(), 0));
        // What may still come after the last key byte: the frame on its way, the frames drawn
        // while the server still believes the key held (terminals send no key-up: the hold ends
        // 3 repeat intervals, 135 ms with the default 45 ms interval, after the last repeat; at
        // most 5 frames at 30 fps), and the one that shows the view at rest. Before frames
        // were paced by the link, seconds of queued frames came: 500 kB at this rate.
        assert!(held_frames > 0, "frames arrived while the key was held");
        assert!(
            after_bytes <= 7 * frame.max(2000),
            "{after_bytes} bytes ({after_frames} frames) arrived after the release, frames of \
             {frame} bytes"
        );
        srv.shutdown().await;
    });
}

/// How many frames end in `data`.
fn frames_in(data: &[u8]) -> usize {
    data.windows(FRAME_END.len())
        .filter(|w| *w == FRAME_END)
        .count()
}

/// In the namespace: a page on 3 Mbit/s joins at truecolor and turns for 10 s, acking each
/// frame as it reads it; at the end of the turn the level is truecolor again and frames go
/// compressed. (Raw, turning truecolor frames at 80×24 are about 33 kB: 11 a second on this
/// link, which would drop the level; compressed, about 9.5 kB.)
fn page_inside() {
    shape("3mbit");
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    rt.block_on(async {
        let (srv, _dir) = server(|c| {
            c.web = Some(halfcast::serve::web::WebOptions::new(
                "127.0.0.1:0".parse().expect("addr"),
            ));
        })
        .await;
        let addr = srv.web_addr().expect("the web listener runs");
        let mut page = open(addr, "name=page&cols=80&rows=24", None)
            .await
            .expect("upgraded");
        assert!(page.until(|s| header_has(s, "you are page")).await);
        page.drain_for(Duration::from_secs(1)).await;
        page.key("d", true).await;
        let started = Instant::now();
        // (when, bytes on the wire, bytes inflated) of each frame in the turn's last 4 s.
        let mut late: Vec<(Instant, u64, usize)> = Vec::new();
        while started.elapsed() < Duration::from_secs(10) {
            let wire = page.wire;
            match page.frame(Duration::from_millis(200)).await {
                Ok(Some(f)) if started.elapsed() >= Duration::from_secs(6) => {
                    late.push((Instant::now(), page.wire - wire, f.len()));
                }
                Ok(_) => {}
                Err(closed) => panic!("the page was closed: {closed:?}"),
            }
        }
        page.key("d", false).await;
        let status = row_text(page.screen.screen(), 23);
        let view: Vec<_> = late.iter().filter(|f| f.2 > 1_500).collect();
        let wire: u64 = view.iter().map(|f| f.1).sum();
        let inflated: usize = view.iter().map(|f| f.2).sum();
        println!(
            "page link: 3mbit, 80x24: {} view frames in the turn's last 4 s ({:.1}/s), {} bytes \
             each on the wire, {} inflated; status: {status}",
            view.len(),
            view.len() as f64 / 4.0,
            wire / view.len().max(1) as u64,
            inflated / view.len().max(1)
        );
        assert!(
            status.contains("truecolor"),
            "the level at the end: {status}"
        );
        assert!(!view.is_empty(), "the view turned");
        assert!(
            wire * 2 < inflated as u64,
            "frames went compressed: {wire} bytes for {inflated}"
        );
        srv.shutdown().await;
    });
}
