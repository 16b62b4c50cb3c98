//! The browser edge behind a real reverse proxy: HAProxy in HTTP mode with
//! `option forwardfor`, in front of `--web` trusting it. Pages from two source addresses
//! (127.0.0.2, 127.0.0.3) load and play through it, their own addresses are the ones the limits
//! count (one connection per address here), and the page's own origin passes the Origin check
//! through the proxy. Skipped with a notice without HAProxy or extra loopback addresses.

use std::net::SocketAddr;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use halfcast::serve::web::WebOptions;
use tokio_tungstenite::tungstenite::client::IntoClientRequest;

use crate::serve_haproxy::installed;
use crate::serve_process::{free_port, Guard};
use crate::serve_support::web::WebClient;
use crate::serve_support::{header_has, many_loopback_addresses, server, PATIENCE};

fn haproxy(front: u16, web: SocketAddr, dir: &std::path::Path) -> Guard {
    let cfg = format!(
        "global\n  maxconn 100\n\
         defaults\n  mode http\n  timeout connect 5s\n  timeout client 30s\n  timeout server 30s\n  timeout tunnel 1h\n\
         frontend web\n  bind 127.0.0.1:{front}\n  option forwardfor\n  default_backend halfcast\n\
         backend halfcast\n  server w1 {web}\n"
    );
    let path = dir.join("haproxy-web.cfg");
    std::fs::write(&path, cfg).unwrap();
    let child = Command::new("haproxy")
        .args(["-db", "-f"])
        .arg(&path)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("haproxy starts");
    let deadline = Instant::now() + PATIENCE;
    while std::net::TcpStream::connect(("127.0.0.1", front)).is_err() {
        assert!(Instant::now() < deadline, "haproxy never listened");
        std::thread::sleep(Duration::from_millis(50));
    }
    Guard(child)
}

/// A page's WebSocket from source address `from` through the proxy at `front`, sent with the
/// page's own origin as a browser would.
async fn page_from(from: &str, front: u16, name: &str) -> WebClient {
    let socket = tokio::net::TcpSocket::new_v4().unwrap();
    socket.bind(format!("{from}:0").parse().unwrap()).unwrap();
    let tcp = socket
        .connect(format!("127.0.0.1:{front}").parse().unwrap())
        .await
        .expect("the proxy answers");
    let mut req = format!("ws://127.0.0.1:{front}/ws?name={name}&cols=80&rows=24")
        .into_client_request()
        .unwrap();
    req.headers_mut().insert(
        "Origin",
        format!("http://127.0.0.1:{front}").parse().unwrap(),
    );
    let (ws, _) = tokio_tungstenite::client_async(req, tcp)
        .await
        .expect("upgraded through the proxy");
    WebClient {
        ws,
        screen: vt100::Parser::new(24, 80, 0),
        frames: 0,
        acking: true,
        notes: Vec::new(),
    }
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
