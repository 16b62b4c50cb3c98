//! The browser edge behind a real reverse proxy: HAProxy in HTTP mode with
//! `option forwardfor`, in front of `--web` trusting it. Pages from two source addresses
//! (127.0.0.2, 127.0.0.3) load and play through it, their own addresses are the ones the limits
//! count (one connection per address here), and the page's own origin passes the Origin check
//! through the proxy. Skipped with a notice without HAProxy or extra loopback addresses.

use std::net::SocketAddr;
use std::process::{Command, Stdio};
use std::time::Instant;

use halfcast::serve::web::WebOptions;
use tokio_tungstenite::tungstenite::client::IntoClientRequest;

use crate::serve_haproxy::installed;
use crate::serve_process::{free_port, spawn_listening, Guard};
use crate::serve_support::web::{upgrade, WebClient};
use crate::serve_support::{header_has, many_loopback_addresses, server, PATIENCE};

fn haproxy(front: u16, web: SocketAddr, dir: &std::path::Path) -> Guard {
    let cfg = format!(
        "global\n  maxconn 100\n\
         defaults\n  mode http\n  timeout connect 5s\n  timeout client 30s\n  timeout server 30s\n  timeout tunnel 1h\n\
         frontend web\n  bind 127.0.0.1:{front}\n  option forwardfor\n  default_backend halfcast\n\
         backend halfcast\n  server w1 {web}\n"
    );
    haproxy_on(&cfg, front, dir)
}

/// A page's WebSocket from source address `from` through the proxy at `front`, sent with the
/// page's own origin as a browser would.
async fn page_from(from: &str, front: u16, name: &str) -> WebClient {
    through_proxy(from, front, name, None).await
}

/// A page's WebSocket from `from` through the proxy at `front`, with the page's origin and, when
/// `forged` names one, that address in both headers a proxy may use.
async fn through_proxy(from: &str, front: u16, name: &str, forged: Option<&str>) -> WebClient {
    let socket = tokio::net::TcpSocket::new_v4().unwrap();
    socket.bind(format!("{from}:0").parse().unwrap()).unwrap();
    let tcp = socket
        .connect(format!("127.0.0.1:{front}").parse().unwrap())
        .await
        .expect("the proxy answers");
    let mut req = format!("ws://127.0.0.1:{front}/ws?name={name}&cols=80&rows=24")
        .into_client_request()
        .unwrap();
    let h = req.headers_mut();
    h.insert(
        "Origin",
        format!("http://127.0.0.1:{front}").parse().unwrap(),
    );
    if let Some(forged) = forged {
        h.insert("Forwarded", format!("for={forged}").parse().unwrap());
        h.append(
            "X-Forwarded-For",
            format!("{forged}, 198.51.100.9").parse().unwrap(),
        );
    }
    upgrade(req, tcp).await.expect("upgraded through the proxy")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn pages_play_through_haproxy_limited_by_their_own_addresses() {
    if !installed("haproxy", "-v") {
        eprintln!("SKIPPED: HAProxy is not installed (apt-get install haproxy)");
        return;
    }
    if !many_loopback_addresses() {
        return;
    }
    let (srv, dir) = server(|c| {
        c.max_per_ip = 1;
        let mut w = WebOptions::new("127.0.0.1:0".parse().unwrap());
        w.trusted_proxies = vec!["127.0.0.1".parse().unwrap()];
        c.web = Some(w);
    })
    .await;
    let front = free_port();
    let _proxy = haproxy(front, srv.web_addr().unwrap(), dir.path());
    let page = tokio::task::spawn_blocking(move || crate::serve_support::http::get(front, "/"))
        .await
        .unwrap();
    assert_eq!(page.0, 200, "the page through the proxy");
    let mut two = page_from("127.0.0.2", front, "two").await;
    let mut three = page_from("127.0.0.3", front, "three").await;
    assert!(two.until(|s| header_has(s, "you are two")).await);
    assert!(three.until(|s| header_has(s, "you are three")).await);
    // Through one proxy address, yet counted by the players' own: a second page from 127.0.0.2
    // is over its address's limit.
    let mut again = page_from("127.0.0.2", front, "again").await;
    let closed = again.closed().await;
    assert!(
        closed
            .reason
            .contains("too many connections from your address"),
        "{closed:?}"
    );
    srv.shutdown().await;
}

/// The shipped web snippet (docs/deploy/haproxy-halfcast-web.cfg) with its TLS binds moved to
/// `bind` lines of the test's and its world at `web`, after a `global` of the test's own.
fn shipped_config(binds: &str, web: u16) -> String {
    use crate::serve_haproxy::{deploy, moved};
    let snippet = deploy("haproxy-halfcast-web.cfg");
    let snippet = moved(
        &snippet,
        "    bind :443 ssl crt /etc/haproxy/certs/game.pem\n    bind :::443 v6only ssl crt /etc/haproxy/certs/game.pem\n",
        binds,
    );
    let snippet = moved(
        &snippet,
        "server web1 127.0.0.1:8081",
        &format!("server web1 127.0.0.1:{web}"),
    );
    format!("global\n    maxconn 1024\n\n{snippet}")
}

/// HAProxy on `cfg`, once it listens on `front`.
fn haproxy_on(cfg: &str, front: u16, dir: &std::path::Path) -> Guard {
    let path = dir.join("haproxy-web.cfg");
    std::fs::write(&path, cfg).unwrap();
    let mut haproxy = Command::new("haproxy");
    haproxy.args(["-db", "-f"]).arg(&path);
    spawn_listening(haproxy, front)
}

/// A page's WebSocket from `from` through the proxy at `front` that also sends addresses of
/// its own choosing, in both headers a proxy may use.
pub(crate) async fn forging_page_from(
    from: &str,
    front: u16,
    name: &str,
    forged: &str,
) -> WebClient {
    through_proxy(from, front, name, Some(forged)).await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_shipped_web_snippet_gives_the_real_client_whatever_headers_it_sends() {
    if !installed("haproxy", "-v") {
        eprintln!("SKIPPED: HAProxy is not installed (apt-get install haproxy)");
        return;
    }
    if !many_loopback_addresses() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let web = crate::serve_process::free_port();
    let w = web.to_string();
    let (_world, _ssh, log) = crate::serve_process::spawn_server(
        dir.path(),
        &[
            "--web",
            &w,
            "--web-trusted-proxy",
            "127.0.0.1",
            "--max-per-ip",
            "1",
        ],
    );
    let front = free_port();
    let cfg = shipped_config(&format!("    bind 127.0.0.1:{front}\n"), web);
    let _proxy = haproxy_on(&cfg, front, dir.path());
    // Both players claim 203.0.113.5 (and more); each is counted by their own address.
    forged_addresses_never_count(front, &log).await;
}

#[test]
fn the_shipped_web_snippet_ends_tls_with_a_real_certificate() {
    if !installed("haproxy", "-v") || !installed("openssl", "version") || !installed("curl", "-V") {
        eprintln!("SKIPPED: HAProxy, openssl or curl is not installed");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let pem = dir.path().join("game.pem");
    let (key, cert) = (dir.path().join("key.pem"), dir.path().join("cert.pem"));
    let made = Command::new("openssl")
        .args([
            "req",
            "-x509",
            "-newkey",
            "ec",
            "-pkeyopt",
            "ec_paramgen_curve:prime256v1",
        ])
        .args(["-nodes", "-days", "1", "-subj", "/CN=localhost", "-keyout"])
        .arg(&key)
        .arg("-out")
        .arg(&cert)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .unwrap();
    assert!(made.success(), "openssl made a certificate");
    let both = [std::fs::read(&cert).unwrap(), std::fs::read(&key).unwrap()].concat();
    std::fs::write(&pem, both).unwrap();
    let web = crate::serve_process::free_port();
    let w = web.to_string();
    let (_world, _ssh, _log) = crate::serve_process::spawn_server(
        dir.path(),
        &["--web", &w, "--web-trusted-proxy", "127.0.0.1"],
    );
    let front = free_port();
    let binds = format!("    bind 127.0.0.1:{front} ssl crt {}\n", pem.display());
    let _proxy = haproxy_on(&shipped_config(&binds, web), front, dir.path());
    let out = Command::new("curl")
        .args([
            "-sk",
            "-o",
            "/dev/null",
            "-w",
            "%{http_code} %{ssl_verify_result}",
        ])
        .arg(format!("https://127.0.0.1:{front}/healthz"))
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        said.starts_with("200"),
        "/healthz over TLS through the snippet: {said}"
    );
    let page = Command::new("curl")
        .args(["-sk"])
        .arg(format!("https://127.0.0.1:{front}/"))
        .output()
        .unwrap();
    assert!(
        String::from_utf8_lossy(&page.stdout).contains("<script"),
        "the page over TLS"
    );
}

/// Through a trusted proxy on `front`, pages from 127.0.0.2 and 127.0.0.3 that send their own
/// `Forwarded` and `X-Forwarded-For` are limited and logged (`log`, the world's) by the address
/// the proxy saw; no forged address reaches the log.
pub(crate) async fn forged_addresses_never_count(
    front: u16,
    log: &std::sync::mpsc::Receiver<String>,
) {
    let mut two = forging_page_from("127.0.0.2", front, "two", "203.0.113.5").await;
    let mut three = forging_page_from("127.0.0.3", front, "three", "203.0.113.5").await;
    assert!(two.until(|s| header_has(s, "you are two")).await);
    assert!(three.until(|s| header_has(s, "you are three")).await);
    // A second page from 127.0.0.2 claiming another address is over 127.0.0.2's limit.
    let mut again = forging_page_from("127.0.0.2", front, "again", "203.0.113.77").await;
    let closed = again.closed().await;
    assert!(
        closed
            .reason
            .contains("too many connections from your address"),
        "{closed:?}"
    );
    drop((two, three));
    let mut lines: Vec<String> = Vec::new();
    let deadline = Instant::now() + PATIENCE;
    while !(lines
        .iter()
        .any(|l| l.contains("127.0.0.2") && l.contains("\"two\""))
        && lines
            .iter()
            .any(|l| l.contains("127.0.0.3") && l.contains("\"three\"")))
    {
        let left = deadline.saturating_duration_since(Instant::now());
        match log.recv_timeout(left) {
            Ok(l) => lines.push(l),
            Err(_) => panic!("the players' own addresses were never logged: {lines:#?}"),
        }
    }
    lines.extend(log.try_iter());
    for forged in ["203.0.113", "198.51.100"] {
        assert!(
            lines.iter().all(|l| !l.contains(forged)),
            "a client's own address reached the log: {lines:#?}"
        );
    }
}
