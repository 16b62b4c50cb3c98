//! What every edge's connections share with the server: its settings, the world and its
//! snapshots, the counters and the log, the stop signals, the limits and the leaderboard.

use std::sync::atomic::AtomicU64;
use std::sync::Arc;

use tokio::sync::watch;

use super::config::ServeConfig;
use super::edge::hooks::BoardLine;
use super::limits::Limiter;
use super::ops::log::Log;
use super::ops::stats::ServeStats;
use crate::play::session::Rules;
use crate::play::world_port::WorldHandle;
use crate::world::World;

/// What every connection shares with the server, over SSH or from a browser.
pub struct Shared {
    pub config: ServeConfig,
    pub world: WorldHandle,
    /// The served world, with the avatar sheet at `avatar_sheet`.
    pub world_data: Arc<World>,
    pub avatar_sheet: usize,
    /// Every served map, in rotation order: the ray debugger's `/trace.*?map=NAME` finds its
    /// world here (by `Map::name`; the first when no map is named).
    pub maps: Vec<Arc<World>>,
    pub stats: Arc<ServeStats>,
    pub log: Log,
    pub shutdown: watch::Receiver<bool>,
    /// What sessions are told when they end with the server (see [`super::ops::drain`]).
    pub farewell: watch::Receiver<&'static str>,
    /// Who is logging in and who plays, against the caps.
    pub limiter: Limiter,
    /// The lasting leaderboard, when the server keeps one.
    pub boards: Option<BoardLine>,
    /// The next connection's number, over every transport, so log lines never share one.
    pub next_id: AtomicU64,
}

impl Shared {
    /// What the server decides for every session: the world, the frame rate, the timeouts.
    #[must_use]
    pub fn rules(&self) -> Rules {
        Rules {
            world: self.world.clone(),
            world_data: Arc::clone(&self.world_data),
            avatar_sheet: self.avatar_sheet,
            fps: self.config.fps,
            idle_timeout: self.config.idle_timeout,
            stall_timeout: self.config.stall_timeout,
        }
    }
}
