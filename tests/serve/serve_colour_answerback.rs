//! A terminal known by its answers: where `TERM` names no colours (PuTTY's plain `xterm`) and
//! `COLORTERM` says nothing, the server also sends ENQ (between two DA1 requests), and PuTTY's
//! answerback with its VT102 device attributes gets 24-bit colour. A plain `xterm` that answers
//! nothing gets 256. The fake terminals here answer each request in the order it arrives, as a
//! real terminal does (PuTTY 0.78 answers `ESC[c ENQ ESC[c` with `ESC[?6c PuTTY ESC[?6c`).

use crate::serve_support;

use russh::ChannelMsg;
use serve_support::{connect_raw, header_has, row_text, server, Client, PATIENCE};

const ENQ: u8 = 0x05;
const DA1_REQUEST: &[u8] = b"\x1b[c";
/// XTGETTCAP `RGB`, the query's first request.
const XTGETTCAP_RGB: &[u8] = b"\x1bP+q524742\x1b\\";

/// How a fake terminal answers.
#[derive(Clone, Copy, Default)]
struct Fake {
    /// Its reply to DA1 (`None`: it answers nothing at all).
    da1: Option<&'static [u8]>,
    /// Its answerback to ENQ (`None`: ENQ is ignored, like the Linux console).
    answerback: Option<&'static [u8]>,
    /// Its reply to XTGETTCAP `RGB` (`None`: not answered, like PuTTY).
    rgb: Option<&'static [u8]>,
    /// Send each reply a byte at a time, one SSH data message each.
    bytewise: bool,
    /// Wait this long before the first reply (a terminal slower than the server's patience).
    delay: Option<std::time::Duration>,
    /// Answer only the first DA1 request.
    da1_once: bool,
}

const PUTTY: Fake = Fake {
    da1: Some(b"\x1b[?6c"),
    answerback: Some(b"PuTTY"),
    rgb: None,
    bytewise: false,
    delay: None,
    da1_once: false,
};

/// What the server sent before its first frame.
struct Seen {
    /// ENQs received.
    enq: usize,
    /// DA1 requests received.
    da1: usize,
    /// Whether the colour query went out at all.
    queried: bool,
}

async fn reply(c: &Client, bytes: &[u8], fake: &mut Fake) {
    if let Some(d) = fake.delay.take() {
        tokio::time::sleep(d).await;
    }
    if fake.bytewise {
        for b in bytes {
            c.keys(std::slice::from_ref(b)).await;
        }
    } else {
        c.keys(bytes).await;
    }
}

/// Connects with `term` (and `COLORTERM` as an env request if given), answering requests as
/// `fake` does until the first header; returns the client and what was asked.
async fn connect_as(
    addr: std::net::SocketAddr,
    term: &str,
    colorterm: Option<&str>,
    mut fake: Fake,
) -> (Client, Seen) {
    let (cols, rows) = (100, 16);
    let mut handle = connect_raw(addr, None).await.expect("connect");
    assert!(handle
        .authenticate_none("ann")
        .await
        .expect("auth")
        .success());
    let channel = handle.channel_open_session().await.expect("session");
    if let Some(v) = colorterm {
        channel.set_env(true, "COLORTERM", v).await.expect("env");
    }
    channel
        .request_pty(true, term, cols, rows, 0, 0, &[])
        .await
        .expect("pty");
    channel.request_shell(true).await.expect("shell");
    let mut c = Client::new(handle, channel, cols as u16, rows as u16);
    let mut out = Vec::new();
    let mut at = 0;
    let mut seen = Seen {
        enq: 0,
        da1: 0,
        queried: false,
    };
    let deadline = tokio::time::Instant::now() + PATIENCE;
    while !header_has(c.screen.screen(), "halfcast |") {
        match tokio::time::timeout_at(deadline, c.wait()).await {
            Ok(Some(ChannelMsg::Data { data })) => {
                out.extend_from_slice(&data);
                c.screen.process(&data);
            }
            Ok(Some(_)) => continue,
            _ => panic!("no first frame: {}", String::from_utf8_lossy(&out)),
        }
        // Answer each request in order, as a terminal reads them.
        while at < out.len() {
            let rest = &out[at..];
            if rest[0] == ENQ {
                seen.enq += 1;
                if let Some(a) = fake.answerback {
                    reply(&c, a, &mut fake).await;
                }
                at += 1;
            } else if rest.starts_with(DA1_REQUEST) {
                seen.da1 += 1;
                if let Some(r) = fake.da1.filter(|_| seen.da1 == 1 || !fake.da1_once) {
                    reply(&c, r, &mut fake).await;
                }
                at += DA1_REQUEST.len();
            } else if rest.starts_with(XTGETTCAP_RGB) {
                seen.queried = true;
                if let Some(r) = fake.rgb {
                    reply(&c, r, &mut fake).await;
                }
                at += XTGETTCAP_RGB.len();
            } else if [DA1_REQUEST, XTGETTCAP_RGB]
                .iter()
                .any(|r| rest.len() < r.len() && r.starts_with(rest))
            {
                // Maybe a request cut between reads: wait for the rest.
                break;
            } else {
                at += 1;
            }
        }
    }
    (c, seen)
}

/// The header once it shows the colour level.
async fn header(c: &mut Client) -> String {
    assert!(c.until(|s| header_has(s, "colours")).await);
    row_text(c.screen.screen(), 0)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn putty_known_by_its_answerback_and_device_attributes_gets_truecolor() {
    let (srv, _dir) = server(|_| {}).await;
    let (mut c, seen) = connect_as(srv.local_addr(), "xterm", None, PUTTY).await;
    assert!(seen.queried);
    assert_eq!((seen.enq, seen.da1), (1, 2), "ENQ between two DA1 requests");
    let h = header(&mut c).await;
    assert!(h.contains("| truecolor (PuTTY) |"), "{h}");
    // Its answerback was not typed: the game still runs, the minimap still shown.
    c.drain_for(std::time::Duration::from_millis(300)).await;
    assert!(!c.closed);
    assert!(c.screen.screen().contents().contains(" map "));
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn putty_answering_a_byte_a_message_still_gets_truecolor() {
    let (srv, _dir) = server(|_| {}).await;
    let fake = Fake {
        bytewise: true,
        ..PUTTY
    };
    let (mut c, _) = connect_as(srv.local_addr(), "xterm", None, fake).await;
    let h = header(&mut c).await;
    assert!(h.contains("| truecolor (PuTTY) |"), "{h}");
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_plain_xterm_answering_nothing_gets_256() {
    let (srv, _dir) = server(|_| {}).await;
    let (mut c, seen) = connect_as(srv.local_addr(), "xterm", None, Fake::default()).await;
    assert!(seen.queried && seen.enq == 1);
    let h = header(&mut c).await;
    assert!(h.contains("| 256 (TERM) |"), "{h}");
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_changed_answerback_is_swallowed_not_typed_and_falls_back_to_the_term_rule() {
    let (srv, _dir) = server(|_| {}).await;
    // Typed, `m` would hide the minimap and `q` would quit; split into one message a byte.
    let fake = Fake {
        answerback: Some(b"mq"),
        bytewise: true,
        ..PUTTY
    };
    let (mut c, _) = connect_as(srv.local_addr(), "xterm", None, fake).await;
    let h = header(&mut c).await;
    assert!(h.contains("| 256 (TERM) |"), "{h}");
    c.drain_for(std::time::Duration::from_millis(300)).await;
    assert!(!c.closed, "the answerback quit the game");
    assert!(c.screen.screen().contents().contains(" map "));
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_real_xterm_still_says_truecolor_itself() {
    let (srv, _dir) = server(|_| {}).await;
    let fake = Fake {
        da1: Some(b"\x1b[?64;1;2;6;9;15;16;17;18;21;22;28c"),
        answerback: Some(b""),
        rgb: Some(b"\x1bP1+r524742=382f382f38\x1b\\"),
        ..PUTTY
    };
    let (mut c, _) = connect_as(srv.local_addr(), "xterm", None, fake).await;
    let h = header(&mut c).await;
    assert!(h.contains("| truecolor (terminal said so) |"), "{h}");
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_console_vt100_and_screen_keep_16() {
    let (srv, _dir) = server(|_| {}).await;
    // The Linux console answers DA1 as a VT102 and ignores ENQ; GNU screen says VT100 + AVO.
    for (term, da1) in [
        ("linux", &b"\x1b[?6c"[..]),
        ("vt100", b"\x1b[?1;2c"),
        ("screen", b"\x1b[?1;2c"),
    ] {
        let fake = Fake {
            da1: Some(da1),
            answerback: None,
            ..Fake::default()
        };
        let (mut c, seen) = connect_as(srv.local_addr(), term, None, fake).await;
        assert_eq!(seen.enq, 1, "{term}");
        let h = header(&mut c).await;
        assert!(h.contains("| 16 (TERM) |"), "{term}: {h}");
    }
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn no_enq_where_term_names_its_colours_or_colorterm_speaks() {
    let (srv, _dir) = server(|_| {}).await;
    // PuTTY set to say xterm-256color: 256 by its TERM, and no ENQ goes out.
    let (mut c, seen) = connect_as(srv.local_addr(), "xterm-256color", None, PUTTY).await;
    assert!(seen.queried);
    assert_eq!((seen.enq, seen.da1), (0, 1));
    let h = header(&mut c).await;
    assert!(h.contains("| 256 (TERM) |"), "{h}");
    let (mut c, seen) = connect_as(srv.local_addr(), "xterm", Some("truecolor"), PUTTY).await;
    assert_eq!((seen.queried, seen.enq, seen.da1), (false, 0, 0));
    let h = header(&mut c).await;
    assert!(h.contains("| truecolor (COLORTERM) |"), "{h}");
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_answerback_later_than_the_patience_is_swallowed_not_typed() {
    let (srv, _dir) = server(|_| {}).await;
    // Past the server's patience (0.5 s): the first frame goes out at the TERM guess, and the
    // answers, coming after it, are not keys: typed, `m` would hide the minimap, `q` quit.
    let fake = Fake {
        answerback: Some(b"mq"),
        delay: Some(std::time::Duration::from_millis(1500)),
        ..PUTTY
    };
    let (mut c, _) = connect_as(srv.local_addr(), "xterm", None, fake).await;
    let h = header(&mut c).await;
    assert!(h.contains("| 256 (TERM) |"), "{h}");
    c.drain_for(std::time::Duration::from_millis(500)).await;
    assert!(!c.closed, "the late answerback quit the game");
    assert!(c.screen.screen().contents().contains(" map "));
    // Keys after it are the player's again.
    c.keys(b"m").await;
    assert!(
        c.until(|s| !s.contents().contains(" map ")).await,
        "{}",
        c.screen.screen().contents()
    );
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_terminal_answering_da1_once_is_still_known_and_keys_after_are_keys() {
    let (srv, _dir) = server(|_| {}).await;
    // DA1 answered, then the answerback, then nothing for the second DA1.
    let fake = Fake {
        da1_once: true,
        ..PUTTY
    };
    let (mut c, seen) = connect_as(srv.local_addr(), "xterm", None, fake).await;
    assert_eq!(seen.da1, 2);
    let h = header(&mut c).await;
    assert!(h.contains("| truecolor (PuTTY) |"), "{h}");
    // The player's keys right after the first frame are not taken for an answerback.
    c.keys(b"m").await;
    assert!(
        c.until(|s| !s.contents().contains(" map ")).await,
        "{}",
        c.screen.screen().contents()
    );
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn putty_s_answers_sent_at_once_in_either_order_are_known() {
    let (srv, _dir) = server(|_| {}).await;
    // A client that answers the whole query at once, as soon as it starts, with ENQ's answer
    // before or after DA1's (one DA1 reply only).
    for canned in [&b"PuTTY\x1b[?6c"[..], b"\x1b[?6cPuTTY"] {
        let fake = Fake {
            da1: None,
            answerback: None,
            rgb: Some(canned),
            ..PUTTY
        };
        let (mut c, _) = connect_as(srv.local_addr(), "xterm", None, fake).await;
        let h = header(&mut c).await;
        assert!(h.contains("| truecolor (PuTTY) |"), "{canned:?}: {h}");
        c.drain_for(std::time::Duration::from_millis(300)).await;
        assert!(!c.closed);
    }
    srv.shutdown().await;
}
