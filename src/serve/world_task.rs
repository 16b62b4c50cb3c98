//! The one task that owns the shared game state and advances it at a fixed tick.
//!
//! Sessions talk to it only through a [`WorldHandle`]: messages in (join, leave, held keys) and the
//! latest [`Snapshot`] out through a `watch` channel, so a slow session never slows the world.

use std::sync::Arc;
use std::time::Duration;

use tokio::sync::{mpsc, watch};
use tokio::time::MissedTickBehavior;

use super::round_phase::RoundPhase;
use crate::game::multi::players::{Players, Rules, Snapshot};
use crate::game::multi::round::RoundEnd;
use crate::play::world_port::{WorldHandle, WorldMsg};
use crate::world::World;

/// The world task for a server: rounds over `worlds` in turn by `rules`; `round_over` is called
/// (on the world task: it must not block) with each finished round's results as it ends. Its
/// results stay on screen, no next round starting, once `hold` is true (a draining world ends
/// with the round, not with the one after). Returns the sessions' line to the world, and where
/// the round stands (for the drain).
///
/// # Panics
/// When `worlds` is empty.
#[must_use]
pub fn spawn_rounds(
    worlds: Vec<Arc<World>>,
    tick_hz: u32,
    rules: Rules,
    mut round_over: impl FnMut(&RoundEnd) + Send + 'static,
    hold: watch::Receiver<bool>,
) -> (WorldHandle, watch::Receiver<RoundPhase>) {
    let (tx, mut rx) = mpsc::channel::<WorldMsg>(1024);
    let (snap_tx, snap_rx) = watch::channel(Arc::new(Snapshot::default()));
    let (phase_tx, phase_rx) = watch::channel(RoundPhase::Waiting);
    let tick_hz = tick_hz.clamp(1, 1000);
    let dt = 1.0 / f64::from(tick_hz);
    tokio::spawn(async move {
        let mut players = Players::rotating(worlds, rules);
        let mut was_over = false;
        let mut tick = tokio::time::interval(Duration::from_secs_f64(dt));
        tick.set_missed_tick_behavior(MissedTickBehavior::Skip);
        loop {
            tick.tick().await;
            let mut joined_or_left = false;
            loop {
                match rx.try_recv() {
                    Ok(WorldMsg::Join { id, name }) => {
                        players.join(id, &name);
                        joined_or_left = true;
                    }
                    Ok(WorldMsg::Leave { id }) => {
                        players.leave(id);
                        joined_or_left = true;
                    }
                    Ok(WorldMsg::Input {
                        id,
                        input,
                        view_width,
                        releases_known: true,
                    }) => players.input_with_releases(id, input, view_width),
                    Ok(WorldMsg::Input {
                        id,
                        input,
                        view_width,
                        releases_known: false,
                    }) => players.input(id, input, view_width),
                    Err(mpsc::error::TryRecvError::Empty) => break,
                    Err(mpsc::error::TryRecvError::Disconnected) => return,
                }
            }
            let started = std::time::Instant::now();
            // Held: the results stay, and no next round starts.
            if !(was_over && *hold.borrow()) {
                players.tick(dt);
            }
            super::ops::metrics::world_tick(started.elapsed());
            let over = players.ended();
            if let (Some(end), false) = (over, was_over) {
                round_over(end);
            }
            was_over = over.is_some();
            let was = *phase_tx.borrow();
            let now = RoundPhase::next(was, was_over, players.len(), started);
            if now != was {
                phase_tx.send_replace(now);
            }
            // The world moves every tick (doors, animations); an empty one has nothing to show.
            if joined_or_left || !players.is_empty() {
                let _ = snap_tx.send(Arc::new(players.snapshot()));
            }
        }
    });
    (WorldHandle::new(tx, snap_rx), phase_rx)
}

#[cfg(test)]
mod height_rules;
