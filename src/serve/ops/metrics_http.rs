//! The `--metrics` address's own small HTTP listener: `/metrics` (Prometheus' text format) and
//! `/healthz` (a load balancer's health check: 200 accepting, 503 draining or full).
//!
//! Each request is one GET (or HEAD) answered and closed (`Connection: close`); health checks
//! arrive here, never on the SSH port, so they are neither logged as players nor counted in
//! `halfcast_connections_total` (they have `halfcast_health_checks_total` of their own).
//! Bounded: a request line and headers of at most [`MAX_REQUEST`] bytes within
//! [`REQUEST_WAIT`], at most [`MAX_OPEN`] requests at once (more are closed at accept).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::Duration;

use metrics_exporter_prometheus::PrometheusHandle;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};

use super::health::Readiness;

/// Longest request (line and headers) read; a longer one is answered 431.
pub const MAX_REQUEST: usize = 8192;
/// How long a client may take to send its request.
pub const REQUEST_WAIT: Duration = Duration::from_secs(5);
/// Requests served at once.
pub const MAX_OPEN: usize = 64;
/// How often the recorder's histograms are maintained (the exporter's own listener did this).
const UPKEEP: Duration = Duration::from_secs(5);

/// Serves `/metrics` from `handle` and `/healthz` from `ready` on `listener` until the task is
/// dropped or aborted.
pub async fn serve(listener: TcpListener, handle: PrometheusHandle, ready: Arc<Readiness>) {
    let open = Arc::new(AtomicUsize::new(0));
    let mut upkeep = tokio::time::interval(UPKEEP);
    loop {
        let socket = tokio::select! {
            _ = upkeep.tick() => {
                handle.run_upkeep();
                continue;
            }
            r = listener.accept() => match r {
                Ok((s, _)) => s,
                Err(_) => {
                    // E.g. out of file descriptors: back off instead of spinning.
                    tokio::time::sleep(Duration::from_millis(100)).await;
                    continue;
                }
            },
        };
        if open.load(Ordering::Relaxed) >= MAX_OPEN {
            continue;
        }
        open.fetch_add(1, Ordering::Relaxed);
        let (open, handle, ready) = (Arc::clone(&open), handle.clone(), Arc::clone(&ready));
        tokio::spawn(async move {
            let _ = tokio::time::timeout(REQUEST_WAIT * 2, answer(socket, &handle, &ready)).await;
            open.fetch_sub(1, Ordering::Relaxed);
        });
    }
}

/// An answer: status, content type, body.
struct Reply {
    status: u16,
    kind: &'static str,
    body: String,
}

/// Reads one request from `socket` and answers it.
async fn answer(mut socket: TcpStream, handle: &PrometheusHandle, ready: &Readiness) {
    let mut buf = Vec::with_capacity(512);
    let complete = tokio::time::timeout(REQUEST_WAIT, async {
        let mut chunk = [0u8; 1024];
        loop {
            if buf.windows(4).any(|w| w == b"\r\n\r\n") {
                return true;
            }
            if buf.len() >= MAX_REQUEST {
                return false;
            }
            match socket.read(&mut chunk).await {
                Ok(0) | Err(_) => return buf.contains(&b'\n'),
                Ok(n) => buf.extend_from_slice(&chunk[..n]),
            }
        }
    })
    .await
    .unwrap_or(false);
    let (method, reply) = if complete {
        let line = buf.split(|&b| b == b'\n').next().unwrap_or_default();
        let line = String::from_utf8_lossy(line);
        let mut parts = line.split_ascii_whitespace();
        let method = parts.next().unwrap_or_default().to_owned();
        let target = parts.next().unwrap_or_default();
        let reply = route(&method, target, handle, ready);
        (method, reply)
    } else if buf.len() >= MAX_REQUEST {
        (String::new(), text(431, "request too large\n"))
    } else {
        // Nothing sensible arrived in time: close without a word.
        return;
    };
    let head = format!(
        "HTTP/1.1 {} {}\r\nContent-Type: {}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
        reply.status,
        reason(reply.status),
        reply.kind,
        reply.body.len()
    );
    let mut out = head.into_bytes();
    if method != "HEAD" {
        out.extend_from_slice(reply.body.as_bytes());
    }
    let _ = socket.write_all(&out).await;
    let _ = socket.shutdown().await;
}

/// What a request for `target` by `method` is answered with.
fn route(method: &str, target: &str, handle: &PrometheusHandle, ready: &Readiness) -> Reply {
    if method != "GET" && method != "HEAD" {
        return text(405, "only GET and HEAD\n");
    }
    let path = target.split('?').next().unwrap_or_default();
    match path {
        "/healthz" => {
            let h = ready.health();
            super::metrics::health_check(h.word());
            text(h.status(), &format!("{}\n", h.word()))
        }
        "/metrics" => {
            super::metrics::before_scrape();
            Reply {
                status: 200,
                kind: "text/plain; version=0.0.4",
                body: handle.render(),
            }
        }
        _ => text(404, "not found: try /metrics or /healthz\n"),
    }
}

fn text(status: u16, body: &str) -> Reply {
    Reply {
        status,
        kind: "text/plain; charset=utf-8",
        body: body.to_owned(),
    }
}

fn reason(status: u16) -> &'static str {
    match status {
        200 => "OK",
        404 => "Not Found",
        405 => "Method Not Allowed",
        431 => "Request Header Fields Too Large",
        503 => "Service Unavailable",
        _ => "",
    }
}
