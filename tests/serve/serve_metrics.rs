//! `halfcast serve --metrics`: the Prometheus endpoint of a real server process, scraped with a
//! plain HTTP GET and read as the text format, while russh clients join, are refused and
//! leave. (A process of its own: the metrics recorder is process-wide.)

use crate::serve_support;

use std::collections::HashMap;
use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::{Duration, Instant};

use crate::serve_process::{free_port, spawn_server};
use serve_support::{connect_raw, header_has, Client, PATIENCE};

/// GET /metrics, parsed: `name{labels}` → value (histograms as their `_count`, `_sum`, …).
fn scrape(port: u16) -> HashMap<String, f64> {
    let mut s = TcpStream::connect(("127.0.0.1", port)).expect("metrics port");
    s.set_read_timeout(Some(PATIENCE)).unwrap();
    write!(
        s,
        "GET /metrics HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut body = String::new();
    s.read_to_string(&mut body).expect("response");
    assert!(body.starts_with("HTTP/1.1 200"), "{body}");
    let text = body.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    let mut out = HashMap::new();
    for line in text.lines() {
        if line.starts_with('#') || line.trim().is_empty() {
            continue;
        }
        let (name, value) = line.rsplit_once(' ').expect("NAME VALUE");
        let v: f64 = value
            .parse()
            .unwrap_or_else(|_| panic!("a number in {line}"));
        out.insert(name.to_owned(), v);
    }
    out
}

fn get(m: &HashMap<String, f64>, k: &str) -> f64 {
    m.get(k).copied().unwrap_or(0.0)
}

/// Scrapes until `ok` holds (fails with the last scrape otherwise).
async fn wait_for(port: u16, what: &str, ok: impl Fn(&HashMap<String, f64>) -> bool) {
    let deadline = Instant::now() + PATIENCE;
    loop {
        let m = scrape(port);
        if ok(&m) {
            return;
        }
        assert!(
            Instant::now() < deadline,
            "gave up waiting for {what}: {m:#?}"
        );
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn counters_move_as_clients_join_are_refused_and_leave() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mport = free_port();
    let metrics = mport.to_string();
    let (_srv, port, _log) = spawn_server(
        dir.path(),
        &["--metrics", &metrics, "--max-sessions", "2", "--db", "none"],
    );
    let addr: std::net::SocketAddr = format!("127.0.0.1:{port}").parse().unwrap();
    let m = scrape(mport);
    assert_eq!(get(&m, "halfcast_connections_total"), 0.0, "{m:#?}");

    let mut ann = Client::connect(addr, "ann", 80, 24, "xterm-256color").await;
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    wait_for(mport, "ann playing and her frames", |m| {
        get(m, r#"halfcast_sessions{state="playing"}"#) == 1.0
            && get(m, "halfcast_connections_total") == 1.0
            && get(m, "halfcast_logging_in") == 0.0
            && get(m, "halfcast_frames_sent_total") > 0.0
            && get(m, "halfcast_payload_bytes_total") > 0.0
            && get(m, "halfcast_wire_bytes_total") > 0.0
            && get(m, "halfcast_frame_render_seconds_count") > 0.0
            && get(m, "halfcast_frame_encode_seconds_count") > 0.0
            && get(m, "halfcast_world_tick_seconds_count") > 0.0
            && m.contains_key(r#"halfcast_frame_render_seconds_bucket{le="+Inf"}"#)
            // Each frame that went says how long it waited for the link (on loopback: none).
            && get(m, "halfcast_link_wait_seconds_count") > 0.0
    })
    .await;

    // A watcher takes the second and last place.
    let mut w = Client::connect(addr, "watch", 80, 24, "xterm-256color").await;
    assert!(w.until(|s| header_has(s, "watching")).await);
    wait_for(mport, "a watcher", |m| {
        get(m, r#"halfcast_sessions{state="watching"}"#) == 1.0
    })
    .await;

    // Two sessions at most: bob is told the server is full.
    let mut bob = connect_raw(addr, None).await.expect("bob connects");
    let _ = bob.authenticate_none("bob").await;
    wait_for(mport, "bob refused as full", |m| {
        get(m, r#"halfcast_refusals_total{reason="full"}"#) == 1.0
            && get(m, "halfcast_connections_total") == 3.0
    })
    .await;
    drop(bob);

    // Ann quits: one session fewer playing; the watcher stays.
    ann.keys(b"q").await;
    wait_for(mport, "ann gone", |m| {
        get(m, r#"halfcast_sessions{state="playing"}"#) == 0.0
            && get(m, r#"halfcast_sessions{state="watching"}"#) == 1.0
            && get(m, "halfcast_logging_in") == 0.0
    })
    .await;
}
