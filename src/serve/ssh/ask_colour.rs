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
/// reply (keys the player already typed), to be handled as input. When the patience ran out
/// before the last reply, `data` is swapped for one whose late replies (and answerback) are
/// stripped ([`strip_late_replies`]), so they never arrive as keys.
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
    let decided = rules::decide(choice, &scanner.answers());
    // A terminal that began answering sent the rest at once: what has not come by now (a
    // second DA1 reply some terminal skips) is not coming, and keys are keys again.
    if scanner.done() || scanner.answering() {
        let (_, rest) = scanner.finish();
        return (decided, rest);
    }
    let rest = scanner.take_keys();
    let (tx, rx) = mpsc::channel(data.max_capacity());
    let original = std::mem::replace(data, rx);
    tokio::spawn(strip_late_replies(original, tx, scanner));
    (decided, rest)
}

/// How long after the query late replies are still looked for: a terminal that has not
/// answered by then never will.
const LATE_FOR: Duration = Duration::from_secs(10);

/// How long after a late first DA1 reply the answerback may still come (it is sent at once,
/// with the second DA1 reply); past it, bytes are keys again even if that reply never comes.
const ANSWERBACK_WINDOW: Duration = Duration::from_millis(500);

/// How long an unfinished sequence waits for its next bytes before it counts as keys (a lone
/// Esc); a reply cut between reads arrives far sooner.
const UNFINISHED_WAIT: Duration = Duration::from_millis(20);

/// Bytes fed to the scanner at a time, so that none is dropped as past its bound for keys.
const FEED_CHUNK: usize = 1024;

/// Forwards `from` to `to` with the rest of the query's replies (late, after the patience) and
/// the answerback between its DA1 replies left out, for [`LATE_FOR`] or until the last reply;
/// then forwards as it is. Ends when either side closes.
async fn strip_late_replies(
    mut from: mpsc::Receiver<Vec<u8>>,
    to: mpsc::Sender<Vec<u8>>,
    mut scanner: ReplyScanner,
) {
    let mut until = tokio::time::Instant::now() + LATE_FOR;
    let mut windowed = false;
    while !scanner.done() && tokio::time::Instant::now() < until {
        if !windowed && scanner.answering() {
            windowed = true;
            until = until.min(tokio::time::Instant::now() + ANSWERBACK_WINDOW);
        }
        let wait = if scanner.has_unfinished() {
            UNFINISHED_WAIT
        } else {
            until.saturating_duration_since(tokio::time::Instant::now())
        };
        let got = tokio::select! {
            got = tokio::time::timeout(wait, from.recv()) => got,
            () = to.closed() => return,
        };
        let keys = match got {
            Ok(Some(bytes)) => {
                let mut keys = Vec::new();
                for chunk in bytes.chunks(FEED_CHUNK) {
                    scanner.feed(chunk);
                    keys.append(&mut scanner.take_keys());
                }
                keys
            }
            Ok(None) => break,
            Err(_) => scanner.take_unfinished(),
        };
        if !keys.is_empty() && to.send(keys).await.is_err() {
            return;
        }
    }
    let unfinished = scanner.take_unfinished();
    if !unfinished.is_empty() && to.send(unfinished).await.is_err() {
        return;
    }
    loop {
        let bytes = tokio::select! {
            got = from.recv() => got,
            () = to.closed() => return,
        };
        let Some(bytes) = bytes else { return };
        if to.send(bytes).await.is_err() {
            return;
        }
    }
}

/// How long a session waits for the client's terminal to answer: a local terminal's patience
/// plus a network round trip.
pub const SSH_QUERY_PATIENCE: Duration = QUERY_PATIENCE.saturating_add(Duration::from_millis(300));

#[cfg(test)]
mod tests {
    use super::*;

    /// Starts stripping after a query with the answerback asked and nothing answered in time;
    /// returns the client's side and what the session reads.
    fn late() -> (mpsc::Sender<Vec<u8>>, mpsc::Receiver<Vec<u8>>) {
        let (client, from) = mpsc::channel(8);
        let (to, session) = mpsc::channel(8);
        tokio::spawn(strip_late_replies(from, to, ReplyScanner::new(true)));
        (client, session)
    }

    /// Everything the session reads until `want` bytes came (or a second passed).
    async fn read(session: &mut mpsc::Receiver<Vec<u8>>, want: usize) -> Vec<u8> {
        let mut got = Vec::new();
        while got.len() < want {
            match tokio::time::timeout(Duration::from_secs(1), session.recv()).await {
                Ok(Some(b)) => got.extend(b),
                _ => break,
            }
        }
        got
    }

    #[tokio::test]
    async fn a_late_answerback_and_late_replies_never_reach_the_session_as_keys() {
        let (client, mut session) = late();
        for part in [
            &b"w"[..],
            b"\x1bP0+r5247",
            b"42\x1b\\\x1b[?6",
            b"c",
            b"Pu",
            b"TTY",
            b"\x1b[?6c",
            b"a",
        ] {
            client.send(part.to_vec()).await.unwrap();
        }
        assert_eq!(read(&mut session, 2).await, b"wa");
        // Done: from now on bytes pass as they are, replies included.
        client.send(b"\x1b[?6cq".to_vec()).await.unwrap();
        assert_eq!(read(&mut session, 6).await, b"\x1b[?6cq");
    }

    #[tokio::test]
    async fn keys_after_a_late_da1_reply_whose_second_never_comes_are_keys_again() {
        let (client, mut session) = late();
        // One DA1 reply only (the second DA1 skipped): what follows at once is taken for the
        // answerback, but not for long.
        client.send(b"\x1b[?1;2cxy".to_vec()).await.unwrap();
        tokio::time::sleep(ANSWERBACK_WINDOW + Duration::from_millis(200)).await;
        client.send(b"wasd".to_vec()).await.unwrap();
        assert_eq!(read(&mut session, 4).await, b"wasd");
    }

    #[tokio::test]
    async fn a_lone_esc_is_not_held_back_for_long() {
        let (client, mut session) = late();
        client.send(b"\x1b".to_vec()).await.unwrap();
        // It could be the start of a late reply, but no more came: it is a key after all.
        assert_eq!(read(&mut session, 1).await, b"\x1b");
        // An arrow key cut after its ESC still arrives whole, in order.
        client.send(b"\x1b[".to_vec()).await.unwrap();
        client.send(b"A".to_vec()).await.unwrap();
        assert_eq!(read(&mut session, 3).await, b"\x1b[A");
    }

    #[tokio::test]
    async fn the_session_sees_the_client_leave() {
        let (client, mut session) = late();
        client.send(b"x".to_vec()).await.unwrap();
        drop(client);
        assert_eq!(read(&mut session, 1).await, b"x");
        assert_eq!(session.recv().await, None);
    }
}
