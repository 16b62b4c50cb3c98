//! SSH compression with russh on both ends: the delayed `zlib@openssh.com` (what `ssh -C`
//! negotiates), plain `zlib`, and none. Each must carry a long stream of frames without desync,
//! and the compressed ones must put fewer bytes on the wire.

use crate::serve_support;

use std::sync::atomic::Ordering;
use std::time::Duration;

use russh::compression;
use serve_support::{connect_counting, full_view, header_has, server};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_compression_carries_many_frames_and_zlib_shrinks_them() {
    let (srv, _dir) = server(|_| {}).await;
    let addr = srv.local_addr();
    let mut wire = Vec::new();
    for (name, alg) in [
        ("zlib@openssh.com", compression::ZLIB_LEGACY),
        ("zlib", compression::ZLIB),
        ("none", compression::NONE),
    ] {
        let (mut c, read) = connect_counting(addr, "ann", 80, 24, "xterm-direct", alg).await;
        assert!(
            c.until(|s| header_has(s, "you are ann")).await,
            "{name}: first frame"
        );
        // Turn for a while: every frame changes, hundreds of packets after authentication.
        let start = read.load(Ordering::Relaxed);
        let payload_start = c.bytes;
        for _ in 0..40 {
            c.keys(b"d").await;
            c.drain_for(Duration::from_millis(25)).await;
        }
        c.keys(b"\x1b[C").await;
        c.drain_for(Duration::from_millis(200)).await;
        assert!(!c.closed, "{name}: the stream stays in sync");
        assert!(
            c.until(|s| full_view(s, 80, 24) && header_has(s, "you are ann"))
                .await,
            "{name}: frames still decode"
        );
        let on_wire = read.load(Ordering::Relaxed) - start;
        let payload = (c.bytes - payload_start) as u64;
        eprintln!("{name}: {payload} payload bytes, {on_wire} bytes on the wire");
        wire.push((name, payload, on_wire));
        c.keys(b"\x03").await;
        c.until(|_| false).await;
    }
    for &(name, payload, on_wire) in &wire[..2] {
        assert!(
            on_wire * 2 < payload,
            "{name} compresses the frame stream at least 2x ({on_wire} of {payload})"
        );
    }
    srv.shutdown().await;
}
