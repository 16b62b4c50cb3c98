//! Over SSH, the colour level is decided before the first frame: `COLORTERM` from the client's
//! env request first, else the client's terminal is asked (XTGETTCAP / DECRQSS, DA1 as the end
//! marker), else the `TERM` rule. The header says which, through a real russh client.

use crate::serve_support;

use russh::ChannelMsg;
use serve_support::{connect_raw, header_has, row_text, server, Client, PATIENCE};

/// The query's first bytes (XTGETTCAP `RGB`), as the server sends them.
const QUERY_START: &[u8] = b"\x1bP+q524742\x1b\\";

fn contains(hay: &[u8], needle: &[u8]) -> bool {
    hay.windows(needle.len()).any(|w| w == needle)
}

/// Connects as `user` with `TERM=xterm-256color` (and `COLORTERM` as an env request if
/// given); when the server's query arrives, answers with `answer` (nothing if `None`).
/// Returns the client and whether the query was seen before the first frame's header.
async fn connect_answering(
    addr: std::net::SocketAddr,
    colorterm: Option<&str>,
    answer: Option<&[u8]>,
) -> (Client, bool) {
    let (cols, rows) = (100, 16);
    let mut handle = connect_raw(addr, None).await.expect("connect");
    assert!(handle
        .authenticate_none("ada")
        .await
        .expect("auth")
        .success());
    let channel = handle.channel_open_session().await.expect("session");
    if let Some(v) = colorterm {
        channel.set_env(true, "COLORTERM", v).await.expect("env");
    }
    channel
        .request_pty(true, "xterm-256color", cols, rows, 0, 0, &[])
        .await
        .expect("pty");
    channel.request_shell(true).await.expect("shell");
    let mut c = Client::new(handle, channel, cols as u16, rows as u16);
    let mut seen = Vec::new();
    let mut queried = false;
    let deadline = tokio::time::Instant::now() + PATIENCE;
    // Until the first header: answer the query (once) the moment it arrives.
    while !header_has(c.screen.screen(), "halfcast |") {
        match tokio::time::timeout_at(deadline, c.wait()).await {
            Ok(Some(ChannelMsg::Data { data })) => {
                seen.extend_from_slice(&data);
                c.screen.process(&data);
                if !queried && contains(&seen, QUERY_START) {
                    queried = true;
                    if let Some(a) = answer {
                        c.keys(a).await;
                    }
                }
            }
            Ok(Some(_)) => {}
            _ => panic!("no first frame: {}", String::from_utf8_lossy(&seen)),
        }
    }
    (c, queried)
}

async fn header_after(colorterm: Option<&str>, answer: Option<&[u8]>) -> (String, bool) {
    let (srv, _dir) = server(|_| {}).await;
    let (mut c, queried) = connect_answering(srv.local_addr(), colorterm, answer).await;
    assert!(c.until(|s| header_has(s, "colours")).await);
    let header = row_text(c.screen.screen(), 0);
    srv.shutdown().await;
    (header, queried)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_terminal_answering_xtgettcap_rgb_gets_truecolor() {
    let (h, queried) = header_after(
        None,
        Some(b"\x1bP1+r524742\x1b\\\x1bP0+r5463\x1b\\\x1b[?62;22c"),
    )
    .await;
    assert!(queried);
    assert!(h.contains("| truecolor (terminal said so) |"), "{h}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_terminal_reporting_the_24_bit_sgr_back_gets_truecolor() {
    let (h, _) = header_after(None, Some(b"\x1bP1$r0;48:2::1:2:3m\x1b\\\x1b[?62c")).await;
    assert!(h.contains("| truecolor (terminal said so) |"), "{h}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_terminal_answering_only_da1_keeps_the_term_rule() {
    // tmux 3.3 answers neither query, only the device attributes.
    let (h, queried) = header_after(None, Some(b"\x1b[?1;2c")).await;
    assert!(queried);
    assert!(h.contains("| 256 (TERM) |"), "{h}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_terminal_answering_nothing_still_gets_its_first_frame() {
    let (h, queried) = header_after(None, None).await;
    assert!(queried);
    assert!(h.contains("| 256 (TERM) |"), "{h}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn colorterm_from_the_env_request_wins_without_asking() {
    let (h, queried) = header_after(Some("truecolor"), None).await;
    assert!(!queried, "no query when COLORTERM already said");
    assert!(h.contains("| truecolor (COLORTERM) |"), "{h}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn keys_typed_before_the_answer_are_kept() {
    let (srv, _dir) = server(|_| {}).await;
    // The player pressed M (hide the minimap) just before the terminal's DA1 reply.
    let (mut c, queried) = connect_answering(srv.local_addr(), None, Some(b"m\x1b[?1;2c")).await;
    assert!(queried);
    assert!(
        c.until(|s| s.contents().contains(" ray ") && !s.contents().contains(" map "))
            .await,
        "{}",
        c.screen.screen().contents()
    );
    srv.shutdown().await;
}
