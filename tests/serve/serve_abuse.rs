//! Abuse of a logged-in session and of the protocol: garbage and escape floods, resize storms,
//! absurd window sizes, more than 130 pty modes, an all-zero Curve25519 key. Each bounded in
//! time, on loopback; each asserts what the server does, and that it still serves afterwards.

use crate::serve_support;

use std::time::{Duration, Instant};

use russh::{ChannelMsg, Pty};
use serve_support::{header_has, server, Client, PATIENCE};
use tokio::io::{AsyncReadExt, AsyncWriteExt};

/// Counts the frames (data messages) a client receives over `d`, turning all along so that
/// every frame differs.
async fn frames_while_turning(c: &mut Client, d: Duration) -> usize {
    let end = Instant::now() + d;
    let mut frames = 0;
    let mut next_key = Instant::now();
    while Instant::now() < end {
        if Instant::now() >= next_key {
            c.keys(b"d").await;
            next_key = Instant::now() + Duration::from_millis(40);
        }
        if let Ok(Some(ChannelMsg::Data { data })) =
            tokio::time::timeout(Duration::from_millis(20), c.wait()).await
        {
            c.bytes += data.len();
            c.screen.process(&data);
            frames += 1;
        }
    }
    frames
}

/// One session floods garbage, unfinished escape sequences and 1 000 window changes a second
/// for 3 s; another session keeps getting frames, and the flooder's own session survives.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn garbage_escape_and_resize_storms_do_not_starve_another_session() {
    let (srv, _dir) = server(|_| {}).await;
    let addr = srv.local_addr();
    let mut victim = Client::connect(addr, "calm", 60, 16, "xterm-256color").await;
    assert!(victim.until(|s| header_has(s, "you are calm")).await);
    let calm = frames_while_turning(&mut victim, Duration::from_secs(2)).await;
    let flooder = Client::connect(addr, "storm", 80, 24, "xterm").await;
    let storm = tokio::spawn(async move {
        // Random bytes, but none that quits (q, Esc, control bytes): the flood must hit a
        // live session for 3 s, not end it.
        let mut garbage = Vec::with_capacity(32 * 1024);
        let mut x: u32 = 12345;
        while garbage.len() < 32 * 1024 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let b = x as u8;
            if b >= 0x80 || (b.is_ascii_lowercase() && b != b'q') {
                garbage.push(b);
            }
        }
        // Escape sequences that never end (each overruns the parser's 64-byte bound).
        let mut unit = b"\x1b[".to_vec();
        unit.extend(b"9;".repeat(40));
        let escapes = unit.repeat(32 * 1024 / unit.len());
        let end = Instant::now() + Duration::from_secs(3);
        let (mut sent, mut resizes, mut n) = (0usize, 0usize, 0u32);
        let mut next_resize = Instant::now();
        while Instant::now() < end {
            let chunk = if n % 2 == 0 {
                &garbage[..]
            } else {
                &escapes[..]
            };
            n += 1;
            if tokio::time::timeout(Duration::from_millis(100), flooder.channel.data(chunk))
                .await
                .is_ok_and(|r| r.is_ok())
            {
                sent += chunk.len();
            }
            // 1 000 window changes a second, sizes all over (including absurd ones).
            while next_resize <= Instant::now() {
                let (c, r) = (20 + (resizes % 400) as u32, 5 + (resizes % 90) as u32);
                let change = flooder.channel.window_change(c, r, 0, 0);
                let _ = tokio::time::timeout(Duration::from_millis(100), change).await;
                resizes += 1;
                next_resize += Duration::from_millis(1);
            }
        }
        (flooder, sent, resizes)
    });
    let stormy = frames_while_turning(&mut victim, Duration::from_secs(3)).await;
    let (mut flooder, sent, resizes) = storm.await.expect("storm");
    eprintln!(
        "storm: {:.1} MB of garbage/escapes and {resizes} window changes in 3 s; the other \
         session got {calm} frames in 2 s calm, {stormy} in 3 s of storm",
        sent as f64 / 1e6
    );
    assert!(sent > 1_000_000, "the flood got through ({sent} bytes)");
    assert!(resizes > 1_000, "{resizes} window changes");
    // A liveness bound, not a speed measure: the other session was not starved.
    assert!(
        stormy * 4 >= calm,
        "the other session got {stormy} frames during the storm, {calm} in 2 s before it"
    );
    assert!(!victim.closed);
    // The flooder's session is still the game, at its last size.
    flooder.resize(70, 20).await;
    assert!(flooder.until(|s| header_has(s, "you are storm")).await);
    srv.shutdown().await;
}

/// A client claiming a terminal of 100 000 × 70 000 cells gets the bounds, and the header says
/// so; a later sane size clears the note.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn absurd_window_sizes_are_clamped_and_the_header_says_so() {
    let (srv, _dir) = server(|_| {}).await;
    let mut c = Client::connect(srv.local_addr(), "big", 60, 16, "xterm").await;
    assert!(c.until(|s| header_has(s, "you are big")).await);
    c.channel
        .window_change(100_000, 70_000, 0, 0)
        .await
        .expect("window change");
    c.screen.set_size(200, 500);
    assert!(
        c.until(|s| header_has(s, "clamped to 500x200")).await,
        "{}",
        serve_support::row_text(c.screen.screen(), 0)
    );
    c.resize(60, 16).await;
    assert!(
        c.until(|s| !header_has(s, "clamped") && header_has(s, "you are big"))
            .await
    );
    srv.shutdown().await;
}

/// A pty request with 200 terminal modes (russh < 0.62.4 panicked beyond 130; 0.65 refuses
/// the request as inconsistent and drops the connection) ends that connection cleanly, and the
/// server serves the next client.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_pty_request_with_more_than_130_modes_is_handled() {
    let (srv, _dir) = server(|_| {}).await;
    let mut h = serve_support::connect_raw(srv.local_addr(), None)
        .await
        .expect("connect");
    assert!(h.authenticate_none("modes").await.expect("auth").success());
    let mut ch = h.channel_open_session().await.expect("session");
    let modes: Vec<(Pty, u32)> = (0..200u32).map(|i| (Pty::VINTR, i)).collect();
    ch.request_pty(true, "xterm", 60, 16, 0, 0, &modes)
        .await
        .expect("pty");
    let deadline = tokio::time::Instant::now() + PATIENCE;
    let mut answer = None;
    while let Ok(Some(msg)) = tokio::time::timeout_at(deadline, ch.wait()).await {
        if matches!(msg, ChannelMsg::Success | ChannelMsg::Failure) {
            answer = Some(msg);
            break;
        }
    }
    // Give the client's side a moment to see the close, if that is the answer.
    for _ in 0..50 {
        if answer.is_some() || h.is_closed() {
            break;
        }
        tokio::time::sleep(std::time::Duration::from_millis(20)).await;
    }
    eprintln!(
        "200 pty modes: answer {answer:?}, connection closed: {}",
        h.is_closed()
    );
    assert!(
        answer.is_some() || h.is_closed(),
        "the pty request is answered or its connection closed, not left hanging"
    );
    drop(ch);
    let mut c = Client::connect(srv.local_addr(), "after", 60, 16, "xterm").await;
    assert!(c.until(|s| header_has(s, "you are after")).await);
    srv.shutdown().await;
}

/// An SSH binary packet, unencrypted (before the first NEWKEYS): length, padding length,
/// payload, at least 4 bytes of padding to a multiple of 8.
fn packet(payload: &[u8]) -> Vec<u8> {
    let mut pad = 8 - (5 + payload.len()) % 8;
    if pad < 4 {
        pad += 8;
    }
    let len = u32::try_from(1 + payload.len() + pad).expect("len");
    let mut p = len.to_be_bytes().to_vec();
    p.push(u8::try_from(pad).expect("pad"));
    p.extend_from_slice(payload);
    p.extend(std::iter::repeat_n(0u8, pad));
    p
}

fn name_list(out: &mut Vec<u8>, s: &str) {
    out.extend_from_slice(&u32::try_from(s.len()).expect("len").to_be_bytes());
    out.extend_from_slice(s.as_bytes());
}

/// Reads one unencrypted packet's payload.
async fn read_packet(s: &mut tokio::net::TcpStream) -> Option<Vec<u8>> {
    let mut len = [0u8; 4];
    s.read_exact(&mut len).await.ok()?;
    let len = u32::from_be_bytes(len) as usize;
    if len > 64 * 1024 {
        return None;
    }
    let mut rest = vec![0u8; len];
    s.read_exact(&mut rest).await.ok()?;
    let pad = usize::from(*rest.first()?);
    rest.get(1..len.checked_sub(pad)?).map(<[u8]>::to_vec)
}

/// A key exchange offering an all-zero Curve25519 public key (russh < 0.62.4 could panic on
/// it) gets no key exchange reply: the server refuses it and keeps serving.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_all_zero_curve25519_key_is_refused() {
    let (srv, _dir) = server(|_| {}).await;
    let addr = srv.local_addr();
    let mut s = tokio::net::TcpStream::connect(addr).await.expect("tcp");
    s.write_all(b"SSH-2.0-zerokey_test\r\n").await.expect("id");
    // The server's version line, then its KEXINIT.
    let mut line = Vec::new();
    let mut b = [0u8; 1];
    while !line.ends_with(b"\n") {
        s.read_exact(&mut b).await.expect("server id");
        line.push(b[0]);
    }
    assert!(line.starts_with(b"SSH-2.0-"), "{line:?}");
    let kexinit = read_packet(&mut s).await.expect("server KEXINIT");
    assert_eq!(kexinit[0], 20);
    let mut ours = vec![20u8];
    ours.extend_from_slice(&[7u8; 16]);
    for l in [
        "curve25519-sha256",
        "ssh-ed25519",
        "chacha20-poly1305@openssh.com",
        "chacha20-poly1305@openssh.com",
        "hmac-sha2-256",
        "hmac-sha2-256",
        "none",
        "none",
        "",
        "",
    ] {
        name_list(&mut ours, l);
    }
    ours.push(0);
    ours.extend_from_slice(&0u32.to_be_bytes());
    s.write_all(&packet(&ours)).await.expect("KEXINIT");
    let mut ecdh = vec![30u8];
    name_list(&mut ecdh, &String::from_utf8(vec![0u8; 32]).expect("zeros"));
    s.write_all(&packet(&ecdh)).await.expect("ECDH_INIT");
    // Whatever comes back before the close must not be a key exchange reply (31).
    let mut replies = Vec::new();
    let _ = tokio::time::timeout(PATIENCE, async {
        while let Some(p) = read_packet(&mut s).await {
            replies.push(p[0]);
        }
    })
    .await;
    eprintln!("all-zero Curve25519 key: server sent message types {replies:?}, then closed");
    assert!(
        !replies.contains(&31),
        "no KEX_ECDH_REPLY to a zero key: {replies:?}"
    );
    let mut c = Client::connect(addr, "after", 60, 16, "xterm").await;
    assert!(c.until(|s| header_has(s, "you are after")).await);
    srv.shutdown().await;
}
