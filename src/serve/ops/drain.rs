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

/// The seconds a drained player is told to wait before reconnecting: spread over this range
/// so a world's players do not all arrive at once at the worlds left (or at a balancer with
/// one world left, "server full"), and many return after the restarted world is back in the
/// balancer (a restart plus HAProxy's `rise 2` checks 2 s apart: about 5 s).
pub const RECONNECT_AFTER: std::ops::RangeInclusive<u64> = 2..=15;

/// The line session `session`'s terminal shows last when the server stops with `farewell`
/// ([`farewell_for`]).
#[must_use]
pub fn farewell_line_for(farewell: &str, session: u64) -> Vec<u8> {
    format!("halfcast: {}.\r\n", farewell_for(farewell, session)).into_bytes()
}

/// What session `session` is told when the server stops with `farewell`: a restart says when to
/// reconnect (`… in N s`), a number of seconds in [`RECONNECT_AFTER`] drawn from the session and
/// the process, the same for every transport.
#[must_use]
pub fn farewell_for(farewell: &str, session: u64) -> String {
    if farewell != RESTARTING {
        return farewell.to_owned();
    }
    let wait = reconnect_after(session ^ process_salt());
    format!("{farewell} in {wait} s")
}

/// Seconds in [`RECONNECT_AFTER`], spread evenly over `key`s (SplitMix64's finaliser).
fn reconnect_after(key: u64) -> u64 {
    let mut z = key.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    let span = RECONNECT_AFTER.end() - RECONNECT_AFTER.start() + 1;
    RECONNECT_AFTER.start() + z % span
}

/// Differs between processes, so two worlds' session 1 are not told the same wait.
fn process_salt() -> u64 {
    static SALT: std::sync::OnceLock<u64> = std::sync::OnceLock::new();
    *SALT.get_or_init(|| {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos() as u64);
        nanos ^ u64::from(std::process::id()).rotate_left(32)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drained_players_are_told_waits_spread_over_the_range() {
        let mut seen = [0u32; 16];
        for session in 0..1600 {
            let s = reconnect_after(session);
            assert!(RECONNECT_AFTER.contains(&s), "{s}");
            seen[s as usize] += 1;
        }
        // 14 values, about 114 sessions each.
        for s in RECONNECT_AFTER {
            assert!((60..=170).contains(&seen[s as usize]), "{seen:?}");
        }
        let line = String::from_utf8(farewell_line_for(RESTARTING, 7)).unwrap();
        assert!(line.starts_with("halfcast: this world restarts: reconnect to continue in "));
        assert!(line.ends_with(" s.\r\n"), "{line:?}");
        assert_eq!(
            farewell_line_for(SHUTTING_DOWN, 7),
            b"halfcast: the server is shutting down.\r\n"
        );
    }
}
