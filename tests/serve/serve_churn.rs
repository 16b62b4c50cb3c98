//! Hundreds of clients that vanish mid-frame leave the server's file descriptors, threads and
//! memory where they were. (One test in this file: it counts the whole process's descriptors.)

use crate::serve_support;

use std::time::{Duration, Instant};

use russh::ChannelMsg;
use serve_support::{connect_tapped, header_has, process_usage, server, Client, TapMode};

const CLIENTS: usize = 300;
const AT_ONCE: usize = 25;

/// Connects, waits for the first bytes of a frame, and cuts the socket in the middle of it.
async fn vanish_mid_frame(addr: std::net::SocketAddr, n: usize) -> bool {
    let Ok((mut c, tap)) =
        connect_tapped(addr, &format!("ghost{n}"), "xterm-256color", 120, 40).await
    else {
        return false;
    };
    let got = tokio::time::timeout(Duration::from_secs(10), async {
        loop {
            match c.wait().await {
                Some(ChannelMsg::Data { .. }) => return true,
                None => return false,
                Some(_) => {}
            }
        }
    })
    .await
    .unwrap_or(false);
    tap.set(TapMode::Cut);
    drop(c);
    got
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn clients_killed_mid_frame_leave_no_descriptors_threads_or_memory_behind() {
    let Some(_) = process_usage() else {
        eprintln!("skipped: no /proc to count descriptors and memory");
        return;
    };
    let (srv, _dir) = server(|c| {
        c.max_sessions = 64;
        c.max_per_ip = 64;
        c.max_startups = "64".parse().expect("startups");
        c.max_startups_per_ip = 64;
    })
    .await;
    let addr = srv.local_addr();
    // Warm up with as many clients as the test then churns, so the allocator's arenas and
    // lazily built state exist before the baseline (measured: RSS rises over the first few
    // hundred clients, then stays within a few MiB however many follow); from then on, nothing
    // may grow per client.
    let mut warm = Client::connect(addr, "warm", 120, 40, "xterm-256color").await;
    assert!(warm.until(|s| header_has(s, "you are warm")).await);
    drop(warm);
    churn(addr, 0, CLIENTS).await;
    settle(&srv, Duration::from_secs(5)).await;
    let base = process_usage().expect("usage");
    let sampling = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(true));
    let sampler = {
        let on = std::sync::Arc::clone(&sampling);
        tokio::spawn(async move {
            let mut peak = (0, 0, 0);
            while on.load(std::sync::atomic::Ordering::Relaxed) {
                if let Some(u) = process_usage() {
                    peak = (peak.0.max(u.0), peak.1.max(u.1), peak.2.max(u.2));
                }
                tokio::time::sleep(Duration::from_millis(20)).await;
            }
            peak
        })
    };
    let start = Instant::now();
    let cut_mid_frame = churn(addr, CLIENTS, CLIENTS).await;
    sampling.store(false, std::sync::atomic::Ordering::Relaxed);
    let peak = sampler.await.expect("sampler");
    settle(&srv, Duration::from_secs(10)).await;
    // Descriptors are closed as the server notices each cut; give it a moment. Threads are
    // counted for the whole test process, so a neighbouring test's threads can show for a while
    // too (the suite runs several tests at once): wait for both to come back. A neighbour may
    // hold its own for a while (serve_pg_outage's worlds' pipes and sockets, about 20 s).
    let mut after = process_usage().expect("usage");
    let deadline = Instant::now() + Duration::from_secs(30);
    while (after.0 > base.0 || after.1 > base.1 + 2) && Instant::now() < deadline {
        tokio::time::sleep(Duration::from_millis(100)).await;
        after = process_usage().expect("usage");
    }
    eprintln!(
        "churn: {CLIENTS} clients after {CLIENTS} warm-up ones ({cut_mid_frame} cut after their first frame bytes) in {:.1} s; \
         fds {} → peak {} → {}, threads {} → {} → {}, RSS {} → {} → {} KiB",
        start.elapsed().as_secs_f64(),
        base.0,
        peak.0,
        after.0,
        base.1,
        peak.1,
        after.1,
        base.2,
        peak.2,
        after.2
    );
    assert!(
        cut_mid_frame >= CLIENTS * 9 / 10,
        "{cut_mid_frame} got frames before the cut"
    );
    assert_eq!(
        srv.stats().sessions_live,
        0,
        "no session outlives its client"
    );
    assert!(
        after.0 <= base.0,
        "file descriptors back at baseline: {} → {}",
        base.0,
        after.0
    );
    assert!(
        after.1 <= base.1 + 2,
        "threads back at baseline: {} → {}",
        base.1,
        after.1
    );
    // 16 MiB over 300 clients: a leak of 55 KiB per client would show (measured: +5.4 MiB, the
    // allocator's noise).
    assert!(
        after.2 < base.2 + 16 * 1024,
        "RSS back near baseline: {} → {} KiB",
        base.2,
        after.2
    );
    // And the server still serves.
    let mut c = Client::connect(addr, "after", 60, 16, "xterm").await;
    assert!(c.until(|s| header_has(s, "you are after")).await);
    srv.shutdown().await;
}

/// `count` clients, `AT_ONCE` at a time, each vanishing mid-frame; how many got frame bytes.
async fn churn(addr: std::net::SocketAddr, first: usize, count: usize) -> usize {
    let mut cut_mid_frame = 0;
    for batch in 0..count / AT_ONCE {
        let tasks: Vec<_> = (0..AT_ONCE)
            .map(|i| tokio::spawn(vanish_mid_frame(addr, first + batch * AT_ONCE + i)))
            .collect();
        for t in tasks {
            if t.await.unwrap_or(false) {
                cut_mid_frame += 1;
            }
        }
    }
    cut_mid_frame
}

/// Waits until no session is live (or `d` passes).
async fn settle(srv: &halfcast::serve::RunningServer, d: Duration) {
    let end = Instant::now() + d;
    while srv.stats().sessions_live > 0 && Instant::now() < end {
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    // Connections outlive their session by up to a second (see handler::AFTER_GAME).
    tokio::time::sleep(Duration::from_millis(1500)).await;
}
