//! The server's side of a running play session, for every transport: its frame metrics, its log
//! line when the world renames a player, the leaderboard it shows, the world's draining as a note.

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;

use tokio::sync::watch;

use crate::game::multi::players::{PlayerId, Snapshot};
use crate::play::hooks::Hooks;
use crate::serve::leaderboard::writer::Leaderboard;
use crate::serve::leaderboard::{board_key, shown_name, Boards, TOP};
use crate::serve::ops::drain::{DRAINING_NOTICE, RESTARTING};
use crate::serve::ops::log::Log;
use crate::serve::ops::metrics::FrameMetrics;
use crate::ui::results::Board;

/// What a session needs of the lasting leaderboard.
#[derive(Debug, Clone)]
pub struct BoardLine {
    /// The leaderboard thread's handle.
    pub board: Leaderboard,
    /// The served maps' content hashes, by index.
    pub hashes: Arc<Vec<String>>,
    /// The mode played ("coop", "tag").
    pub mode: &'static str,
}

/// One session's hooks into the server.
pub struct ServerHooks {
    pub id: u64,
    pub peer: SocketAddr,
    pub log: Log,
    pub metrics: FrameMetrics,
    /// The leaderboard and its latest tops, when the server keeps one.
    pub boards: Option<(BoardLine, watch::Receiver<Arc<Boards>>)>,
}

impl ServerHooks {
    /// Hooks for session `id` from `peer`.
    #[must_use]
    pub fn new(id: u64, peer: SocketAddr, log: Log, boards: Option<BoardLine>) -> Self {
        Self {
            id,
            peer,
            log,
            metrics: FrameMetrics::new(),
            boards: boards.map(|line| {
                let rx = line.board.boards();
                (line, rx)
            }),
        }
    }
}

impl Hooks for ServerHooks {
    fn frame_sent(&self, bytes: usize) {
        self.metrics.sent(bytes);
    }

    fn ticks_skipped(&self, n: u64) {
        self.metrics.skipped(n);
    }

    fn link_waited(&self, wait: Duration) {
        self.metrics.link_wait(wait);
    }

    fn level_stepped(&self, down: bool) {
        self.metrics.level_step(down);
    }

    fn frame_timed(&self, render: Duration, encode: Duration) {
        self.metrics.timed(render, encode);
    }

    fn renamed(&self, asked: &str, given: &str) {
        // The log line at login named what was asked for.
        self.log.session(
            self.id,
            self.peer,
            format_args!("{asked:?} was taken: plays as {given:?}"),
        );
    }

    fn best_wanted(&self, map: usize, name: &str) {
        if let Some((line, _)) = &self.boards {
            if let Some(hash) = line.hashes.get(map) {
                line.board.lookup(hash, line.mode, name);
            }
        }
    }

    fn board(&self, snap: &Snapshot, me: PlayerId) -> Option<Board> {
        let (line, rx) = self.boards.as_ref()?;
        leaders(line, &rx.borrow(), snap, me)
    }
}

/// The world's draining, as a note for a session's player: told at once, not only when it
/// closes.
pub fn draining_notes(
    mut farewell: watch::Receiver<&'static str>,
) -> watch::Receiver<Option<String>> {
    let (tx, rx) = watch::channel(None);
    tokio::spawn(async move {
        loop {
            tokio::select! {
                // Err: the server is gone; its shutdown signal ends the session.
                changed = farewell.changed() => if changed.is_err() { return },
                () = tx.closed() => return,
            }
            if *farewell.borrow_and_update() == RESTARTING {
                let _ = tx.send(Some(DRAINING_NOTICE.to_owned()));
            }
        }
    });
    rx
}

/// The leaderboard a session shows for the map of `snap` (the finished round's map while the
/// results show): top entries with escaped names, and `me`'s own best.
fn leaders(line: &BoardLine, boards: &Boards, snap: &Snapshot, me: PlayerId) -> Option<Board> {
    let map = snap.ended.as_ref().map_or(snap.map, |e| e.map);
    let hash = line.hashes.get(map)?;
    let board = boards.maps.get(&board_key(hash, line.mode));
    let top = board.map(|b| b.top.as_slice()).unwrap_or_default();
    let rows = top
        .iter()
        .enumerate()
        .map(|(i, e)| {
            (
                format!("{:>2}. {}", i + 1, shown_name(&e.name)),
                e.figure(line.mode),
            )
        })
        .collect();
    let own = snap
        .player(me)
        .and_then(|p| board?.bests.get(&p.name))
        .map(|e| e.figure(line.mode));
    Some(Board {
        title: format!("All-time top {TOP} on this map"),
        rows,
        own,
    })
}
