//! What the browser edge shares with the rest of the server: the same world, limits, log,
//! leaderboard and health as the SSH edge, handed over by [`crate::serve::server`].

use std::sync::atomic::AtomicU64;
use std::sync::Arc;

use tokio::sync::watch;

use super::options::WebOptions;
use crate::play::world_port::WorldHandle;
use crate::serve::config::ServeConfig;
use crate::serve::limits::Limiter;
use crate::serve::ops::health::Readiness;
use crate::serve::ops::log::Log;
use crate::serve::ops::stats::ServeStats;
use crate::serve::session_hooks::BoardLine;
use crate::world::World;

/// What every browser connection shares with the rest of the server.
pub struct WebEdge {
    pub options: WebOptions,
    pub config: ServeConfig,
    pub world: WorldHandle,
    /// The served world, with the avatar sheet at `avatar_sheet`.
    pub world_data: Arc<World>,
    pub avatar_sheet: usize,
    pub stats: Arc<ServeStats>,
    pub log: Log,
    pub shutdown: watch::Receiver<bool>,
    pub farewell: watch::Receiver<&'static str>,
    pub limiter: Limiter,
    pub boards: Option<BoardLine>,
    /// What `/healthz` answers.
    pub ready: Arc<Readiness>,
    /// Session numbers, shared with the SSH listener so log lines never share one.
    pub next_id: Arc<AtomicU64>,
}
