//! The glyph key over SSH: each session has its own block characters. One player switches to
//! octants while another stays on half-blocks, and each receives its own frames.

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
