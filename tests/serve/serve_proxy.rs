//! `--proxy-protocol`: behind a load balancer every connection opens with a PROXY header, and
//! the address it names is the one the limits use. Here the test is the balancer: it writes
//! v1 and v2 headers itself on loopback connections (all really from 127.0.0.1), then speaks
//! SSH with russh on the same stream. Without the flag, a header is refused as bad input.

use crate::serve_support;

use std::net::SocketAddr;
use std::sync::Arc;

use halfcast::serve::RunningServer;
use russh::client;
use serve_support::{server, Trusting};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

fn v1(src: &str, port: u16) -> Vec<u8> {
    format!("PROXY TCP4 {src} 127.0.0.1 {port} 2222\r\n").into_bytes()
}

fn v2(src: [u8; 4], port: u16) -> Vec<u8> {
    let mut b = b"\r\n\r\n\0\r\nQUIT\n".to_vec();
    b.extend_from_slice(&[0x21, 0x11, 0, 12]);
    b.extend_from_slice(&src);
    b.extend_from_slice(&[127, 0, 0, 1]);
    b.extend_from_slice(&port.to_be_bytes());
    b.extend_from_slice(&2222u16.to_be_bytes());
    b
}

/// A loopback connection that starts with `header`.
async fn with_header(addr: SocketAddr, header: &[u8]) -> TcpStream {
    let mut s = TcpStream::connect(addr).await.expect("connect");
    s.write_all(header).await.expect("header");
    s
}

/// SSH over `stream`, logged in as `user` (no auth).
async fn ssh(stream: TcpStream, user: &str) -> Result<client::Handle<Trusting>, String> {
    let mut h = client::connect_stream(Arc::new(client::Config::default()), stream, Trusting)
        .await
        .map_err(|e| e.to_string())?;
    let ok = h.authenticate_none(user).await.map_err(|e| e.to_string())?;
    if ok.success() {
        Ok(h)
    } else {
        Err("auth refused".into())
    }
}

/// Everything the server says before it closes.
async fn said(mut s: TcpStream) -> String {
    let mut out = Vec::new();
    let _ = tokio::time::timeout(serve_support::PATIENCE, s.read_to_end(&mut out)).await;
    String::from_utf8_lossy(&out).into_owned()
}

async fn behind_balancer() -> (RunningServer, tempfile::TempDir) {
    server(|c| {
        c.proxy_protocol = true;
        c.max_per_ip = 1;
    })
    .await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn v1_and_v2_headers_name_the_client_and_two_sources_are_limited_apart() {
    let (srv, _dir) = behind_balancer().await;
    let addr = srv.local_addr();
    // 127.0.0.2 through a v1 header: in.
    let a = ssh(with_header(addr, &v1("127.0.0.2", 40001)).await, "ann")
        .await
        .expect("ann via v1");
    // 127.0.0.2 again through v2: its one place is taken, whatever the TCP peer.
    let refused = said(with_header(addr, &v2([127, 0, 0, 2], 40002)).await).await;
    assert!(
        refused.contains("too many connections from your address"),
        "{refused:?}"
    );
    // 127.0.0.3 through v2: a place of its own.
    let b = ssh(with_header(addr, &v2([127, 0, 0, 3], 40003)).await, "bob")
        .await
        .expect("bob via v2");
    assert_eq!(srv.live().0 + srv.live().1, 2);
    drop((a, b));
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn missing_and_malformed_headers_are_refused() {
    let (srv, _dir) = behind_balancer().await;
    let addr = srv.local_addr();
    let plain = said(with_header(addr, b"SSH-2.0-OpenSSH_9.2\r\n").await).await;
    assert_eq!(
        plain,
        "halfcast: the connection did not start with a PROXY protocol header\r\n"
    );
    let bad = said(with_header(addr, b"PROXY TCP4 1.2.3 5.6.7.8 1 2\r\n").await).await;
    assert!(bad.starts_with("halfcast: bad PROXY v1 header"), "{bad:?}");
    let mut v2_bad = v2([10, 0, 0, 1], 5);
    v2_bad[12] = 0x31; // version 3
    let bad = said(with_header(addr, &v2_bad).await).await;
    assert!(bad.starts_with("halfcast: bad PROXY v2 header"), "{bad:?}");
    assert_eq!(srv.live(), (0, 0));
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn without_the_flag_a_header_is_bad_input() {
    let (srv, _dir) = server(|_| {}).await;
    let addr = srv.local_addr();
    let e = ssh(with_header(addr, &v1("192.0.2.1", 4000)).await, "ann").await;
    assert!(
        e.is_err(),
        "a PROXY header was taken without --proxy-protocol"
    );
    let e = ssh(with_header(addr, &v2([192, 0, 2, 1], 4000)).await, "ann").await;
    assert!(
        e.is_err(),
        "a PROXY v2 header was taken without --proxy-protocol"
    );
    // Plain SSH still works.
    let ok = ssh(TcpStream::connect(addr).await.expect("connect"), "ann").await;
    assert!(ok.is_ok(), "{:?}", ok.err());
    srv.shutdown().await;
}
