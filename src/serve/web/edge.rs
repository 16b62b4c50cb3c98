//! What the browser edge shares with the rest of the server: the same world, limits, log,
//! leaderboard and health as the SSH edge, handed over by [`crate::serve::server`].

use std::sync::Arc;

use super::options::WebOptions;
use crate::serve::ops::health::Readiness;
use crate::serve::shared::Shared;

/// What every browser connection shares with the rest of the server.
pub struct WebEdge {
    pub options: WebOptions,
    /// What every connection shares, the SSH port's included.
    pub shared: Arc<Shared>,
    /// What `/healthz` answers.
    pub ready: Arc<Readiness>,
}
