//! A client that stops reading is disconnected — the whole SSH connection, not only its game —
//! after `--stall-timeout`, its place freed, and the server's memory stays bounded meanwhile.
//! (One test in this file, so its memory figures are not mixed with other tests'.)

use crate::serve_support;

use std::time::{Duration, Instant};

use serve_support::{
    connect_tapped, header_has, process_usage, server, try_connect, TapMode, PATIENCE,
};

const STALL: Duration = Duration::from_secs(2);

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_client_that_stops_reading_is_disconnected_and_its_place_freed() {
    let (srv, _dir) = server(|c| {
        c.max_sessions = 1;
        c.stall_timeout = STALL;
    })
    .await;
    let addr = srv.local_addr();
    // The biggest screen a client may have, so that frames are large.
    let (mut c, tap) = connect_tapped(addr, "sloth", "xterm-256color", 500, 200)
        .await
        .expect("connect");
    assert!(c.until(|s| header_has(s, "you are sloth")).await);
    let before = process_usage();
    tap.set(TapMode::Stalled);
    let stalled_at = Instant::now();
    // Keep turning so that every frame differs, while never reading a byte. The buffers between
    // (socket, SSH window) fill first, which takes longer on a loaded machine: the bound is
    // generous, the time it took is printed.
    let mut freed = None;
    let mut peak_rss = 0;
    while stalled_at.elapsed() < STALL + PATIENCE {
        let _ = tokio::time::timeout(Duration::from_millis(50), c.channel.data(&b"dddd"[..])).await;
        if let Some((_, _, rss)) = process_usage() {
            peak_rss = peak_rss.max(rss);
        }
        if srv.stats().sessions_live == 0 {
            freed = Some(stalled_at.elapsed());
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    let freed = freed.expect("the stalled session ended");
    // The place is free: another player gets in (max_sessions is 1).
    let mut other = None;
    for _ in 0..40 {
        if let Ok(o) = try_connect(addr, "next", 40, 12).await {
            other = Some(o);
            break;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    let mut other = other.expect("the stalled client's place is free again");
    assert!(other.until(|s| header_has(s, "you are next")).await);
    // The SSH connection itself is gone: reading again, the client finds it closed.
    tap.set(TapMode::Open);
    let deadline = Instant::now() + Duration::from_secs(5);
    while !c.handle.is_closed() && Instant::now() < deadline {
        c.drain_for(Duration::from_millis(100)).await;
    }
    assert!(
        c.handle.is_closed(),
        "the server closed the stalled connection"
    );
    if let Some((_, _, rss0)) = before {
        eprintln!(
            "stalled reader (500x200, stall timeout {STALL:?}): session and connection closed \
             {:.2} s after the client stopped reading; RSS {} KiB before, peak {} KiB while \
             stalled (+{} KiB)",
            freed.as_secs_f64(),
            rss0,
            peak_rss,
            peak_rss.saturating_sub(rss0)
        );
        assert!(
            peak_rss < rss0 + 64 * 1024,
            "memory stays bounded while a client does not read ({rss0} → {peak_rss} KiB)"
        );
    }
    srv.shutdown().await;
}
