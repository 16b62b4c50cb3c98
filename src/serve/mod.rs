//! `halfcast serve`: an SSH server where everyone connected walks one shared world.
//!
//! Layout, one concept per file:
//! - [`config`]: operator settings and the client size bounds; [`auth`]: who may connect;
//!   [`hostkey`]: the persisted Ed25519 identity; [`limits`]: admission (logging-in and playing
//!   connections counted apart); [`lifecycle`]: one connection's kill switch and login clock.
//! - [`server`]: the accept loop; [`handler`]: the SSH side of one connection (pty, resize,
//!   refusals); [`session`]: one terminal's loop (keys in, frames out, bounded).
//! - [`world_task`]: the fixed-tick task owning [`crate::game::multi::players::Players`] (one `game::GameState` per
//!   player, moved by `game::step_shared`, and the doors they share); sessions send it the
//!   `game::Input` of their keys and read its snapshots.
//! - [`crate::ui::key_bytes`]: the raw key byte parser; [`crate::ui::key_route`]: server keys, the rest
//!   to the game screen's key map (both in the transport-free `ui` room).
//! - [`screen`]: the TUI's panes under a header ([`header`] fits it to the width), through the
//!   `Presenter`; [`avatars`]: other players as the world's 8-view sprite, and their names on
//!   the minimap.
//! - [`served_map`]: a map of the rotation and its content hash; [`leaderboard`]: the SQLite
//!   file of finished rounds, written by a thread of its own; [`metrics`]: the Prometheus
//!   series; [`metrics_http`]: the `--metrics` address's `/metrics` and `/healthz`;
//!   [`health`]: whether a balancer should send this world players; [`process_stats`]: memory,
//!   CPU and files from `/proc`; [`drain`]: stopping on SIGTERM without losing players;
//!   [`proxy_header`]: PROXY protocol headers from a load balancer; [`log`]: text or JSON lines.

pub(crate) mod ask_colour;
pub mod auth;
pub(crate) mod avatars;
pub(crate) mod config;
pub(crate) mod drain;
pub(crate) mod drain_wait;
pub(crate) mod handler;
pub(crate) mod header;
pub mod health;
pub(crate) mod hostkey;
pub mod leaderboard;
pub(crate) mod lifecycle;
pub mod limits;
pub(crate) mod link_echo;
pub(crate) mod link_pacer;
pub(crate) mod link_probe;
pub mod log;
pub(crate) mod metrics;
pub(crate) mod metrics_http;
pub(crate) mod process_stats;
pub(crate) mod proxy_header;
pub(crate) mod round_phase;
pub(crate) mod screen;
pub(crate) mod served_map;
pub mod server;
pub(crate) mod session;
pub(crate) mod stats;
pub(crate) mod world_task;

pub use config::ServeConfig;
pub use served_map::ServedMap;
pub use server::{run_until_signal, start, start_maps, RunningServer};
