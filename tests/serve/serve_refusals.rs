//! `halfcast serve` offers only the game: no exec, no subsystems, no forwarding; and it keeps to
//! its connection limits and authentication mode.

use crate::serve_support;

use halfcast::serve::auth::AuthMode;
use russh::ChannelMsg;
use std::net::Ipv4Addr;

use serve_support::{
    closed_within, connect_raw, header_has, live_becomes, server, tcp_from, try_connect, Client,
    PATIENCE,
};

/// Waits for the reply to a want-reply channel request: true = success.
async fn reply(ch: &mut russh::Channel<russh::client::Msg>) -> Option<bool> {
    let deadline = tokio::time::Instant::now() + PATIENCE;
    loop {
        match tokio::time::timeout_at(deadline, ch.wait()).await.ok()?? {
            ChannelMsg::Success => return Some(true),
            ChannelMsg::Failure => return Some(false),
            _ => {}
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn exec_subsystem_and_forwarding_are_refused() {
    let (srv, _dir) = server(|_| {}).await;
    let mut h = connect_raw(srv.local_addr(), None).await.expect("connect");
    assert!(h
        .authenticate_none("mallory")
        .await
        .expect("auth")
        .success());
    let mut ch = h.channel_open_session().await.expect("session");
    ch.exec(true, "cat /etc/passwd").await.expect("send exec");
    assert_eq!(reply(&mut ch).await, Some(false), "exec is refused");
    ch.request_subsystem(true, "sftp")
        .await
        .expect("send subsystem");
    assert_eq!(reply(&mut ch).await, Some(false), "sftp is refused");
    ch.set_env(true, "LD_PRELOAD", "/tmp/x.so")
        .await
        .expect("send env");
    assert_eq!(reply(&mut ch).await, Some(false), "env is refused");
    assert!(
        h.channel_open_direct_tcpip("127.0.0.1", 22, "127.0.0.1", 5555)
            .await
            .is_err(),
        "port forwarding is refused"
    );
    assert!(
        h.tcpip_forward("127.0.0.1", 0).await.is_err(),
        "remote forwarding is refused"
    );
    assert!(
        h.channel_open_session().await.is_err(),
        "one session channel per connection"
    );
    // The session channel still works as the game after all that.
    ch.request_pty(true, "xterm", 40, 12, 0, 0, &[])
        .await
        .expect("pty");
    assert_eq!(reply(&mut ch).await, Some(true));
    ch.request_shell(true).await.expect("shell");
    assert_eq!(reply(&mut ch).await, Some(true));
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn max_sessions_counts_players_and_the_per_address_limit_says_why() {
    let (srv, _dir) = server(|c| {
        c.max_sessions = 2;
        c.max_per_ip = 3;
    })
    .await;
    let addr = srv.local_addr();
    let mut a = Client::connect(addr, "a", 40, 10, "xterm").await;
    let _b = Client::connect(addr, "b", 40, 10, "xterm").await;
    assert!(a.until(|s| header_has(s, "2 here")).await);
    // A third player logs in but is told the server is full (an SSH disconnect message).
    assert!(
        try_connect(addr, "c", 40, 10).await.is_err(),
        "a third session is refused"
    );
    assert_eq!(srv.stats().refused, 1);
    // The client hears the refusal before the server's task has let go of that connection.
    assert!(live_becomes(&srv, (0, 2)).await, "{:?}", srv.live());
    // Two playing and one logging in from this address: a fourth connection hears why not.
    let _pending = tcp_from(Ipv4Addr::LOCALHOST, addr).await.expect("tcp");
    assert!(live_becomes(&srv, (1, 2)).await, "{:?}", srv.live());
    let mut fourth = tcp_from(Ipv4Addr::LOCALHOST, addr).await.expect("tcp");
    let mut got = Vec::new();
    assert!(closed_within(&mut fourth, PATIENCE, &mut got).await);
    assert_eq!(
        got,
        halfcast::serve::server::refusal_bytes(
            &halfcast::serve::limits::Refusal::TooManyFromAddress
        ),
        "the reason line, a version line and a disconnect packet"
    );
    drop(_pending);
    drop(a);
    // The freed place is usable again (the server notices the drop first).
    let mut ok = false;
    for _ in 0..100 {
        if try_connect(addr, "d", 40, 10).await.is_ok() {
            ok = true;
            break;
        }
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    }
    assert!(ok, "a place frees up when a client leaves");
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn password_mode_rejects_none_and_wrong_passwords() {
    let (srv, _dir) = server(|c| c.auth = AuthMode::Password("sesame".into())).await;
    let mut h = connect_raw(srv.local_addr(), None).await.expect("connect");
    assert!(!h.authenticate_none("ann").await.expect("auth").success());
    assert!(!h
        .authenticate_password("ann", "open")
        .await
        .expect("auth")
        .success());
    assert!(h
        .authenticate_password("ann", "sesame")
        .await
        .expect("auth")
        .success());
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn idle_players_are_closed_with_a_message_but_spectators_stay() {
    let (srv, _dir) = server(|c| c.idle_timeout = std::time::Duration::from_secs(1)).await;
    let mut w = Client::connect(srv.local_addr(), "watch", 60, 12, "xterm").await;
    let mut c = Client::connect(srv.local_addr(), "ann", 60, 12, "xterm").await;
    assert!(c.until(|s| header_has(s, "you are ann")).await);
    assert!(w.until(|s| header_has(s, "watching ann")).await);
    assert!(
        c.until(|s| s.contents().contains("idle too long")).await,
        "{}",
        c.screen.screen().contents()
    );
    c.until(|_| false).await;
    assert!(c.closed);
    // The spectator, silent just as long, still watches (now waiting for a player).
    assert!(w.until(|s| header_has(s, "waiting for players")).await);
    w.drain_for(std::time::Duration::from_millis(1500)).await;
    assert!(!w.closed, "a spectator who only watches is not idle-kicked");
    srv.shutdown().await;
}
