//! One player's game over any transport: input events in, the world's snapshots followed, frames
//! out through a sink, paced to the link. No SSH, sockets or WebSocket here: a transport (the SSH
//! edge in `serve`, a browser edge) adapts its connection to [`sink::FrameSink`] and
//! [`input::Input`] and runs [`session::run`].
//!
//! - [`session`]: the loop, given a [`setup`] (when to draw, idle and stall rules, the frame-rate cap),
//!   giving back an [`end`];
//!   [`player`]: what one client has on screen (keys, whom it watches, what a frame is drawn
//!   from); [`header_text`] and [`header_fit`]: the header row; [`screen`] and [`avatars`]: the
//!   panes with the other players in them.
//! - [`pacing`]: when the next frame may go and the colour level's steps, from [`link`] figures
//!   and the client's acknowledgements ([`acks`]); [`link_text`]: those figures for people.
//! - [`sink`], [`input`], [`hooks`], [`world_port`]: what a session is given: where frames go,
//!   what the client sends, the server's metrics and leaderboard, the world's inbox and snapshots.
//! - [`size`]: the terminal sizes drawn.

pub mod acks;
pub(crate) mod avatars;
pub mod end;
pub(crate) mod header_fit;
mod header_text;
pub mod hooks;
pub mod input;
pub mod link;
pub mod link_text;
pub mod pacing;
mod player;
mod ray_debug;
pub(crate) mod screen;
pub mod session;
pub mod setup;
pub mod sink;
pub mod size;
pub mod world_port;

#[cfg(test)]
mod session_tests;
