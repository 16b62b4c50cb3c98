//! The glyph key over SSH: each session has its own block characters. One player switches to
//! octants while another stays on half-blocks, and each receives its own frames. Behind tmux
//! (as the pty's TERM tells) the key skips octants, unless the client asked for them.

use crate::serve_support;

use serve_support::{half_block_cells, server, status_has, view_rect, Client};

/// Cells of the view drawn with a character from the octant run (U+1CD00–1CDE5).
fn octant_cells(s: &vt100::Screen, cols: u16, rows: u16) -> usize {
    let v = view_rect(cols, rows);
    let mut n = 0;
    for r in v.top()..v.bottom() {
        for c in v.left()..v.right() {
            let cell = s.cell(r, c).expect("cell");
            if let Some(ch) = cell.contents().chars().next() {
                if (0x1CD00..=0x1CDE5).contains(&u32::from(ch)) {
                    n += 1;
                }
            }
        }
    }
    n
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn one_session_switches_to_octants_while_another_stays_on_half_blocks() {
    let (cols, rows) = (140, 24);
    let (srv, _dir) = server(|_| {}).await;
    let mut ann = Client::connect(srv.local_addr(), "ann", cols, rows, "xterm-direct").await;
    let mut bob = Client::connect(srv.local_addr(), "bob", cols, rows, "xterm-direct").await;
    for c in [&mut ann, &mut bob] {
        assert!(
            c.until(|s| half_block_cells(s, view_rect(cols, rows)) > 0)
                .await
        );
    }
    // U three times: quadrant, sextant, octant.
    for name in ["quadrant blocks", "sextant blocks", "octant blocks"] {
        ann.keys(b"u").await;
        assert!(ann.until(|s| status_has(s, name)).await, "{name}");
    }
    assert!(
        ann.until(|s| octant_cells(s, cols, rows) > 100).await,
        "ann's view is not drawn in octants"
    );
    // Bob's terminal never received an octant and still shows half-blocks only.
    bob.drain_for(std::time::Duration::from_millis(500)).await;
    let s = bob.screen.screen();
    assert_eq!(octant_cells(s, cols, rows), 0);
    assert!(
        !status_has(s, "blocks"),
        "bob's status line names no other setting"
    );
    let v = view_rect(cols, rows);
    assert!(half_block_cells(s, v) > usize::from(v.width) * usize::from(v.height) / 2);
    srv.shutdown().await;
}

/// Quadrant-only characters (`▖ ▗ ▘ ▙ ▚ ▛ ▜ ▝ ▞ ▟`) in the view.
fn quadrant_cells(s: &vt100::Screen, cols: u16, rows: u16) -> usize {
    let v = view_rect(cols, rows);
    (v.top()..v.bottom())
        .flat_map(|r| (v.left()..v.right()).map(move |c| (r, c)))
        .filter(|&(r, c)| {
            let cell = s.cell(r, c).expect("cell");
            cell.contents()
                .chars()
                .next()
                .is_some_and(|ch| (0x2596..=0x259F).contains(&u32::from(ch)))
        })
        .count()
}

/// Connects as `user` with a `cols`×`rows` pty of `term`, sending `env` first (as
/// `ssh -o SetEnv=…` does).
async fn connect_env(
    addr: std::net::SocketAddr,
    user: &str,
    (cols, rows): (u16, u16),
    term: &str,
    env: &[(&str, &str)],
) -> Client {
    let mut handle = serve_support::connect_raw(addr, None)
        .await
        .expect("connect");
    assert!(handle
        .authenticate_none(user)
        .await
        .expect("auth")
        .success());
    let channel = handle.channel_open_session().await.expect("session");
    for (k, v) in env {
        channel.set_env(true, *k, *v).await.expect("env");
    }
    channel
        .request_pty(true, term, u32::from(cols), u32::from(rows), 0, 0, &[])
        .await
        .expect("pty");
    channel.request_shell(true).await.expect("shell");
    Client::new(handle, channel, cols, rows)
}

/// A client behind tmux (its pty's TERM says so): the glyph key goes quadrant, sextant, then
/// back to half-blocks with a note saying why, and never sends an octant. A client that asks
/// for octants (`HALFCAST_GLYPHS=octant`, as `ssh -o SetEnv=…` sends it) gets them anyway.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn behind_tmux_the_glyph_key_skips_octants_unless_the_client_asks_for_them() {
    let (cols, rows) = (140, 24);
    let (srv, _dir) = server(|_| {}).await;
    let truecolor = ("COLORTERM", "truecolor");
    let addr = srv.local_addr();
    let mut cy = connect_env(addr, "cy", (cols, rows), "tmux-256color", &[truecolor]).await;
    assert!(
        cy.until(|s| half_block_cells(s, view_rect(cols, rows)) > 0)
            .await
    );
    for name in ["quadrant blocks", "sextant blocks"] {
        cy.keys(b"u").await;
        assert!(cy.until(|s| status_has(s, name)).await, "{name}");
    }
    // From here on, every screen the client shows is checked for octants.
    let most = std::cell::Cell::new(0);
    let seen = |s: &vt100::Screen| most.set(most.get().max(octant_cells(s, cols, rows)));
    cy.keys(b"u").await;
    let note = "octants off: tmux drops them; ssh -o SetEnv=HALFCAST_GLYPHS=octant forces";
    assert!(
        cy.until(|s| {
            seen(s);
            status_has(s, note)
        })
        .await
    );
    let v = view_rect(cols, rows);
    let most_cells = usize::from(v.width) * usize::from(v.height) / 2;
    assert!(
        cy.until(|s| {
            seen(s);
            half_block_cells(s, v) > most_cells
        })
        .await,
        "half-blocks again"
    );
    cy.keys(b"u").await;
    assert!(
        cy.until(|s| {
            seen(s);
            quadrant_cells(s, cols, rows) > 20
        })
        .await,
        "quadrants again"
    );
    assert_eq!(most.get(), 0, "an octant reached the client behind tmux");

    // Asking for octants: the session starts with them, behind tmux or not.
    let glyphs = ("HALFCAST_GLYPHS", "octant");
    let term = "tmux-256color";
    let mut di = connect_env(addr, "di", (cols, rows), term, &[truecolor, glyphs]).await;
    assert!(di.until(|s| status_has(s, "octant blocks")).await);
    assert!(
        di.until(|s| octant_cells(s, cols, rows) > 100).await,
        "di's view is not drawn in octants"
    );
    srv.shutdown().await;
}
