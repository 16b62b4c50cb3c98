//! `halfcast serve --log-format json`: every line on stderr is one JSON object, and a client
//! that connects, logs in, plays through a round and quits (with a second connection refused
//! meanwhile) leaves connect, login, refusal, round_end and disconnect events with the fields
//! a log shipper reads.

use crate::serve_process::spawn_server;
use crate::serve_support;

use std::sync::mpsc;
use std::time::{Duration, Instant};

use serde_json::Value;
use serve_support::{connect_raw, header_has, Client, PATIENCE};

/// Reads JSON lines until one has `event` == `want`; every line read must parse.
fn next_event(rx: &mpsc::Receiver<String>, want: &str, seen: &mut Vec<Value>) -> Value {
    let deadline = Instant::now() + PATIENCE;
    loop {
        let left = deadline
            .checked_duration_since(Instant::now())
            .unwrap_or_else(|| panic!("no {want} event; saw {seen:#?}"));
        let line = rx
            .recv_timeout(left)
            .unwrap_or_else(|_| panic!("no {want} event; saw {seen:#?}"));
        let v: Value = serde_json::from_str(&line).unwrap_or_else(|e| panic!("{e}: {line}"));
        assert!(v["ts"].as_f64().is_some_and(|t| t > 1.6e9), "{line}");
        seen.push(v.clone());
        if v["event"] == want {
            return v;
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn each_event_is_one_json_object_with_its_fields() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (_srv, port, log) = spawn_server(
        dir.path(),
        &[
            "--log-format",
            "json",
            "--db",
            "none",
            "--max-per-ip",
            "1",
            "--round-minutes",
            "0.02",
        ],
    );
    let addr: std::net::SocketAddr = format!("127.0.0.1:{port}").parse().unwrap();
    let mut seen = Vec::new();
    let mut ann = Client::connect(addr, "ann", 80, 24, "xterm-256color").await;
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    let c = next_event(&log, "connect", &mut seen);
    let id = c["session"].as_u64().expect("a session id");
    assert!(c["peer"].as_str().unwrap().starts_with("127.0.0.1:"), "{c}");
    let l = next_event(&log, "login", &mut seen);
    assert_eq!(
        (&l["session"], &l["name"], &l["as"], &l["term"]),
        (
            &Value::from(id),
            &Value::from("ann"),
            &Value::from("playing"),
            &Value::from("xterm-256color")
        )
    );

    // A second connection from the same address is over --max-per-ip.
    let _ = connect_raw(addr, None).await;
    let r = next_event(&log, "refusal", &mut seen);
    assert_eq!(r["reason"], "per-address", "{r}");
    assert_eq!(
        r["session"],
        Value::Null,
        "refused before it had a session: {r}"
    );
    assert!(
        r["text"].as_str().unwrap().contains("too many connections"),
        "{r}"
    );

    // The 1.2 s round runs out.
    let e = next_event(&log, "round_end", &mut seen);
    assert_eq!(e["mode"], "coop");
    assert_eq!(e["map"], "default.cub", "{e}");
    assert_eq!(e["map_hash"].as_str().unwrap().len(), 16);
    assert!(e["seconds"].as_f64().unwrap() >= 1.2, "{e}");
    assert_eq!(e["players"][0]["name"], "ann", "{e}");

    ann.keys(b"q").await;
    ann.drain_for(Duration::from_millis(100)).await;
    let d = loop {
        let d = next_event(&log, "disconnect", &mut seen);
        if d["session"] == id {
            break d;
        }
    };
    assert!(d["seconds"].as_f64().unwrap() > 1.0, "{d}");
    assert!(d["bytes_out"].as_u64().unwrap() > 1000, "{d}");
    assert!(d["bytes_in"].as_u64().unwrap() > 100, "{d}");
    // The link it played over (loopback: a round trip under a second, nothing stepped).
    let link = &d["link"];
    assert!(link["rtt_ms"].as_f64().unwrap() < 1000.0, "{d}");
    assert!(link["kbit_per_s"].as_f64().unwrap() > 0.0, "{d}");
    assert!(link["max_queued_bytes"].is_u64(), "{d}");
    assert_eq!(link["level_steps_down"], 0, "{d}");
    assert_eq!(link["level_steps_up"], 0, "{d}");
    // Why it closed, when the server closed it (one game per connection: after `q` the
    // server hangs up if the client has not already).
    assert!(d["error"].is_null() || d["error"].is_string(), "{d}");
}

#[test]
fn a_world_that_cannot_start_says_why_in_its_json_log() {
    let dir = tempfile::tempdir().expect("tempdir");
    // Its SSH port is taken.
    let taken = std::net::TcpListener::bind("127.0.0.1:0").expect("a port");
    let port = taken.local_addr().unwrap().port();
    let (mut srv, log) = crate::serve_process::spawn(
        port,
        &dir.path().join("hk"),
        &["--log-format", "json", "--db", "none"],
        &[],
    );
    let status = srv.0.wait().expect("it exits");
    // A port in use is an I/O failure (README's exit codes: 1), not bad input (issue 56).
    assert_eq!(status.code(), Some(1));
    let lines: Vec<String> = log.iter().collect();
    // Every line is JSON, the last says why, with the cause.
    let events: Vec<serde_json::Value> = lines
        .iter()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect();
    let last = events.last().expect("a line");
    assert_eq!(last["event"], "start_failed", "{lines:#?}");
    let text = last["text"].as_str().unwrap();
    assert!(
        text.contains(&format!("cannot listen on 127.0.0.1:{port}")) && text.contains("in use"),
        "{text}"
    );
}
