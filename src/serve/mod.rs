//! `halfcast serve`: a server where everyone connected walks one shared world.
//!
//! Rooms, one concept each:
//! - [`edge`]: the one way in for every transport: admission and refusals, the name check,
//!   connection numbers, a player let in and counted live, the session run with its panic
//!   caught, the end's bookkeeping, the server's hooks into a session.
//! - [`ssh`]: the SSH edge (protocol, auth, host key, the channel as a play session's sink);
//!   the session itself is transport-free, in [`crate::play`].
//! - [`web`]: the browser edge (the page, its WebSocket, the page's acks as a frame sink); it
//!   and [`ssh`] never use each other.
//! - [`server`]: the process: worlds, listeners, leaderboard, metrics, drain; [`config`]:
//!   operator settings; [`limits`]: admission (logging-in and playing connections counted
//!   apart); [`proxy_header`]: PROXY protocol headers from a load balancer.
//! - [`world_task`]: the fixed-tick task owning [`crate::game::multi::players::Players`] (one
//!   `game::GameState` per player, moved by `game::step_shared`, and the doors they share);
//!   sessions send it the `game::Input` of their keys and read its snapshots.
//! - [`shared`]: what every edge's connections share with the server.
//! - [`served_map`]: a map of the rotation and its content hash; [`leaderboard`]: finished
//!   rounds in SQLite or PostgreSQL, written by a thread of its own.
//! - [`ops`]: metrics, `/healthz`, drain, process figures, the log.

pub(crate) mod config;
pub mod edge;
pub mod leaderboard;
pub mod limits;
pub mod ops;
pub(crate) mod proxy_header;
pub(crate) mod round_phase;
pub(crate) mod served_map;
pub mod server;
pub(crate) mod shared;
pub mod ssh;
pub mod web;
pub(crate) mod world_task;

pub use config::ServeConfig;
pub use ops::{health, log};
pub use served_map::ServedMap;
pub use server::{run_until_signal, start, start_maps, RunningServer};
pub use ssh::auth;
