//! Stopping a world without losing its players: on SIGTERM it drains (`/healthz` says 503, the
//! port closes so a balancer's retries land elsewhere, the round in play may finish), then
//! every session ends with a farewell that tells the player what to do.

use std::time::Duration;

/// What players are told when the server stops at once (Ctrl-C).
pub const SHUTTING_DOWN: &str = "the server is shutting down";

/// What players are told when the world stops after draining (SIGTERM: a restart or upgrade);
/// behind a balancer, reconnecting lands them on another world of the fleet.
pub const RESTARTING: &str = "this world restarts: reconnect to continue";

/// What players see over the status line while their world drains.
pub const DRAINING_NOTICE: &str = "this world restarts soon: reconnect when it closes";

/// The default `--drain-seconds`: how long a draining world waits for its round to end.
pub const DEFAULT_DRAIN: Duration = Duration::from_secs(30);

/// How long players see a round's results before a draining world stops, when the round ends
/// within the drain (so the results and the leaderboard are seen, and the round is recorded).
pub const AFTER_LAST_ROUND: Duration = Duration::from_secs(5);

/// The line a session's terminal shows last when the server stops with `farewell`.
#[must_use]
pub fn farewell_line(farewell: &str) -> Vec<u8> {
    format!("halfcast: {farewell}.\r\n").into_bytes()
}
