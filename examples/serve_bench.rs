//! Load test for `halfcast serve`, loopback only and bounded: N russh clients for T seconds,
//! each pressing random movement keys, against an in-process server whose runtime has its own
//! named threads, so its CPU time can be read apart from the clients'.
//!
//! `cargo run --release --example serve_bench -- --clients 32 --secs 10 --term xterm-direct \
//!     --compression none --cols 80 --rows 24 --server-threads 1 [--map PATH] \
//!     [--metrics on] [--db on] [--round-secs N] [--idle N]`
//!
//! `--transport web` makes the clients browser pages instead: each a WebSocket that acks every
//! frame on arrival and taps the same keys (press and release together), with the server's
//! `--web-compress auto|always|never` set by `--web-compress` (CPU per browser player against an
//! SSH player: `--transport ssh --term xterm-direct` is the same truecolor level).
//!
//! `--motion turn` has every client turn all the time instead (an SSH client sends `d` every
//! 30 ms, as a terminal's key repeat does; a page holds `d` down): the same views over both
//! transports, for comparing them.
//!
//! `--glyphs quadrant|sextant|octant` has every client ask for that view setting (the
//! `HALFCAST_GLYPHS` variable `ssh -o SetEnv=…` sends). `--map` serves that map file (e.g. one
//! with creatures, to see what game logic costs) instead of the embedded default. `--metrics on` installs the Prometheus recorder and its
//! listener (on a free loopback port, scraped once a second as Prometheus would, more often),
//! `--db on` keeps the SQLite leaderboard in a temporary file; `--round-secs N` ends each
//! round after N seconds so rounds (and their leaderboard writes and results screens) happen
//! during the run. The leaderboard thread's CPU counts as the server's. `--idle N` makes the
//! first N clients press no key at all (what an idle player costs the server).
//!
//! Prints one JSON object: server CPU, frames/s and bytes/s per client (payload and on the wire),
//! frames the server sent and frame ticks it skipped (slow readers), connections refused.

/// What `--help` (and a bad option) prints.
const USAGE: &str = "usage: serve_bench [--clients N] [--secs S] [--term TERM] [--compression none|zlib@openssh.com]
       [--cols C] [--rows R] [--fps F] [--server-threads T] [--map PATH]
       [--metrics on] [--db on] [--round-secs N] [--idle N] [--glyphs half|quadrant|sextant|octant]
       [--transport ssh|web] [--web-compress auto|always|never] [--motion taps|turn]
Connects N russh clients (or browser pages) over loopback to an in-process server for S seconds and prints one
JSON object: server CPU, frames and bytes per client, clients per core at the target fps.";

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use futures_util::{SinkExt, StreamExt};
use halfcast::serve::web::{Compress, WebOptions};
use halfcast::serve::{start, ServeConfig};
use halfcast::{Glyphs, World};
use russh::{compression, ChannelMsg};
use tokio_tungstenite::tungstenite::Message;

/// The allocator the `halfcast` binary serves with (src/main.rs), so the figures are the server's.
#[global_allocator]
static ALLOC: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The same client the integration tests use (one copy of the SSH client code).
#[path = "../tests/support/serve_support/mod.rs"]
#[allow(dead_code)] // the load test drives the server and counted connections, not the test client
mod serve_support;

/// Movement keys a bot presses (the local TUI's key map: walk, turn, strafe).
const MOVES: &[u8] = b"wasdzx";

struct Opts {
    clients: usize,
    secs: u64,
    cols: u32,
    rows: u32,
    term: String,
    compression: String,
    fps: u32,
    server_threads: usize,
    map: Option<String>,
    metrics: bool,
    db: bool,
    round_secs: Option<u64>,
    idle: usize,
    glyphs: Glyphs,
    /// Browser pages instead of SSH clients.
    web: bool,
    web_compress: Compress,
    /// Every client turns all the time (else random movement keys every 100 ms).
    turn: bool,
}

fn opts() -> Opts {
    let mut o = Opts {
        clients: 32,
        secs: 10,
        cols: 80,
        rows: 24,
        term: "xterm-direct".into(),
        compression: "none".into(),
        fps: 30,
        server_threads: 1,
        map: None,
        metrics: false,
        db: false,
        round_secs: None,
        idle: 0,
        glyphs: Glyphs::Half,
        web: false,
        web_compress: Compress::Auto,
        turn: false,
    };
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = |why: &str| -> ! {
        eprintln!("serve_bench: {why}\n\n{USAGE}");
        std::process::exit(2)
    };
    if args.iter().any(|a| a == "--help" || a == "-h") {
        println!("{USAGE}");
        std::process::exit(0);
    }
    for pair in args.chunks(2) {
        let Some(v) = pair.get(1).cloned() else {
            usage(&format!("{} needs a value", pair[0]))
        };
        let num = |v: &str| {
            v.parse::<u64>()
                .unwrap_or_else(|_| usage(&format!("{} takes a number, not {v:?}", pair[0])))
        };
        match pair[0].as_str() {
            // Bounded on purpose: this is a loopback load test, not a flood tool.
            "--clients" => o.clients = num(&v).clamp(1, 256) as usize,
            "--secs" => o.secs = num(&v).clamp(1, 120),
            "--cols" => o.cols = num(&v).clamp(1, 500) as u32,
            "--rows" => o.rows = num(&v).clamp(1, 200) as u32,
            "--term" => o.term = v,
            "--compression" => o.compression = v,
            "--fps" => o.fps = num(&v) as u32,
            "--server-threads" => o.server_threads = num(&v).clamp(1, 8) as usize,
            "--map" => o.map = Some(v),
            "--metrics" => o.metrics = v == "on",
            "--db" => o.db = v == "on",
            "--round-secs" => o.round_secs = Some(num(&v).clamp(1, 3600)),
            "--idle" => o.idle = num(&v) as usize,
            "--glyphs" => match v.parse::<Glyphs>() {
                Ok(g) => o.glyphs = g,
                Err(why) => usage(&format!("--glyphs: {why}")),
            },
            "--transport" => match v.as_str() {
                "ssh" => o.web = false,
                "web" => o.web = true,
                _ => usage("--transport takes ssh or web"),
            },
            "--web-compress" => match v.as_str() {
                "auto" => o.web_compress = Compress::Auto,
                "always" => o.web_compress = Compress::Always,
                "never" => o.web_compress = Compress::Never,
                _ => usage("--web-compress takes auto, always or never"),
            },
            "--motion" => match v.as_str() {
                "taps" => o.turn = false,
                "turn" => o.turn = true,
                _ => usage("--motion takes taps or turn"),
            },
            other => usage(&format!("unknown option {other}")),
        }
    }
    o
}

/// CPU seconds used so far by this process's threads whose name starts with `prefix` (Linux).
fn thread_cpu(prefix: &str) -> f64 {
    let Ok(dir) = std::fs::read_dir("/proc/self/task") else {
        return f64::NAN;
    };
    let tick = 100.0; // USER_HZ on Linux
    let mut total = 0u64;
    for t in dir.flatten() {
        let comm = std::fs::read_to_string(t.path().join("comm")).unwrap_or_default();
        if !comm.starts_with(prefix) {
            continue;
        }
        let stat = std::fs::read_to_string(t.path().join("stat")).unwrap_or_default();
        // Fields after the ")" that closes the command name: utime is the 12th, stime the 13th.
        if let Some(rest) = stat.rsplit_once(')').map(|x| x.1) {
            let f: Vec<&str> = rest.split_whitespace().collect();
            let n = |i: usize| f.get(i).and_then(|s| s.parse::<u64>().ok()).unwrap_or(0);
            total += n(11) + n(12);
        }
    }
    total as f64 / tick
}

#[derive(Default)]
struct PerClient {
    /// Frames seen by the client (synchronized-update markers; mono frames have none).
    frames: AtomicU64,
    payload: AtomicU64,
    wire: std::sync::Mutex<Option<Arc<AtomicU64>>>,
}

fn main() {
    let o = opts();
    let server_rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(o.server_threads)
        .thread_name("srv-worker")
        .enable_all()
        .build()
        .expect("server runtime");
    let dir = tempfile::tempdir().expect("tempdir");
    let mut cfg = ServeConfig::local("127.0.0.1:0".parse().expect("addr"), dir.path().join("hk"));
    cfg.quiet = true;
    cfg.max_sessions = o.clients;
    cfg.max_per_ip = o.clients;
    // Every bot logs in at once from 127.0.0.1: lift the logging-in caps for the load test.
    cfg.max_startups = o.clients.to_string().parse().expect("startups");
    cfg.max_startups_per_ip = o.clients;
    cfg.fps = o.fps;
    cfg.round_limit = o.round_secs.map(Duration::from_secs);
    cfg.db = o.db.then(|| dir.path().join("bench.sqlite"));
    let metrics_port = o.metrics.then(|| {
        std::net::TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .expect("a free port")
            .port()
    });
    cfg.metrics = metrics_port.map(|p| std::net::SocketAddr::from(([127, 0, 0, 1], p)));
    if o.web {
        let mut web = WebOptions::new("127.0.0.1:0".parse().expect("addr"));
        web.compress = o.web_compress;
        cfg.web = Some(web);
    }
    let world = match &o.map {
        Some(path) => {
            World::from_file(std::path::Path::new(path), false)
                .unwrap_or_else(|e| panic!("{path}: {e}"))
                .0
        }
        None => World::default_world(),
    };
    let creatures = world.map.creatures.len();
    let server = server_rt.block_on(start(cfg, world)).expect("server");
    let addr = server.local_addr();
    let web_addr = server.web_addr();

    let client_rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .thread_name("cli-worker")
        .enable_all()
        .build()
        .expect("client runtime");
    let alg = match o.compression.as_str() {
        "zlib" => compression::ZLIB,
        "zlib@openssh.com" => compression::ZLIB_LEGACY,
        _ => compression::NONE,
    };
    let per: Vec<Arc<PerClient>> = (0..o.clients).map(|_| Arc::default()).collect();
    let secs = o.secs;
    let (cpu, client_cpu, elapsed) = client_rt.block_on(async {
        let mut tasks = Vec::new();
        for (i, pc) in per.iter().enumerate() {
            let pc = Arc::clone(pc);
            let term = o.term.clone();
            let glyphs = o.glyphs.name();
            let (cols, rows) = (o.cols as u16, o.rows as u16);
            let idle = i < o.idle;
            let bot = Bot {
                i,
                size: (cols, rows),
                secs,
                idle,
                turn: o.turn,
                pc,
            };
            tasks.push(if let Some(web) = web_addr {
                tokio::spawn(web_bot(web, bot))
            } else {
                tokio::spawn(ssh_bot(addr, bot, term, glyphs, alg))
            });
        }
        let scraper = metrics_port.map(|port| tokio::spawn(scrape_every_second(port)));
        let cpu0 = thread_cpu("srv-worker") + thread_cpu("halfcast-leader");
        let ccpu0 = thread_cpu("cli-worker");
        let t0 = Instant::now();
        for t in tasks {
            let _ = t.await;
        }
        if let Some(s) = scraper {
            s.abort();
        }
        (
            thread_cpu("srv-worker") + thread_cpu("halfcast-leader") - cpu0,
            thread_cpu("cli-worker") - ccpu0,
            t0.elapsed().as_secs_f64(),
        )
    });
    // Sessions add their counters when they end, just after their clients leave.
    std::thread::sleep(Duration::from_secs(1));
    let stats = server.stats();
    server_rt.block_on(server.shutdown());
    let n = per.len() as f64;
    let fps: Vec<f64> = per
        .iter()
        .map(|p| p.frames.load(Ordering::Relaxed) as f64 / elapsed)
        .collect();
    let payload = per
        .iter()
        .map(|p| p.payload.load(Ordering::Relaxed) as f64)
        .sum::<f64>()
        / n
        / elapsed;
    let wire = per
        .iter()
        .map(|p| {
            let w = p.wire.lock().expect("wire");
            w.as_ref().map_or(0, |w| w.load(Ordering::Relaxed)) as f64
        })
        .sum::<f64>()
        / n
        / elapsed;
    let cpu_frac = cpu / elapsed;
    // Frames the server sent (every level); the client-side count needs the sync markers.
    let mean_fps = stats.frames_sent as f64 / n / elapsed;
    println!(
        "{{\"map\":\"{}\",\"creatures\":{},\"clients\":{},\"secs\":{:.1},\"cols\":{},\"rows\":{},\"term\":\"{}\",\"compression\":\"{}\",\
\"target_fps\":{},\"server_threads\":{},\"server_cpu_percent\":{:.1},\"client_cpu_percent\":{:.1},\"fps_per_client_mean\":{:.1},\
\"fps_per_client_min_seen\":{:.1},\"payload_bytes_per_s_per_client\":{:.0},\"wire_bytes_per_s_per_client\":{:.0},\
\"server_frames_sent\":{},\"server_frame_ticks_skipped\":{},\"refused\":{},\
\"clients_per_core_at_target_fps\":{:.1},\"metrics\":{},\"db\":{},\"round_secs\":{},\"idle_clients\":{},\"glyphs\":\"{}\",\
\"transport\":\"{}\"}}",
        o.map.as_deref().unwrap_or("(embedded)"),
        creatures,
        o.clients,
        elapsed,
        o.cols,
        o.rows,
        o.term,
        o.compression,
        o.fps,
        o.server_threads,
        cpu_frac * 100.0,
        client_cpu / elapsed * 100.0,
        mean_fps,
        fps.iter().copied().fold(f64::INFINITY, f64::min),
        payload,
        wire,
        stats.frames_sent,
        stats.frames_dropped,
        stats.refused,
        n * (mean_fps / f64::from(o.fps)) / cpu_frac.max(1e-9),
        o.metrics,
        o.db,
        o.round_secs.unwrap_or(0),
        o.idle.min(o.clients),
        o.glyphs.name(),
        match (o.web, o.web_compress) {
            (false, _) => "ssh",
            (true, Compress::Auto) => "web (compress auto)",
            (true, Compress::Always) => "web (compress always)",
            (true, Compress::Never) => "web (compress never)",
        },
    );
}

/// One load-test client: its number, its window, how long it plays, whether it presses keys,
/// and where it counts what it got.
struct Bot {
    i: usize,
    size: (u16, u16),
    secs: u64,
    idle: bool,
    /// Turns all the time instead of random keys.
    turn: bool,
    pc: Arc<PerClient>,
}

impl Bot {
    /// The next movement key this bot presses (a fixed sequence per bot).
    fn key(&self, lcg: &mut u32) -> u8 {
        if self.turn {
            return b'd';
        }
        *lcg = lcg.wrapping_mul(1_103_515_245).wrapping_add(12345);
        MOVES[(*lcg >> 16) as usize % MOVES.len()]
    }

    fn seed(&self) -> u32 {
        0x9e37_79b9u32.wrapping_mul(self.i as u32 + 1)
    }
}

/// An SSH player pressing a random movement key every 100 ms.
async fn ssh_bot(
    addr: std::net::SocketAddr,
    bot: Bot,
    term: String,
    glyphs: &'static str,
    alg: compression::Name,
) {
    let env = [("HALFCAST_GLYPHS", glyphs)];
    let name = format!("bot{}", bot.i);
    let (h, mut ch, wire) =
        serve_support::open_counting(addr, &name, bot.size, &term, &env, alg).await;
    let pc = &bot.pc;
    *pc.wire.lock().expect("wire") = Some(wire);
    let end = tokio::time::Instant::now() + Duration::from_secs(bot.secs);
    let mut next_key = tokio::time::Instant::now();
    let mut lcg = bot.seed();
    let mut tail: Vec<u8> = Vec::new();
    loop {
        let wake = next_key.min(end);
        tokio::select! {
            msg = ch.wait() => match msg {
                Some(ChannelMsg::Data { data }) => {
                    pc.payload.fetch_add(data.len() as u64, Ordering::Relaxed);
                    tail.extend_from_slice(&data);
                    let n = tail.windows(8).filter(|w| *w == b"\x1b[?2026h").count();
                    pc.frames.fetch_add(n as u64, Ordering::Relaxed);
                    let keep = tail.len().min(7);
                    tail.drain(..tail.len() - keep);
                }
                None => break,
                _ => {}
            },
            () = tokio::time::sleep_until(wake) => {
                if tokio::time::Instant::now() >= end { break; }
                next_key += Duration::from_millis(if bot.turn { 30 } else { 100 });
                if bot.idle { continue; }
                let key = bot.key(&mut lcg);
                let _ = ch.data(&[key][..]).await;
            }
        }
    }
    let _ = ch.data(&b"\x03"[..]).await;
    let _ = h.disconnect(russh::Disconnect::ByApplication, "", "").await;
}

/// A browser page holding a random movement key for 100 ms after another, and
/// acking each frame as it arrives, as the page does once it drew it. Payload is the frames'
/// bytes as sent (compressed or not); wire adds nothing for the WebSocket's framing.
async fn web_bot(addr: std::net::SocketAddr, bot: Bot) {
    let (cols, rows) = bot.size;
    let url = format!("ws://{addr}/ws?name=bot{}&cols={cols}&rows={rows}", bot.i);
    let tcp = tokio::net::TcpStream::connect(addr).await.expect("connect");
    // As a browser's socket is: an ack must not wait for the last one's TCP acknowledgement.
    tcp.set_nodelay(true).expect("nodelay");
    let (ws, _) = tokio_tungstenite::client_async(url, tcp)
        .await
        .expect("upgrade");
    let (mut tx, mut rx) = ws.split();
    let pc = &bot.pc;
    let wire = Arc::new(AtomicU64::new(0));
    *pc.wire.lock().expect("wire") = Some(Arc::clone(&wire));
    let end = tokio::time::Instant::now() + Duration::from_secs(bot.secs);
    let mut next_key = tokio::time::Instant::now();
    let mut lcg = bot.seed();
    let mut n = 0u64;
    let mut held = 'w';
    loop {
        let wake = next_key.min(end);
        tokio::select! {
            msg = rx.next() => match msg {
                Some(Ok(Message::Binary(data))) => {
                    n += 1;
                    pc.payload.fetch_add(data.len() as u64, Ordering::Relaxed);
                    wire.fetch_add(data.len() as u64, Ordering::Relaxed);
                    pc.frames.fetch_add(1, Ordering::Relaxed);
                    let ack = format!("{{\"ack\":{n}}}");
                    if tx.send(Message::Text(ack.into())).await.is_err() { break; }
                }
                Some(Ok(_)) => {}
                _ => break,
            },
            () = tokio::time::sleep_until(wake) => {
                if tokio::time::Instant::now() >= end { break; }
                next_key += Duration::from_millis(100);
                if bot.idle { continue; }
                // The last key up and the next down: the view moves all the time, as an SSH
                // bot's taps (each a hold of a terminal's repeat delay) make it.
                let key = char::from(bot.key(&mut lcg));
                if bot.turn && held == key { continue; }
                for (k, down) in [(held, false), (key, true)] {
                    let msg = format!("{{\"key\":\"{k}\",\"down\":{down}}}");
                    let _ = tx.send(Message::Text(msg.into())).await;
                }
                held = key;
            }
        }
    }
    let _ = tx.send(Message::Close(None)).await;
}

/// GETs the metrics page once a second (the scrape's cost on the server counts too).
async fn scrape_every_second(port: u16) {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    loop {
        tokio::time::sleep(Duration::from_secs(1)).await;
        if let Ok(mut s) = tokio::net::TcpStream::connect(("127.0.0.1", port)).await {
            let _ = s
                .write_all(b"GET /metrics HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")
                .await;
            let mut sink = Vec::new();
            let _ = s.read_to_end(&mut sink).await;
        }
    }
}
