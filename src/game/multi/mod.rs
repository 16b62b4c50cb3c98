//! The rules of a shared level: several players in one world ([`players`]) and the round they
//! play ([`round`]: coop or tag, its clock and scoreboard). Pure, with no clock or async runtime:
//! the SSH server's world task drives them once per tick.

pub mod players;
pub mod rotation;
pub mod round;
mod taps;

/// A connection's id; also names its player in the world.
pub type PlayerId = u64;
