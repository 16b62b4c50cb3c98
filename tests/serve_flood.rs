//! Pre-authentication floods: connections that never finish logging in must not keep a real
//! player out for longer than the login grace time.

mod serve_support;

use std::net::Ipv4Addr;
use std::time::{Duration, Instant};

use serve_support::{header_has, server, tcp_from, try_connect};

/// The grace time the flooded server runs with (the default is 20 s; tests keep it short).
const GRACE: Duration = Duration::from_secs(2);

/// 8 silent TCP connections from each of 4 addresses (32, the measured attack on
/// `--max-sessions 32`) while a real player keeps trying to get in from a fifth address.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn silent_flood_from_four_addresses_keeps_no_player_out_past_the_grace_time() {
    let (srv, _dir) = server(|c| {
        c.max_sessions = 32;
        c.login_grace = GRACE;
    })
    .await;
    let addr = srv.local_addr();
    let mut flood = Vec::new();
    for a in 2..=5u8 {
        for _ in 0..8 {
            if let Ok(s) = tcp_from(Ipv4Addr::new(127, 0, 0, a), addr).await {
                flood.push(s);
            }
        }
    }
    assert_eq!(flood.len(), 32, "the flood's TCP connections all connect");
    // Let the server take them all in before the player comes.
    tokio::time::sleep(Duration::from_millis(300)).await;
    let start = Instant::now();
    let limit = GRACE * 2 + Duration::from_secs(3);
    let mut attempts = 0;
    let mut last_err = String::new();
    let mut player = None;
    while start.elapsed() < limit {
        attempts += 1;
        match try_connect(addr, "ann", 60, 16).await {
            Ok(c) => {
                player = Some(c);
                break;
            }
            Err(e) => last_err = e,
        }
        tokio::time::sleep(Duration::from_millis(250)).await;
    }
    let Some(mut player) = player else {
        panic!(
            "no way in for {:.1} s under the flood ({attempts} attempts, last: {last_err})",
            start.elapsed().as_secs_f64()
        );
    };
    assert!(
        player.until(|s| header_has(s, "you are ann")).await,
        "the player gets frames"
    );
    eprintln!(
        "flood: 32 silent connections from 4 addresses; player in after {:.2} s ({attempts} attempts), {} refused at accept",
        start.elapsed().as_secs_f64(),
        srv.stats().refused
    );
    drop(flood);
    srv.shutdown().await;
}
