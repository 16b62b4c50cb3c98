//! Asking an SSH client's terminal whether it shows 24-bit colour, over the channel, before the
//! first frame: the same queries as the local game ([`crate::ui::colour_query`]), answered
//! through the channel's data.

use std::time::Duration;

use russh::server::Handle;
use russh::ChannelId;
use tokio::sync::mpsc;

use crate::ui::colour_query::{ReplyScanner, QUERY, QUERY_PATIENCE};

/// Sends `before` (the session's terminal set-up) and the query, and reads the client's input until the DA1 reply or `patience` (the round
/// trip is longer than a local terminal's, so the caller may allow more).
///
/// Returns the answer (`None`: the terminal said nothing about colour) and the bytes read that
/// were not a reply (keys the player already typed), to be handled as input.
pub async fn ask_truecolor(
    handle: &Handle,
    channel: ChannelId,
    before: &[u8],
    data: &mut mpsc::Receiver<Vec<u8>>,
    patience: Duration,
) -> (Option<bool>, Vec<u8>) {
    let bytes = [before, QUERY].concat();
    let sent = tokio::time::timeout(patience, handle.data(channel, bytes)).await;
    if !matches!(sent, Ok(Ok(()))) {
        return (None, Vec::new());
    }
    let deadline = tokio::time::Instant::now() + patience;
    let mut scanner = ReplyScanner::default();
    while !scanner.done() {
        match tokio::time::timeout_at(deadline, data.recv()).await {
            Ok(Some(bytes)) => scanner.feed(&bytes),
            // Timed out, or the client closed its input.
            Ok(None) | Err(_) => break,
        }
    }
    scanner.finish()
}

/// How long a session waits for the client's terminal to answer: a local terminal's patience
/// plus a network round trip.
pub const SSH_QUERY_PATIENCE: Duration = QUERY_PATIENCE.saturating_add(Duration::from_millis(300));
