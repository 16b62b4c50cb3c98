//! `halfcast serve` end to end: a real russh client connects to an in-process server on a free
//! loopback port; what it receives goes through a vt100 terminal model.

use crate::serve_support;

use std::time::Duration;

use serve_support::{
    colours, connect_tapped, full_view, half_block_cells, header_has, row_text, server, status_has,
    view_rect, Client, TapMode,
};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_frame_arrives_and_decodes_to_the_tui_layout() {
    let (srv, _dir) = server(|_| {}).await;
    let mut c = Client::connect(srv.local_addr(), "ann", 120, 40, "xterm-direct").await;
    assert!(
        c.until(|s| header_has(s, "you are ann") && full_view(s, 120, 40) && status_has(s, "help"))
            .await,
        "the header, a full truecolor half-block view and the status line arrive; screen:\n{}",
        c.screen.screen().contents()
    );
    // The local TUI's side panes: the minimap and the debugger's pane of the centre ray.
    let text = c.screen.screen().contents();
    for needle in [" map ", " ray ", "column", "hit (15,0)", "perp = sideDistY"] {
        assert!(text.contains(needle), "{needle:?} in:\n{text}");
    }
    let v = view_rect(120, 40);
    assert_eq!((v.x, v.y), (0, 1), "the view sits under the header");
    assert!(v.width < 120, "the side panes take the right-hand side");
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn window_change_changes_the_frame_size_and_absurd_sizes_are_clamped() {
    let (srv, _dir) = server(|_| {}).await;
    let mut c = Client::connect(srv.local_addr(), "ann", 60, 20, "xterm-direct").await;
    assert!(
        c.until(|s| header_has(s, "you are ann") && full_view(s, 60, 20))
            .await
    );
    c.resize(40, 12).await;
    assert!(
        c.until(|s| header_has(s, "you are ann") && full_view(s, 40, 12))
            .await,
        "after the resize the view fills 40x12 under the header:\n{}",
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
        c.until(|s| header_has(s, "you are ann") && full_view(s, 30, 10))
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
    let mut ann = Client::connect(addr, "ann", 120, 40, "xterm-direct").await;
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    let mut bob = Client::connect(addr, "bob", 120, 40, "xterm-direct").await;
    assert!(
        ann.until(|s| header_has(s, "2 here: ann, bob")).await,
        "ann sees bob join"
    );
    assert!(
        bob.until(|s| header_has(s, "2 here: ann, bob")).await,
        "bob sees ann"
    );
    // Each sees the other's name on the minimap, in the other's colour (second in the palette
    // for bob, first for ann); the sprites themselves are checked pixel by pixel in
    // `serve::screen`'s tests.
    assert!(
        ann.until(|s| s.contents().contains("●bob") && colours(s).contains(&(64, 200, 255)))
            .await,
        "bob is on ann's minimap:\n{}",
        ann.screen.screen().contents()
    );
    assert!(
        bob.until(|s| s.contents().contains("●ann") && colours(s).contains(&(255, 64, 64)))
            .await,
        "ann is on bob's minimap"
    );

    // A third client sends garbage: broken escapes, invalid UTF-8, huge CSI parameters.
    let mut eve = Client::connect(addr, "eve", 80, 24, "xterm").await;
    assert!(eve.until(|s| header_has(s, "3 here")).await);
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
        ann.until(|s| header_has(s, "1 here: ann")).await,
        "abrupt disconnects leave the world:\n{}",
        row_text(ann.screen.screen(), 0)
    );
    // And the server still accepts newcomers.
    let mut cat = Client::connect(addr, "cat", 80, 10, "xterm").await;
    assert!(cat.until(|s| header_has(s, "2 here: ann, cat")).await);
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn quitting_restores_the_terminal_and_closes_the_channel() {
    let (srv, _dir) = server(|_| {}).await;
    let mut c = Client::connect(srv.local_addr(), "ann", 40, 12, "xterm-256color").await;
    assert!(
        c.until(|s| header_has(s, "you are ann") && s.alternate_screen())
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
    let mut w = Client::connect(addr, "watch", 120, 40, "xterm-direct").await;
    assert!(w.until(|s| header_has(s, "waiting for players")).await);
    let mut ann = Client::connect(addr, "ann", 60, 16, "xterm-direct").await;
    let mut bob = Client::connect(addr, "bob", 60, 16, "xterm-direct").await;
    assert!(ann.until(|s| header_has(s, "2 here")).await);
    assert!(bob.until(|s| header_has(s, "2 here")).await);
    // The followed player's view, minimap and debug pane, at the spectator's own size.
    assert!(
        w.until(|s| header_has(s, "watching ann")
            && full_view(s, 120, 40)
            && s.contents().contains("rayDir")
            && s.contents().contains("●bob"))
            .await,
        "{}",
        w.screen.screen().contents()
    );
    w.keys(b"\t").await;
    assert!(
        w.until(|s| header_has(s, "watching bob") && s.contents().contains("●ann"))
            .await
    );
    w.keys(b"\x1b[Z").await;
    assert!(w.until(|s| header_has(s, "watching ann")).await);
    // A spectator is not a player.
    assert!(header_has(w.screen.screen(), "2 here: ann, bob"));
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
    let mut c = Client::new(h, ch, 80, 24);
    // No TERM: mono, plain ASCII at the default 80x24: header on top, status line at the bottom.
    assert!(
        c.until(|s| header_has(s, "you are ann") && status_has(s, "help"))
            .await,
        "{}",
        c.screen.screen().contents()
    );
    assert!(row_text(c.screen.screen(), 1).trim_end().len() > 40);
    assert!(row_text(c.screen.screen(), 1).is_ascii());
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_client_that_stops_reading_gets_frames_dropped_then_the_latest_state() {
    let (srv, _dir) = server(|_| {}).await;
    let addr = srv.local_addr();
    // A big truecolor view (about 1 MB a frame) that changes every tick: ann holds "turn right"
    // (a kitty-protocol press with no release).
    let (mut ann, tap) = connect_tapped(addr, "ann", "xterm-direct", 300, 100)
        .await
        .expect("connect");
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    ann.keys(b"\x1b[?11u\x1b[100u").await;
    tap.set(TapMode::Stalled);
    // Ann stops reading (her terminal keeps sending the held key's repeats); bob joins meanwhile.
    for _ in 0..10 {
        tokio::time::sleep(Duration::from_millis(200)).await;
        // Bounded: a client that does not read may stop taking what it sends, too.
        let _ = tokio::time::timeout(Duration::from_millis(50), ann.keys(b"\x1b[100;1:2u")).await;
    }
    let mut bob = Client::connect(addr, "bob", 60, 12, "xterm").await;
    assert!(bob.until(|s| header_has(s, "2 here")).await);
    for _ in 0..5 {
        tokio::time::sleep(Duration::from_millis(200)).await;
        // Bounded: a client that does not read may stop taking what it sends, too.
        let _ = tokio::time::timeout(Duration::from_millis(50), ann.keys(b"\x1b[100;1:2u")).await;
    }
    tap.set(TapMode::Open);
    // When ann reads again she catches up to the present rather than replaying a backlog.
    assert!(ann.until(|s| header_has(s, "2 here: ann, bob")).await);
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
        c.until(|s| header_has(s, "| truecolor (TERM) |")
            && half_block_cells(s, view_rect(100, 16)) > 0)
            .await
    );
    for level in [
        "| 256 (O key) |",
        "| 16 (O key) |",
        "| mono (O key) |",
        "| truecolor (O key) |",
    ] {
        c.keys(b"o").await;
        assert!(
            c.until(|s| header_has(s, level)).await,
            "{level}: {}",
            row_text(c.screen.screen(), 0)
        );
    }
    srv.shutdown().await;
}

/// The cells of the view as (glyph, fg, bg) text, to compare two moments of one client.
fn view_cells(s: &vt100::Screen, cols: u16, rows: u16) -> Vec<String> {
    let v = view_rect(cols, rows);
    let mut out = Vec::new();
    for r in v.top()..v.bottom() {
        for c in v.left()..v.right() {
            let cell = s.cell(r, c).expect("cell");
            out.push(format!(
                "{}{:?}{:?}",
                cell.contents(),
                cell.fgcolor(),
                cell.bgcolor()
            ));
        }
    }
    out
}

/// Reads until the view stops changing for a moment, then returns it.
async fn settled_view(c: &mut Client, cols: u16, rows: u16) -> Vec<String> {
    let mut last = view_cells(c.screen.screen(), cols, rows);
    for _ in 0..40 {
        c.drain_for(Duration::from_millis(250)).await;
        let now = view_cells(c.screen.screen(), cols, rows);
        if now == last {
            return now;
        }
        last = now;
    }
    last
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_player_in_view_is_drawn_as_a_sprite_and_vanishes_on_leaving() {
    let (srv, _dir) = server(|_| {}).await;
    let addr = srv.local_addr();
    let (cols, rows) = (80, 24);
    let mut ann = Client::connect(addr, "ann", cols, rows, "xterm-direct").await;
    assert!(ann.until(|s| header_has(s, "you are ann")).await);
    let bob = Client::connect(addr, "bob", cols, rows, "xterm-direct").await;
    assert!(ann.until(|s| header_has(s, "2 here: ann, bob")).await);
    // On the default map ann starts facing north and bob appears one cell north-west of her:
    // ann turns left about 45° (kitty press, 0.3 s at 2.6 rad/s, release) to face him. Nothing
    // else in that direction moves (doors shut, no animated sprites).
    ann.keys(b"\x1b[?11u").await;
    tokio::time::sleep(Duration::from_millis(100)).await;
    ann.keys(b"\x1b[97u").await;
    tokio::time::sleep(Duration::from_millis(300)).await;
    ann.keys(b"\x1b[97;1:3u").await;
    let with_bob = settled_view(&mut ann, cols, rows).await;
    bob.keys(b"q").await;
    assert!(ann.until(|s| header_has(s, "1 here: ann")).await);
    let without = settled_view(&mut ann, cols, rows).await;
    let changed = with_bob
        .iter()
        .zip(&without)
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        changed > 20,
        "bob's sprite covered {changed} cells of ann's view"
    );
    srv.shutdown().await;
}
