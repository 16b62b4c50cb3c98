//! The last inputs that could hang or flood (issue 22), driven as a hostile user would:
//! a FIFO or device wherever a file is read, a tiny replay claiming a million frames, a client
//! refused at accept (what plain OpenSSH shows of the reason), and password retries on one
//! connection.
//!
//! A FIFO here never gets a writer: before the fix, `open()` blocked on it for ever, so each
//! run is bounded by [`HANG`] and killed past it.

use crate::common;
use crate::serve_support;

use std::net::Ipv4Addr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::root;

/// Past this a run counts as hung (the refusals themselves take milliseconds; the margin is
/// for a loaded machine).
const HANG: Duration = Duration::from_secs(5);

/// Runs the binary with `args` from the project root (its output read as it comes); kills it
/// and fails at [`HANG`].
fn run_bounded(args: &[&str]) -> (Output, Duration) {
    use std::io::Read;
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(args)
        .current_dir(root())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run halfcast");
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut v = Vec::new();
            let _ = r.read_to_end(&mut v);
            v
        })
    };
    let out = drain(Box::new(child.stdout.take().unwrap()));
    let err = drain(Box::new(child.stderr.take().unwrap()));
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if start.elapsed() > HANG {
            let _ = child.kill();
            let _ = child.wait();
            panic!("halfcast {args:?} still running after {HANG:?}: it blocked");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let took = start.elapsed();
    let output = Output {
        status,
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
    };
    (output, took)
}

/// Asserts exit 2 with `needle` in the error and nothing on stdout; returns stderr.
fn refused_with(args: &[&str], needle: &str) -> String {
    let (out, took) = run_bounded(args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    println!("{args:?}: exit {:?} after {took:?}", out.status.code());
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(stderr.contains(needle), "{args:?}: {stderr}");
    assert!(out.stdout.is_empty(), "{args:?} wrote output");
    stderr
}

/// A FIFO at `dir/name`, or `None` (after a notice) where `mkfifo` is missing.
fn fifo(dir: &Path, name: &str) -> Option<PathBuf> {
    let path = dir.join(name);
    let made = Command::new("mkfifo").arg(&path).status();
    if made.is_ok_and(|s| s.success()) {
        Some(path)
    } else {
        println!("SKIPPED: mkfifo is not available");
        None
    }
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

const NOT_REGULAR: &str = "not a regular file (a FIFO, device or socket)";

/// A replay header naming `map` (JSON-quoted), then `end`.
fn replay_naming(map: &str, end: usize) -> String {
    format!(
        "{{\"halfcast_replay\":1,\"map\":{map},\"start\":{{\"pos\":[1.5,1.5],\"angle\":0.0,\"fov\":66.0}},\"size\":[20,10],\"fps\":30,\"seed\":0}}\n{{\"end\":{end}}}\n"
    )
}

#[test]
fn a_fifo_as_the_map_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let Some(f) = fifo(dir.path(), "map.cub") else {
        return;
    };
    let err = refused_with(
        &["render", s(&f), "--size", "40x12", "--format", "txt"],
        NOT_REGULAR,
    );
    assert!(err.contains(s(&f)), "names the file: {err}");
}

#[test]
fn a_fifo_named_by_a_replay_as_its_map_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let Some(f) = fifo(dir.path(), "map.cub") else {
        return;
    };
    let hcr = dir.path().join("r.hcr");
    std::fs::write(&hcr, replay_naming(&format!("\"{}\"", s(&f)), 3)).unwrap();
    let cast = dir.path().join("out.cast");
    refused_with(
        &["replay", s(&hcr), "--format", "cast", "--out", s(&cast)],
        NOT_REGULAR,
    );
    assert!(!cast.exists());
    // The replay file itself as a FIFO, too.
    let Some(g) = fifo(dir.path(), "r2.hcr") else {
        return;
    };
    refused_with(&["replay", s(&g), "--format", "cast"], NOT_REGULAR);
}

#[test]
fn a_fifo_as_either_diff_input_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let Some(f) = fifo(dir.path(), "frame.ansi") else {
        return;
    };
    let good = dir.path().join("good.txt");
    std::fs::write(&good, "ab\ncd\n").unwrap();
    refused_with(&["diff", s(&f), s(&good)], NOT_REGULAR);
    refused_with(&["diff", s(&good), s(&f)], NOT_REGULAR);
}

#[test]
fn devices_are_refused_like_fifos() {
    if !Path::new("/dev/zero").exists() {
        println!("SKIPPED: no /dev/zero on this system");
        return;
    }
    refused_with(&["render", "/dev/zero", "--format", "txt"], NOT_REGULAR);
    refused_with(&["diff", "/dev/zero", "/dev/zero"], NOT_REGULAR);
    refused_with(&["replay", "/dev/zero", "--format", "cast"], NOT_REGULAR);
}

#[test]
fn the_config_password_file_and_bench_frames_refuse_fifos_too() {
    let dir = tempfile::tempdir().unwrap();
    let Some(f) = fifo(dir.path(), "config.toml") else {
        return;
    };
    // The config is read before the terminal is touched.
    refused_with(&["play", "--config", s(&f)], NOT_REGULAR);
    refused_with(
        &[
            "serve",
            "--listen",
            "127.0.0.1:0",
            "--password-file",
            s(&f),
            "--host-key",
            s(&dir.path().join("hk")),
        ],
        NOT_REGULAR,
    );
    let frames = dir.path().join("frames");
    std::fs::create_dir(&frames).unwrap();
    let Some(_) = fifo(&frames, "frame-000.png") else {
        return;
    };
    refused_with(&["bench", "--frames", s(&frames)], NOT_REGULAR);
}

#[test]
fn bench_frames_share_one_pixel_budget() {
    // Five 4000×4000 PNGs (a few KB each, all one colour): within the per-frame limit, but
    // 80 million pixels together, over the 2^26 budget.
    let dir = tempfile::tempdir().unwrap();
    let mut png = Vec::new();
    image::GrayImage::new(4000, 4000)
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    for i in 0..5 {
        std::fs::write(dir.path().join(format!("f{i}.png")), &png).unwrap();
    }
    refused_with(
        &["bench", "--frames", s(dir.path())],
        "5 frames of 4000x4000 pixels hold more than 67108864 pixels (the limit)",
    );
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

const MILLION: &str = "tests/fixtures/million_frames.hcr";

#[test]
fn a_replay_claiming_a_million_frames_is_refused_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let cast = dir.path().join("run.cast");
    let err = refused_with(
        &["replay", MILLION, "--format", "cast", "--out", s(&cast)],
        "more than --max-frames 108000 (the default: one hour at its 30 fps)",
    );
    assert_eq!(
        err,
        format!(
            "error: {MILLION}: the run is 1000000 frames (33333 s at 30 fps), more than \
             --max-frames 108000 (the default: one hour at its 30 fps); nothing was written. \
             Pass --max-frames 1000000 if the recording is really that long, or --until-frame \
             to write its start\n"
        )
    );
    assert!(names(dir.path()).is_empty(), "{:?}", names(dir.path()));
    // To standard output: nothing at all.
    refused_with(
        &["replay", MILLION, "--format", "cast"],
        "--max-frames 108000",
    );
    // Frame files past the limit likewise.
    refused_with(
        &[
            "replay",
            MILLION,
            "--format",
            "txt",
            "--frames",
            "200000",
            "--out",
            s(dir.path()),
        ],
        "the run is 200001 frames",
    );
    assert!(names(dir.path()).is_empty());
    // The start of it is fine.
    let (out, _) = run_bounded(&[
        "replay",
        MILLION,
        "--until-frame",
        "30",
        "--format",
        "cast",
        "--out",
        s(&cast),
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        std::fs::read_to_string(&cast).unwrap().lines().count(),
        2 + 31
    );
}

#[test]
fn the_output_limit_leaves_no_file_that_looks_complete() {
    let dir = tempfile::tempdir().unwrap();
    let cast = dir.path().join("run.cast");
    std::fs::write(&cast, "an older cast\n").unwrap();
    let err = refused_with(
        &[
            "replay",
            MILLION,
            "--max-frames",
            "1000000",
            "--max-output-bytes",
            "200K",
            "--format",
            "cast",
            "--out",
            s(&cast),
        ],
        "the cast would pass --max-output-bytes 204800",
    );
    assert!(err.contains("(not written)"), "{err}");
    // The old file is untouched and no part file is left behind.
    assert_eq!(std::fs::read_to_string(&cast).unwrap(), "an older cast\n");
    assert_eq!(names(dir.path()), ["run.cast"]);
}

#[test]
fn on_standard_output_the_cast_ends_with_whole_lines_and_says_it_is_cut() {
    let (out, _) = run_bounded(&[
        "replay",
        MILLION,
        "--max-frames",
        "1000000",
        "--max-output-bytes",
        "100K",
        "--format",
        "cast",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("standard output (incomplete): stopped at frame"),
        "{stderr}"
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.ends_with('\n'));
    let lines: Vec<&str> = text.lines().collect();
    for l in &lines {
        serde_json::from_str::<serde_json::Value>(l).expect("every line is whole JSON");
    }
    let last = lines.last().unwrap();
    assert!(last.contains("this cast is incomplete"), "{last}");
    // Within the cap, apart from that last notice.
    assert!(text.len() - last.len() - 1 <= 100 << 10);
}

/// Runs plain `ssh` (no -v: what a user sees) against `port`; returns its stderr.
fn plain_ssh(port: u16) -> String {
    let out = Command::new("ssh")
        .args(["-F", "/dev/null", "-p", &port.to_string()])
        .args([
            "-o",
            "StrictHostKeyChecking=no",
            "-o",
            "UserKnownHostsFile=/dev/null",
        ])
        .args(["-o", "BatchMode=yes", "-o", "ConnectTimeout=5"])
        .args(["ann@127.0.0.1", "true"])
        .stdin(Stdio::null())
        .output()
        .expect("run ssh");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn a_plain_openssh_user_refused_by_address_sees_the_reason() {
    if !serve_support::openssh::ssh_available() {
        println!("SKIPPED: OpenSSH `ssh` is not installed (apt-get install openssh-client)");
        return;
    }
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    let (srv, _dir) = rt.block_on(serve_support::server(|c| {
        c.max_per_ip = 1;
    }));
    let addr = srv.local_addr();
    // One silent connection from 127.0.0.1 holds its only place.
    let _held = rt
        .block_on(serve_support::tcp_from(Ipv4Addr::LOCALHOST, addr))
        .expect("tcp");
    assert!(rt.block_on(serve_support::live_becomes(&srv, (1, 0))));
    let err = plain_ssh(addr.port());
    assert!(
        err.contains(&format!(
            "Received disconnect from 127.0.0.1 port {}:12: halfcast: too many connections from your address",
            addr.port()
        )),
        "{err}"
    );
    assert!(!err.contains("kex_exchange_identification"), "{err}");
    rt.block_on(srv.shutdown());
}

/// paramiko asks for the `ssh-userauth` service again before every password attempt. russh from
/// crates.io (0.65.x) leaves the repeated request unanswered, so the second attempt on one
/// connection waits until the login grace closes it (docs/serving.md, "Clients and their quirks").
/// This script makes a wrong then a right attempt on one connection, then a right attempt on a new
/// connection, and prints what each got.
const PARAMIKO_RETRY: &str = r#"
import sys, time, paramiko
port = int(sys.argv[1])
t = paramiko.Transport(("127.0.0.1", port))
t.start_client(timeout=10)
t.auth_timeout = 30
for n, pw in ((1, "wrong"), (2, "sesame")):
    start = time.time()
    try:
        t.auth_password("ann", pw, fallback=False)
        print(f"attempt {n}: accepted after {time.time() - start:.2f} s", flush=True)
    except paramiko.AuthenticationException as e:
        print(f"attempt {n}: refused after {time.time() - start:.2f} s ({e})", flush=True)
    except Exception as e:
        print(f"attempt {n}: {type(e).__name__} after {time.time() - start:.2f} s ({e})", flush=True)
print(f"first connection active: {t.is_active()}", flush=True)
t.close()
t = paramiko.Transport(("127.0.0.1", port))
t.start_client(timeout=10)
start = time.time()
try:
    t.auth_password("ann", "sesame", fallback=False)
    print(f"new connection: accepted after {time.time() - start:.2f} s", flush=True)
except Exception as e:
    print(f"new connection: {type(e).__name__} ({e})", flush=True)
t.close()
"#;

/// Whether `python3` with paramiko is installed (a notice is printed when not).
fn paramiko_available() -> bool {
    let ok = Command::new("python3")
        .args(["-c", "import paramiko"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !ok {
        println!("SKIPPED: python3 with paramiko is not installed (pip install paramiko)");
    }
    ok
}

/// Seconds from the text after `attempt 2: ` ("… after 3.02 s …").
fn seconds_after(text: &str, label: &str) -> Option<f64> {
    let line = text.lines().find(|l| l.starts_with(label))?;
    let rest = &line[line.find(" after ")? + " after ".len()..];
    rest.split(' ').next()?.parse().ok()
}

#[test]
fn paramiko_second_password_attempt_on_one_connection_ends_at_the_login_grace() {
    if !paramiko_available() {
        return;
    }
    let grace = Duration::from_secs(3);
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    let (srv, _dir) = rt.block_on(serve_support::server(|c| {
        c.auth = halfcast::serve::auth::AuthMode::Password("sesame".into());
        c.login_grace = grace;
    }));
    let port = srv.local_addr().port().to_string();
    let out = Command::new("python3")
        .args(["-c", PARAMIKO_RETRY, &port])
        .output()
        .expect("run python3");
    let text = String::from_utf8_lossy(&out.stdout);
    println!("{text}{}", String::from_utf8_lossy(&out.stderr));
    assert!(text.contains("attempt 1: refused"), "{text}");
    // The second attempt is never answered: the connection is closed by the grace, not accepted,
    // and not before the grace (it would then be some other failure).
    assert!(!text.contains("attempt 2: accepted"), "{text}");
    let waited = seconds_after(&text, "attempt 2: ").expect("attempt 2 line");
    assert!(
        waited <= grace.as_secs_f64() + 2.0,
        "the second attempt waited {waited} s, past the {grace:?} login grace: {text}"
    );
    // The grace counts from TCP accept; the key exchange and the first attempt came before.
    assert!(
        waited >= grace.as_secs_f64() - 1.5,
        "the second attempt ended after {waited} s, well before the {grace:?} grace: {text}"
    );
    assert!(text.contains("first connection active: False"), "{text}");
    // Nothing else is broken: a new connection with the right password is let in at once.
    assert!(text.contains("new connection: accepted"), "{text}");
    rt.block_on(srv.shutdown());
}
