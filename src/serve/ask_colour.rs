//! Asking an SSH client's terminal what it draws, over the channel, before the first frame: the
//! same queries and rules as the local game ([`crate::ui::colour_query`]), answered through the
//! channel's data.

use std::time::Duration;

use russh::server::Handle;
use russh::ChannelId;
use tokio::sync::mpsc;

use crate::encode::ColourChoice;
use crate::ui::colour_query::{query, rules, ReplyScanner, QUERY_PATIENCE};

/// Sends `before` (the session's terminal set-up) and the query (with ENQ where the answerback
/// matters, [`ColourChoice::worth_an_answerback`]), and reads the client's input until the last
/// DA1 reply due or `patience` (the round trip is longer than a local terminal's, so the caller
/// may allow more; once more when the terminal has begun answering, so an answerback on its
/// way is not taken for keys).
///
/// Returns `choice` after the answers ([`rules::decide`]) and the bytes read that were not a
/// reply (keys the player already typed), to be handled as input.
pub async fn ask_colour(
    handle: &Handle,
    channel: ChannelId,
    before: &[u8],
    data: &mut mpsc::Receiver<Vec<u8>>,
    patience: Duration,
    choice: ColourChoice,
) -> (ColourChoice, Vec<u8>) {
    let answerback = choice.worth_an_answerback();
    let bytes = [before, &query(answerback)].concat();
    let sent = tokio::time::timeout(patience, handle.data(channel, bytes)).await;
    if !matches!(sent, Ok(Ok(()))) {
        return (choice, Vec::new());
    }
    let mut deadline = tokio::time::Instant::now() + patience;
    let mut extended = false;
    let mut scanner = ReplyScanner::new(answerback);
    while !scanner.done() {
        match tokio::time::timeout_at(deadline, data.recv()).await {
            Ok(Some(bytes)) => scanner.feed(&bytes),
            Err(_) if !extended && scanner.answering() => {
                extended = true;
                deadline += patience;
            }
            // Timed out, or the client closed its input.
            Ok(None) | Err(_) => break,
        }
    }
    let (answers, rest) = scanner.finish();
    (rules::decide(choice, &answers), rest)
}

/// How long a session waits for the client's terminal to answer: a local terminal's patience
/// plus a network round trip.
pub const SSH_QUERY_PATIENCE: Duration = QUERY_PATIENCE.saturating_add(Duration::from_millis(300));
