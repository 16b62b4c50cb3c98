//! The fuzz targets of `halfcast::fuzzing` (the same ones `fuzz/` runs under cargo-fuzz on
//! nightly), driven on stable Rust by a seeded mutation loop so every `cargo test` runs them.
//!
//! Seeds come from `tests/fixtures`, `maps/`, `tests/images`, `tests/snapshots` and the shared
//! cub3D corpus (`../shared/corpus`, or `HALFCAST_CORPUS`; skipped with a notice when absent),
//! plus a few built here. Each iteration applies 1–4 mutations (bit flips, byte sets, inserts of
//! interesting bytes and numbers, deletions, duplications, splices with another input); mutants
//! that a target accepts join the pool, so later mutants start from deeper inputs.
//! `HALFCAST_FUZZ_ITERS` sets the iterations per target (default 3000), `HALFCAST_FUZZ_SEED`
//! the random seed. A panic, or an input still running after [`HANG`], is a finding: the input
//! is written to `target/fuzz-findings/` and the test fails naming it.

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use halfcast::fuzzing;

/// An input still running after this long is reported as a hang (this detects endless work;
/// it is not a speed check — real inputs take milliseconds).
const HANG: Duration = Duration::from_secs(60);

/// Peak memory of the whole test process allowed (all four targets run at once): an input that
/// made a loader allocate without bound would pass it.
const MAX_RSS_KIB: u64 = 2 << 20;

/// Most inputs kept to mutate from (the seeds plus accepted mutants).
const MAX_POOL: usize = 4096;

/// Inputs are cut to this many bytes after mutation (the loaders' own caps are far larger; the
/// point is many varied inputs, not big ones).
const MAX_INPUT: usize = 64 << 10;

/// A small deterministic generator (xorshift64*), so a failing run can be repeated.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const BYTES: &[u8] = b"\x00\xff\x1b[;,.\n\r\t -0123456789xHCBGmu{}\":DNSEW12a\x7f\xc3";

const NUMBERS: &[&str] = &[
    "0",
    "1",
    "-1",
    "255",
    "256",
    "2000",
    "2001",
    "4000",
    "4096",
    "4097",
    "65535",
    "65536",
    "1000000",
    "4294967296",
    "18446744073709551615",
    "99999999999999999999999",
    "1e308",
    "NaN",
    "inf",
    "0.0000001",
    "17216961135462248175",
];

fn mutate(rng: &mut Rng, seeds: &[Vec<u8>], base: &[u8]) -> Vec<u8> {
    let mut d = base.to_vec();
    for _ in 0..=rng.below(4) {
        let at = rng.below(d.len() + 1);
        match rng.below(8) {
            0 if !d.is_empty() => {
                let i = at.min(d.len() - 1);
                d[i] ^= 1 << rng.below(8);
            }
            1 if !d.is_empty() => {
                let i = at.min(d.len() - 1);
                d[i] = BYTES[rng.below(BYTES.len())];
            }
            2 => d.insert(at, BYTES[rng.below(BYTES.len())]),
            3 => {
                let n = NUMBERS[rng.below(NUMBERS.len())];
                d.splice(at..at, n.bytes());
            }
            4 if !d.is_empty() => {
                let end = (at + 1 + rng.below(32)).min(d.len());
                d.drain(at.min(d.len() - 1)..end);
            }
            5 if !d.is_empty() => {
                let start = rng.below(d.len());
                let end = (start + 1 + rng.below(256)).min(d.len());
                let piece = d[start..end].to_vec();
                let copies = 1 + rng.below(8);
                for _ in 0..copies {
                    d.splice(at..at, piece.iter().copied());
                }
            }
            6 => {
                let other = &seeds[rng.below(seeds.len())];
                if !other.is_empty() {
                    let start = rng.below(other.len());
                    let end = (start + 1 + rng.below(512)).min(other.len());
                    d.splice(at..at, other[start..end].iter().copied());
                }
            }
            _ => d.truncate(at),
        }
    }
    d.truncate(MAX_INPUT);
    d
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every file under `dir` (recursively) whose name ends with one of `exts`.
fn files(dir: &Path, exts: &[&str], out: &mut Vec<Vec<u8>>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for p in paths {
        if p.is_dir() {
            files(&p, exts, out);
        } else if let Some(name) = p.file_name().and_then(|n| n.to_str()) {
            if exts.iter().any(|e| name.ends_with(e)) {
                if let Ok(b) = std::fs::read(&p) {
                    out.push(b);
                }
            }
        }
    }
}

fn corpus_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("HALFCAST_CORPUS")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("../shared/corpus"));
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!(
            "skip: no shared corpus at {} (set HALFCAST_CORPUS); using the repository's seeds only",
            dir.display()
        );
        None
    }
}

fn map_seeds() -> Vec<Vec<u8>> {
    let mut s = Vec::new();
    files(&root().join("tests/fixtures"), &[".cub"], &mut s);
    files(&root().join("maps"), &[".cub"], &mut s);
    if let Some(dir) = corpus_dir() {
        files(&dir, &[".cub"], &mut s);
    }
    s
}

fn replay_seeds() -> Vec<Vec<u8>> {
    let mut s = Vec::new();
    files(&root().join("tests/fixtures"), &[".hcr"], &mut s);
    s.push(
        concat!(
            r#"{"halfcast_replay":1,"map":"maps/default.cub","start":{"pos":[2.5,3.5],"angle":0.0,"fov":66.0},"size":[80,24],"fps":30,"seed":7}"#,
            "\n",
            r#"{"frame":0,"held":["forward","crouch"]}"#,
            "\n",
            r#"{"frame":3,"command":"move_column","by":-3}"#,
            "\n",
            r#"{"frame":4,"ui":"toggle_minimap"}"#,
            "\n",
            r#"{"frame":5,"size":[100,30]}"#,
            "\n",
            r#"{"end":9}"#,
            "\n"
        )
        .as_bytes()
        .to_vec(),
    );
    s
}

fn frame_seeds() -> Vec<Vec<u8>> {
    let mut s = Vec::new();
    files(&root().join("tests/images"), &[".png"], &mut s);
    let mut snaps = Vec::new();
    files(&root().join("tests/snapshots"), &[".snap"], &mut snaps);
    for snap in snaps {
        // An insta snapshot: a YAML header between `---` lines, then the frame text.
        let text = String::from_utf8_lossy(&snap);
        if let Some(body) = text.splitn(3, "---\n").nth(2) {
            s.push(body.as_bytes().to_vec());
        }
    }
    s.push(b"\x1b[38;2;1;2;3m\x1b[48;2;4;5;6m\xe2\x96\x80\xe2\x96\x80\x1b[0m\n\x1b[38;5;196m\xe2\x96\x84 \x1b[0m\n".to_vec());
    s.push(b"\x1b[3;5Hab\x1b[1;1Hc\x1b[2C\x1b[4G\x1b[1Bz".to_vec());
    s.push(
        "halfcast-cells v1 2x1\n▀a0b0c0/101010  ~~~~~~/~~~~~~\n"
            .as_bytes()
            .to_vec(),
    );
    s.push(
        "halfcast-cells v2 3x1\n\"e\u{301}?x\"\nstyles:\ny0 x0-1 fg=green ul=idx3 bold\nglyphs:\ny0 x1 U+0301\n"
            .as_bytes()
            .to_vec(),
    );
    s.push(b"plain\ntext frame\n".to_vec());
    s.push(
        "Buffer {\n    area: Rect { x: 0, y: 0, width: 3, height: 1 },\n    content: [\n        \"\u{754c}e\",\n    ],\n    styles: [\n        x: 0, y: 0, fg: Green, bg: Rgb(1, 2, 3), underline: Indexed(9), modifier: BOLD | REVERSED,\n    ]\n}"
            .as_bytes()
            .to_vec(),
    );
    s
}

fn ssh_seeds() -> Vec<Vec<u8>> {
    [
        &b"wasd\x1b[A\x1b[B\x1b[C\x1b[D"[..],
        b"\x1b[1;5A\x1b[3~\x1b[5~\x1b[15~\x1bOP\x1b[Z\r\t\x7f\x03",
        b"\x1b[119;1:1u\x1b[119;1:3u\x1b[?15u\x1b[97u",
        b"\x1b[200~paste\x1b[201~\x1bx\x1b",
        "é日\u{1F600}".as_bytes(),
    ]
    .iter()
    .map(|b| b.to_vec())
    .collect()
}

fn iterations() -> usize {
    std::env::var("HALFCAST_FUZZ_ITERS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(3000)
}

/// The process's peak resident memory in KiB (Linux; 0 elsewhere).
fn peak_rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse().ok())
        })
        .unwrap_or(0)
}

fn save_finding(name: &str, data: &[u8]) -> PathBuf {
    let dir = root().join("target/fuzz-findings");
    let _ = std::fs::create_dir_all(&dir);
    let mut h = flate2::Crc::new();
    h.update(data);
    let path = dir.join(format!("{name}-{:08x}.bin", h.sum()));
    let _ = std::fs::write(&path, data);
    path
}

/// Runs `target` on the seeds and `iterations()` mutants on a worker thread, so a panic is
/// caught and a hang noticed; fails listing every finding.
fn run(name: &str, target: fn(&[u8]) -> bool, seeds: Vec<Vec<u8>>) {
    assert!(!seeds.is_empty(), "{name}: no seeds");
    let seed = std::env::var("HALFCAST_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0x9E37_79B9_7F4A_7C15u64);
    let mut rng = Rng(seed ^ name.len() as u64 ^ 1);
    let (to_worker, inputs) = mpsc::channel::<Vec<u8>>();
    let (to_main, results) = mpsc::channel::<Result<bool, String>>();
    std::thread::spawn(move || {
        for data in inputs {
            let outcome = std::panic::catch_unwind(|| target(&data)).map_err(|p| {
                p.downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| (*s).to_owned()))
                    .unwrap_or_default()
            });
            if to_main.send(outcome).is_err() {
                break;
            }
        }
    });
    let total = iterations();
    let mut findings = Vec::new();
    let mut slowest = Duration::ZERO;
    let mut valid = 0;
    let started = Instant::now();
    let first = seeds.len();
    let mut pool = seeds;
    for i in 0..first + total {
        let data = if i < first {
            pool[i].clone()
        } else {
            let base = rng.below(pool.len());
            mutate(&mut rng, &pool, &pool[base])
        };
        let t0 = Instant::now();
        to_worker.send(data.clone()).expect("worker alive");
        match results.recv_timeout(HANG) {
            Ok(Ok(accepted)) => {
                if accepted && i >= first {
                    valid += 1;
                    // Accepted mutants join the pool: later ones start from deeper inputs.
                    if pool.len() < MAX_POOL {
                        pool.push(data);
                    }
                }
            }
            Ok(Err(msg)) => {
                findings.push(format!(
                    "panic: {msg} ({})",
                    save_finding(name, &data).display()
                ));
            }
            Err(_) => {
                findings.push(format!(
                    "hang over {HANG:?} ({})",
                    save_finding(name, &data).display()
                ));
                break;
            }
        }
        slowest = slowest.max(t0.elapsed());
    }
    eprintln!(
        "fuzz {name}: {} seeds + {total} mutants ({valid} accepted) in {:.1?}, slowest input {slowest:.1?}, peak RSS {} MiB, {} findings",
        first,
        started.elapsed(),
        peak_rss_kib() / 1024,
        findings.len()
    );
    assert!(findings.is_empty(), "{name}: {findings:#?}");
    let peak = peak_rss_kib();
    assert!(peak < MAX_RSS_KIB, "{name}: peak memory {peak} KiB");
}

#[test]
fn fuzz_map_loader() {
    run("map_loader", fuzzing::map_loader, map_seeds());
}

#[test]
fn fuzz_replay_reader() {
    run("replay_reader", fuzzing::replay_reader, replay_seeds());
}

#[test]
fn fuzz_frame_parser() {
    run("frame_parser", fuzzing::frame_parser, frame_seeds());
}

#[test]
fn fuzz_ssh_input() {
    run("ssh_input", fuzzing::ssh_input, ssh_seeds());
}
