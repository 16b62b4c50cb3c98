//! Pre-authentication floods: connections that never finish logging in must not keep a real
//! player out for longer than the login grace time, nor hold their place longer than it.

use crate::serve_support;

use std::net::Ipv4Addr;
use std::time::{Duration, Instant};

use serve_support::{
    closed_within, header_has, live_becomes, server, tcp_from, try_connect, Client, PATIENCE,
};

/// The grace time the flooded servers run with (the default is 20 s; tests keep it short).
const GRACE: Duration = Duration::from_secs(2);

/// Opens `per_addr` TCP connections from each of 127.0.0.`first`..=`last`.
async fn silent_flood(
    addr: std::net::SocketAddr,
    first: u8,
    last: u8,
    per_addr: usize,
) -> Vec<tokio::net::TcpStream> {
    let mut flood = Vec::new();
    for a in first..=last {
        for _ in 0..per_addr {
            if let Ok(s) = tcp_from(Ipv4Addr::new(127, 0, 0, a), addr).await {
                flood.push(s);
            }
        }
    }
    flood
}

/// Keeps trying to get a playing session until `limit`; the client and how long it took.
async fn player_gets_in(
    addr: std::net::SocketAddr,
    limit: Duration,
) -> (Option<Client>, Duration, usize, String) {
    let start = Instant::now();
    let mut attempts = 0;
    let mut last_err = String::new();
    while start.elapsed() < limit {
        attempts += 1;
        match try_connect(addr, "ann", 60, 16).await {
            Ok(c) => return (Some(c), start.elapsed(), attempts, last_err),
            Err(e) => last_err = e,
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    (None, start.elapsed(), attempts, last_err)
}

/// What the flood's sockets saw: (closed by the server, of which were told a reason).
async fn flood_outcome(flood: &mut [tokio::net::TcpStream], within: Duration) -> (usize, usize) {
    let (mut closed, mut told) = (0, 0);
    for s in flood.iter_mut() {
        let mut got = Vec::new();
        if closed_within(s, within, &mut got).await {
            closed += 1;
        }
        if String::from_utf8_lossy(&got).starts_with("halfcast: too many connections") {
            told += 1;
        }
    }
    (closed, told)
}

/// 8 silent TCP connections from each of 4 addresses (32, the measured attack that filled
/// `--max-sessions 32` for ~600 s) while a real player keeps trying from a fifth address.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn silent_flood_from_four_addresses_keeps_no_player_out_past_the_grace_time() {
    if !serve_support::many_loopback_addresses() {
        return;
    }
    let (srv, _dir) = server(|c| {
        c.max_sessions = 32;
        c.login_grace = GRACE;
    })
    .await;
    let addr = srv.local_addr();
    let accepted_at = Instant::now();
    let mut flood = silent_flood(addr, 2, 5, 8).await;
    assert_eq!(flood.len(), 32, "the flood's TCP connections all connect");
    // Let the server take them all in (or refuse them) before the player comes.
    let deadline = Instant::now() + PATIENCE;
    while srv.stats().connections + srv.stats().refused < 32 && Instant::now() < deadline {
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    let (player, took, attempts, last_err) =
        player_gets_in(addr, GRACE * 2 + Duration::from_secs(3)).await;
    let Some(mut player) = player else {
        panic!("no way in for {took:?} under the flood ({attempts} attempts, last: {last_err})");
    };
    assert!(
        player.until(|s| header_has(s, "you are ann")).await,
        "the player gets frames"
    );
    // Every flood connection is gone by the end of the grace time (plus scheduling slack).
    let left = (GRACE + Duration::from_secs(2)).saturating_sub(accepted_at.elapsed());
    let (closed, told) = flood_outcome(&mut flood, left).await;
    assert_eq!(
        closed, 32,
        "every silent connection is closed within the grace time"
    );
    assert!(told >= 32 - 4 * 3, "{told} refused ones were told why");
    eprintln!(
        "flood 4x8 silent: player in after {:.2} s ({attempts} attempts); {told} refused at accept \
         with a reason, all 32 closed {:.1} s after connecting; server counted {} refusals",
        took.as_secs_f64(),
        accepted_at.elapsed().as_secs_f64(),
        srv.stats().refused
    );
    // The player still plays after the flood is gone.
    player.drain_for(Duration::from_millis(200)).await;
    assert!(!player.closed, "the player is not cut with the flood");
    srv.shutdown().await;
}

/// Silent connections from 5 addresses fill every logging-in place (`--max-startups 10`: all
/// refused beyond 10): a newcomer is refused and told why, and gets in once the grace time has
/// cut the flood.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_full_house_of_logging_in_connections_empties_within_the_grace_time() {
    if !serve_support::many_loopback_addresses() {
        return;
    }
    let (srv, _dir) = server(|c| {
        c.login_grace = GRACE;
        c.max_startups = "10".parse().expect("startups");
    })
    .await;
    let addr = srv.local_addr();
    let flooded_at = Instant::now();
    let mut flood = silent_flood(addr, 10, 14, 3).await;
    assert!(live_becomes(&srv, (10, 0)).await, "{:?}", srv.live());
    // A real client is turned away with the reason while the house is full...
    let mut s = tcp_from(Ipv4Addr::new(127, 0, 0, 101), addr)
        .await
        .expect("tcp");
    let mut got = Vec::new();
    assert!(closed_within(&mut s, Duration::from_secs(1), &mut got).await);
    assert_eq!(
        got,
        halfcast::serve::server::refusal_bytes(&halfcast::serve::limits::Refusal::TooManyStartups),
        "the reason line, a version line and a disconnect packet"
    );
    // ...and gets in within the grace time of the flood's start.
    let (player, took, attempts, last_err) = player_gets_in(addr, GRACE * 3).await;
    let Some(mut player) = player else {
        panic!("no way in for {took:?} ({attempts} attempts, last: {last_err})");
    };
    assert!(player.until(|s| header_has(s, "you are ann")).await);
    let waited = flooded_at.elapsed();
    assert!(
        waited < GRACE + Duration::from_secs(3),
        "in after {waited:?}, the grace time is {GRACE:?}"
    );
    let (closed, _) = flood_outcome(&mut flood, Duration::from_secs(2)).await;
    eprintln!(
        "flood 5 addresses x 3 ({} opened, 10 logging-in places): newcomer refused with the reason, \
         player in {:.2} s after the flood began ({attempts} attempts); {closed} of {} flood sockets closed",
        flood.len(),
        waited.as_secs_f64(),
        flood.len()
    );
    assert_eq!(closed, flood.len());
    srv.shutdown().await;
}

/// A client dripping its version line one byte at a time is cut at the grace time, not after
/// the 600 s idle timeout (each byte resets russh's own inactivity timer).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_drip_fed_handshake_is_cut_at_the_grace_time() {
    if !serve_support::many_loopback_addresses() {
        return;
    }
    use tokio::io::AsyncWriteExt;
    let (srv, _dir) = server(|c| c.login_grace = GRACE).await;
    let addr = srv.local_addr();
    let start = Instant::now();
    let mut drips = Vec::new();
    for a in 2..=4u8 {
        drips.push(
            tcp_from(Ipv4Addr::new(127, 0, 0, a), addr)
                .await
                .expect("tcp"),
        );
    }
    let line = b"SSH-2.0-drip_drip_drip_drip_drip_drip_drip_drip_drip_drip\r\n";
    let mut cut = [None; 3];
    'drip: for (i, byte) in line.iter().enumerate() {
        for (k, s) in drips.iter_mut().enumerate() {
            if cut[k].is_none() && s.write_all(&[*byte]).await.is_err() {
                cut[k] = Some(start.elapsed());
            }
        }
        if cut.iter().all(Option::is_some) || start.elapsed() > GRACE * 3 {
            break 'drip;
        }
        // One byte every 100 ms: the line would take 6 s.
        let _ = i;
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    for (k, s) in drips.iter_mut().enumerate() {
        if cut[k].is_none() {
            let mut got = Vec::new();
            if closed_within(s, GRACE, &mut got).await {
                cut[k] = Some(start.elapsed());
            }
        }
    }
    eprintln!("drip: cut after {cut:?} (grace {GRACE:?})");
    for c in cut {
        let c = c.expect("every drip connection is cut");
        assert!(
            c >= GRACE - Duration::from_millis(200) && c < GRACE + Duration::from_secs(2),
            "cut after {c:?}"
        );
    }
    srv.shutdown().await;
}

/// A client that logs in but never asks for a shell (it holds a logging-in place past the key
/// exchange and authentication) is disconnected at the grace time, and its place is free again.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_client_that_logs_in_but_never_plays_is_cut_at_the_grace_time() {
    let (srv, _dir) = server(|c| {
        c.login_grace = GRACE;
        c.max_startups = "1".parse().expect("startups");
    })
    .await;
    let addr = srv.local_addr();
    let start = Instant::now();
    let mut h = serve_support::connect_raw(addr, None)
        .await
        .expect("connect");
    assert!(h.authenticate_none("lurker").await.expect("auth").success());
    let _ch = h.channel_open_session().await.expect("session");
    // The one logging-in place is taken: a newcomer is refused meanwhile.
    assert!(try_connect(addr, "ann", 40, 12).await.is_err());
    while !h.is_closed() && start.elapsed() < GRACE * 3 {
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    let cut = start.elapsed();
    eprintln!(
        "logged in, never played: closed after {:.2} s",
        cut.as_secs_f64()
    );
    assert!(h.is_closed(), "closed by the server");
    assert!(
        cut >= GRACE - Duration::from_millis(200) && cut < GRACE + Duration::from_secs(2),
        "{cut:?}"
    );
    let (player, took, attempts, last_err) = player_gets_in(addr, GRACE).await;
    let mut player = player.unwrap_or_else(|| panic!("{took:?} {attempts} {last_err}"));
    assert!(player.until(|s| header_has(s, "you are ann")).await);
    srv.shutdown().await;
}
