//! Authentication under attack: at most 6 tries per connection, a delay that grows per source
//! address, and `--authorized-keys` letting in listed keys only.

use crate::serve_support;

use std::net::Ipv4Addr;
use std::sync::Arc;
use std::time::{Duration, Instant};

use halfcast::serve::auth::AuthMode;
use russh::keys::ssh_key::private::Ed25519Keypair;
use russh::keys::{PrivateKey, PrivateKeyWithHashAlg};
use serve_support::{server, tcp_from, Trusting};

/// A russh client connected from the loopback address `from`.
async fn connect_from(
    from: Ipv4Addr,
    addr: std::net::SocketAddr,
) -> russh::client::Handle<Trusting> {
    let s = tcp_from(from, addr).await.expect("tcp");
    russh::client::connect_stream(Arc::new(russh::client::Config::default()), s, Trusting)
        .await
        .expect("ssh")
}

/// Wrong passwords until the server hangs up; how long each rejection took (a request answered
/// by the server closing the connection is not a try).
async fn guess_until_cut(h: &mut russh::client::Handle<Trusting>, max: usize) -> Vec<Duration> {
    let mut took = Vec::new();
    for i in 0..max {
        let t = Instant::now();
        let r = h.authenticate_password("ann", format!("guess{i}")).await;
        let elapsed = t.elapsed();
        tokio::time::sleep(Duration::from_millis(50)).await;
        match r {
            Ok(r) if !r.success() && !h.is_closed() => took.push(elapsed),
            _ => break,
        }
    }
    took
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn six_password_tries_per_connection_with_a_delay_growing_per_address() {
    if !serve_support::many_loopback_addresses() {
        return;
    }
    let (srv, _dir) = server(|c| c.auth = AuthMode::Password("sesame".into())).await;
    let addr = srv.local_addr();
    let mut h = connect_from(Ipv4Addr::new(127, 0, 0, 7), addr).await;
    let took = guess_until_cut(&mut h, 10).await;
    eprintln!("password guesses from one address: rejections took {took:?}, then the connection was closed");
    assert_eq!(
        took.len(),
        6,
        "6 tries, then the connection is closed: {took:?}"
    );
    assert!(
        took[5] >= took[0] + Duration::from_secs(2),
        "the delay grows with each failure: {took:?}"
    );
    // Another address starts with no penalty; the same address goes on where it left off.
    let mut other = connect_from(Ipv4Addr::new(127, 0, 0, 8), addr).await;
    let fresh = guess_until_cut(&mut other, 1).await;
    let mut again = connect_from(Ipv4Addr::new(127, 0, 0, 7), addr).await;
    let penalised = guess_until_cut(&mut again, 1).await;
    eprintln!("first guess: from a new address {fresh:?}, from the guessing one {penalised:?}");
    assert!(
        penalised[0] >= fresh[0] + Duration::from_secs(3),
        "{penalised:?} vs {fresh:?}"
    );
    // The right password still gets in: only failures wait.
    let ok = again
        .authenticate_password("ann", "sesame")
        .await
        .expect("auth");
    assert!(ok.success());
    srv.shutdown().await;
}

fn key(seed: u8) -> PrivateKey {
    PrivateKey::from(Ed25519Keypair::from_seed(&[seed; 32]))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn authorized_keys_let_in_listed_keys_only() {
    let listed = key(1);
    let dir = tempfile::tempdir().expect("tempdir");
    let ak = dir.path().join("authorized_keys");
    std::fs::write(
        &ak,
        format!("{}\n", listed.public_key().to_openssh().expect("openssh")),
    )
    .expect("write");
    let mode = AuthMode::from_authorized_keys(&ak).expect("read keys");
    let (srv, _d) = server(|c| c.auth = mode).await;
    let addr = srv.local_addr();
    let mut h = serve_support::connect_raw(addr, None)
        .await
        .expect("connect");
    assert!(!h.authenticate_none("ann").await.expect("none").success());
    assert!(!h
        .authenticate_password("ann", "anything")
        .await
        .expect("password")
        .success());
    let stranger = PrivateKeyWithHashAlg::new(Arc::new(key(2)), None);
    assert!(
        !h.authenticate_publickey("ann", stranger)
            .await
            .expect("key")
            .success(),
        "an unlisted key is refused"
    );
    let mine = PrivateKeyWithHashAlg::new(Arc::new(listed), None);
    assert!(
        h.authenticate_publickey("ann", mine)
            .await
            .expect("key")
            .success(),
        "the listed key gets in"
    );
    srv.shutdown().await;
}
