//! `halfcast serve` end to end: a real russh client connects to an in-process server on a free
//! loopback port; what it receives goes through a vt100 terminal model.

mod serve_support;

use std::time::Duration;

use serve_support::{colours, half_block_cells, row_text, server, status_has, Client};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_frame_arrives_and_decodes_to_half_blocks() {
    let (srv, _dir) = server(|_| {}).await;
    let mut c = Client::connect(srv.local_addr(), "ann", 60, 20, "xterm-direct").await;
    assert!(
        c.until(|s| status_has(s, "you are ann") && half_block_cells(s) == 60 * 19)
            .await,
        "a full truecolor half-block view and the status line arrive; screen:\n{}",
        c.screen.screen().contents()
    );
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn window_change_changes_the_frame_size_and_absurd_sizes_are_clamped() {
    let (srv, _dir) = server(|_| {}).await;
    let mut c = Client::connect(srv.local_addr(), "ann", 60, 20, "xterm-direct").await;
    assert!(c.until(|s| status_has(s, "you are ann")).await);
    c.resize(40, 12).await;
    assert!(
        c.until(|s| status_has(s, "you are ann") && half_block_cells(s) == 40 * 11)
            .await,
        "after the resize the view is 40x11 plus the status line:\n{}",
        c.screen.screen().contents()
    );
    // A flood of resizes, some absurd, then a sane one: the server keeps up and draws the last.
    for i in 0..1000u32 {
        c.channel
            .window_change(i.wrapping_mul(7919), u32::MAX - i, 0, 0)
            .await
            .expect("resize");
    }
    c.resize(30, 10).await;
    assert!(
        c.until(|s| status_has(s, "you are ann") && half_block_cells(s) == 30 * 9)
            .await,
        "the last size wins:\n{}",
        c.screen.screen().contents()
    );
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn two_players_see_each_other_and_survive_garbage_and_abrupt_disconnects() {
    let (srv, _dir) = server(|_| {}).await;
    let addr = srv.local_addr();
    let mut ann = Client::connect(addr, "ann", 80, 24, "xterm-direct").await;
    assert!(ann.until(|s| status_has(s, "you are ann")).await);
    let mut bob = Client::connect(addr, "bob", 80, 24, "xterm-direct").await;
    assert!(
        ann.until(|s| status_has(s, "2 here: ann, bob")).await,
        "ann sees bob join"
    );
    assert!(
        bob.until(|s| status_has(s, "2 here: ann, bob")).await,
        "bob sees ann"
    );
    // The second player's colour (second in the palette) is on ann's screen: minimap or marker.
    assert!(
        ann.until(|s| colours(s).contains(&(64, 200, 255))).await,
        "bob is drawn on ann's screen"
    );

    // A third client sends garbage: broken escapes, invalid UTF-8, huge CSI parameters.
    let mut eve = Client::connect(addr, "eve", 80, 24, "xterm").await;
    assert!(eve.until(|s| status_has(s, "3 here")).await);
    let mut junk = Vec::new();
    let mut x: u32 = 12345;
    for i in 0..20_000u32 {
        x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
        junk.push(match i % 50 {
            0 => 0x1b,
            1 => b'[',
            _ => (x >> 16) as u8,
        });
    }
    junk.extend(b"\x1b[999999999999999999999999;99999999999999999u\x1b[?");
    for chunk in junk.chunks(333) {
        eve.keys(chunk).await;
    }
    // Then vanishes without closing anything.
    drop(eve);

    // Ann still plays: turning changes her view, and the others' departure shows.
    let before = ann.screen.screen().contents_formatted();
    for _ in 0..10 {
        ann.keys(b"d").await;
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    assert!(
        ann.until(|s| s.contents_formatted() != before).await,
        "ann's view changes when she turns"
    );
    drop(bob);
    assert!(
        ann.until(|s| status_has(s, "1 here: ann")).await,
        "abrupt disconnects leave the world:\n{}",
        row_text(ann.screen.screen(), 23)
    );
    // And the server still accepts newcomers.
    let mut cat = Client::connect(addr, "cat", 80, 10, "xterm").await;
    assert!(cat.until(|s| status_has(s, "2 here: ann, cat")).await);
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn quitting_restores_the_terminal_and_closes_the_channel() {
    let (srv, _dir) = server(|_| {}).await;
    let mut c = Client::connect(srv.local_addr(), "ann", 40, 12, "xterm-256color").await;
    assert!(
        c.until(|s| status_has(s, "you are ann") && s.alternate_screen())
            .await
    );
    c.keys(b"\x03").await;
    assert!(c.until(|s| !s.alternate_screen() && !s.hide_cursor()).await);
    c.until(|_| false).await;
    assert!(c.closed, "the server closes the channel after Ctrl-C");
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn spectators_follow_a_player_and_tab_switches() {
    let (srv, _dir) = server(|_| {}).await;
    let addr = srv.local_addr();
    let mut w = Client::connect(addr, "watch", 60, 16, "xterm-direct").await;
    assert!(w.until(|s| status_has(s, "waiting for players")).await);
    let mut ann = Client::connect(addr, "ann", 60, 16, "xterm-direct").await;
    let mut bob = Client::connect(addr, "bob", 60, 16, "xterm-direct").await;
    assert!(ann.until(|s| status_has(s, "2 here")).await);
    assert!(bob.until(|s| status_has(s, "2 here")).await);
    assert!(w.until(|s| status_has(s, "watching ann")).await);
    assert!(half_block_cells(w.screen.screen()) > 0);
    w.keys(b"\t").await;
    assert!(w.until(|s| status_has(s, "watching bob")).await);
    w.keys(b"\x1b[Z").await;
    assert!(w.until(|s| status_has(s, "watching ann")).await);
    // A spectator is not a player.
    assert!(status_has(w.screen.screen(), "2 here: ann, bob"));
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_shell_without_a_pty_request_gets_the_default_size() {
    let (srv, _dir) = server(|_| {}).await;
    let mut h = serve_support::connect_raw(srv.local_addr(), None)
        .await
        .expect("connect");
    assert!(h.authenticate_none("ann").await.expect("auth").success());
    let ch = h.channel_open_session().await.expect("session");
    ch.request_shell(true).await.expect("shell");
    let mut c = Client {
        handle: h,
        channel: ch,
        screen: vt100::Parser::new(24, 80, 0),
        bytes: 0,
        closed: false,
    };
    // No TERM: mono, plain ASCII; the status line sits on row 24 of 80x24.
    assert!(
        c.until(|s| status_has(s, "you are ann")).await,
        "{}",
        c.screen.screen().contents()
    );
    assert!(row_text(c.screen.screen(), 0).trim_end().len() > 40);
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_client_that_stops_reading_gets_frames_dropped_then_the_latest_state() {
    let (srv, _dir) = server(|_| {}).await;
    let addr = srv.local_addr();
    // A big truecolor view (about 1 MB a frame) that changes every tick: ann holds "turn right"
    // (a kitty-protocol press with no release).
    let mut ann = Client::connect(addr, "ann", 300, 100, "xterm-direct").await;
    assert!(ann.until(|s| status_has(s, "you are ann")).await);
    ann.keys(b"\x1b[?11u\x1b[100u").await;
    // Ann stops reading; bob joins meanwhile.
    tokio::time::sleep(Duration::from_secs(2)).await;
    let mut bob = Client::connect(addr, "bob", 60, 12, "xterm").await;
    assert!(bob.until(|s| status_has(s, "2 here")).await);
    tokio::time::sleep(Duration::from_secs(1)).await;
    // When ann reads again she catches up to the present rather than replaying a backlog.
    assert!(ann.until(|s| status_has(s, "2 here: ann, bob")).await);
    ann.keys(b"\x03").await;
    ann.until(|_| false).await;
    // Ann's session adds its counters as it ends: frame ticks were skipped, not queued.
    let mut dropped = 0;
    for _ in 0..200 {
        dropped = srv.stats().frames_dropped;
        if dropped > 0 {
            break;
        }
        tokio::time::sleep(Duration::from_millis(25)).await;
    }
    assert!(dropped > 0, "the stalled session skipped frames");
    drop(bob);
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_colour_key_cycles_levels_down_to_mono_and_back() {
    let (srv, _dir) = server(|_| {}).await;
    let mut c = Client::connect(srv.local_addr(), "ann", 100, 16, "xterm-direct").await;
    assert!(
        c.until(|s| status_has(s, "· truecolor ·") && half_block_cells(s) > 0)
            .await
    );
    for level in ["· 256 ·", "· 16 ·", "· mono ·", "· truecolor ·"] {
        c.keys(b"c").await;
        assert!(
            c.until(|s| status_has(s, level)).await,
            "{level}: {}",
            row_text(c.screen.screen(), 15)
        );
    }
    srv.shutdown().await;
}
