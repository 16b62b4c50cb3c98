//! How long a draining world waits before it tells its players to reconnect: until nobody is
//! left, or the round in play ends (then [`AFTER_LAST_ROUND`] of its results, so they are seen
//! and the round is recorded), or the drain's deadline. A world drained while its results show
//! or while nobody plays stops within [`AFTER_LAST_ROUND`]: it holds the results instead of
//! starting another round, so no drain waits for a whole next round.

use tokio::sync::watch;
use tokio::time::Instant;

use super::drain::AFTER_LAST_ROUND;
use crate::serve::round_phase::RoundPhase;

/// Who is still there, as the drain asks it: (anyone at all, anyone still logging in).
pub type Presence<'a> = &'a (dyn Fn() -> (bool, bool) + Sync);

/// Waits until the drain may end (see the module's note), or `deadline`.
pub async fn until_round_over(
    mut phase: watch::Receiver<RoundPhase>,
    present: Presence<'_>,
    deadline: Instant,
) {
    loop {
        let (anyone, logging_in) = present();
        if !anyone {
            return;
        }
        match *phase.borrow_and_update() {
            RoundPhase::Results { since } => {
                let end = Instant::from_std(since) + AFTER_LAST_ROUND;
                tokio::time::sleep_until(end.min(deadline)).await;
                return;
            }
            // Only watchers (or nobody) in the world: no round to wait for.
            RoundPhase::Waiting if !logging_in => return,
            RoundPhase::Waiting | RoundPhase::Playing => {}
        }
        tokio::select! {
            () = tokio::time::sleep_until(deadline) => return,
            _ = phase.changed() => {}
            // Who is here changes without the phase changing (a watcher leaves).
            () = tokio::time::sleep(std::time::Duration::from_millis(50)) => {}
        }
    }
}
