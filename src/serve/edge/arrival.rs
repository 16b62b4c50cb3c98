//! A player let in: logged in, counted live, and in the world, until its place is given back.
//! Everything counted here is undone by dropping the [`Arrival`] (or the `Live` it holds), so a
//! session that ends in any way, a panic included, leaves no place, gauge or count behind.

use std::net::SocketAddr;
use std::sync::Arc;

use super::Via;
use crate::play::session::{self, Joined};
use crate::serve::limits::Playing;
use crate::serve::ops::metrics;
use crate::serve::ops::stats::ServeStats;
use crate::serve::shared::Shared;

/// Who a transport lets in: its number, address and shown name, whether it only watches, and
/// what carries it.
#[derive(Debug, Clone)]
pub struct Who {
    pub id: u64,
    pub peer: SocketAddr,
    /// The name shown to others ([`super::name::display_name`]).
    pub name: String,
    pub spectator: bool,
    pub via: Via,
}

/// A player in the world, holding its playing place and its live count until dropped.
pub struct Arrival {
    pub(super) shared: Arc<Shared>,
    pub(super) who: Who,
    pub(super) joined: Joined,
    pub(super) live: Live,
}

/// Lets `who` in with `place`: its login line, the live gauges and count, and the player put in
/// the world, before the transport asks its client anything (a draining world then waits for
/// the round of everyone admitted, not only of those whose first frame was drawn).
pub async fn arrive(shared: &Arc<Shared>, who: Who, place: Playing) -> Arrival {
    match &who.via {
        Via::Ssh { term } => shared
            .log
            .login(who.id, who.peer, &who.name, who.spectator, term),
        Via::Web => shared
            .log
            .login_web(who.id, who.peer, &who.name, who.spectator),
    }
    let live = Live::new(Arc::clone(&shared.stats), &who, place);
    let joined = session::join(&shared.world, who.id, &who.name, who.spectator).await;
    Arrival {
        shared: Arc::clone(shared),
        who,
        joined,
        live,
    }
}

impl Arrival {
    /// Who this is.
    #[must_use]
    pub fn who(&self) -> &Who {
        &self.who
    }

    /// What every connection shares with the server.
    #[must_use]
    pub fn shared(&self) -> &Arc<Shared> {
        &self.shared
    }
}

/// A session counted live (the server's count, the `sessions` and `transport_sessions` gauges)
/// and its playing place, both given back when dropped.
pub(super) struct Live {
    stats: Arc<ServeStats>,
    spectator: bool,
    transport: &'static str,
    _place: Playing,
}

impl Live {
    fn new(stats: Arc<ServeStats>, who: &Who, place: Playing) -> Self {
        metrics::session(who.spectator, true);
        metrics::transport_session(who.via.label(), true);
        ServeStats::add(&stats.sessions_live, 1);
        Self {
            stats,
            spectator: who.spectator,
            transport: who.via.label(),
            _place: place,
        }
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        metrics::session(self.spectator, false);
        metrics::transport_session(self.transport, false);
        self.stats
            .sessions_live
            .fetch_sub(1, std::sync::atomic::Ordering::Relaxed);
    }
}
