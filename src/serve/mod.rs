//! `halfcast serve`: an SSH server where everyone connected walks one shared world.
//!
//! Layout, one concept per file:
//! - [`config`]: operator settings and the client size bounds; [`auth`]: who may connect;
//!   [`hostkey`]: the persisted Ed25519 identity; [`limits`]: admission at accept.
//! - [`server`]: the accept loop; [`handler`]: the SSH side of one connection (pty, resize,
//!   refusals); [`session`]: one terminal's loop (keys in, frames out, bounded).
//! - [`world_task`]: the fixed-tick task owning [`players::Players`] (the shared game state);
//!   sessions send it input and read its snapshots.
//! - [`input`]: the raw key byte parser. Stand-ins for other branches' work, marked in each file:
//!   [`player`] (movement), [`controls`] (key map), [`view`] (panes), [`frame`] (encoder),
//!   [`color_level`] (colour ladder).

pub mod auth;
pub mod color_level;
pub mod config;
pub mod controls;
pub mod frame;
pub mod handler;
pub mod hostkey;
pub mod input;
pub mod limits;
pub mod log;
pub mod player;
pub mod players;
pub mod server;
pub mod session;
pub mod stats;
pub mod view;
pub mod world_task;

pub use config::ServeConfig;
pub use server::{run_until_signal, start, RunningServer};
