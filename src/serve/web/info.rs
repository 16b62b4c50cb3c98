//! `/info.json`: what a page shows before it plays (its title, its form): the world's map, how
//! many play and watch, and the mode, from the newest snapshot and the server's counters.

use serde_json::json;

use crate::serve::shared::Shared;

/// `{"world":"default.cub","players":N,"watching":M,"mode":"coop"}`.
#[must_use]
pub fn json(shared: &Shared) -> String {
    let snap = shared.world.snapshots().borrow().clone();
    let world = snap.world.as_ref().map_or_else(
        || shared.world_data.map.name.clone(),
        |w| w.map.name.clone(),
    );
    let players = snap.players.len() as u64;
    let live = shared.stats.snapshot().sessions_live;
    json!({
        "world": world,
        "players": players,
        "watching": live.saturating_sub(players),
        "mode": shared.config.mode.name(),
    })
    .to_string()
}
