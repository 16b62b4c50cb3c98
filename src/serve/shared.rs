//! What every edge's connections share with the server: its settings, the world and its
//! snapshots, the counters and the log, the stop signals, the limits and the leaderboard.

use std::sync::Arc;

use tokio::sync::watch;

use super::config::ServeConfig;
use super::limits::Limiter;
use super::ops::log::Log;
use super::ops::stats::ServeStats;
use super::session_hooks::BoardLine;
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
}
