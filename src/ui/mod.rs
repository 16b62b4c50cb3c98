//! The game screen, with no transport in it: the local terminal (`tui`), the SSH server
//! (`serve`) and on-screen replays all draw and read keys through this one room, so a change here
//! shows the same for every player.
//!
//! - Drawing: [`layout`] splits the screen into panes, [`render`] paints the 3D view, [`screen`]
//!   lays every pane into a ratatui buffer, with the [`status`] line, the [`help`] and
//!   [`results`] boxes ([`centred_box`]) and the frame figures ([`stats`]).
//! - Keys: [`key_bytes`] reads keystrokes from a raw byte stream (an SSH channel, or a terminal's
//!   bytes), [`key_route`] sends them to the session or the game, [`keymap`] binds keys to
//!   actions, [`keys`] turns key events into a game `Input` and [`UiCommand`]s, [`repeat`] tells
//!   a held key from a tapped one where the terminal sends no releases.
//! - [`colour_query`]: asking a terminal whether it shows 24-bit colour (and whether it is PuTTY),
//!   over any byte stream, and the rules that turn its answers into a colour level.
//! - Glyphs: `octant_support` tells from a session's environment whether octants are known to
//!   be dropped on the way to the screen (tmux), and `glyph_cycle` is the glyph key's cycle
//!   that then skips them.
//! - [`replay_player`]: a recording played headlessly through these same screens.

pub mod centred_box;
pub mod colour_query;
// The game and the SSH sessions own a glyph cycle each and read their terminal's octant
// support; with `ui` alone (on-screen replays) neither is used.
pub mod frame_grid;
#[cfg(any(feature = "tui", feature = "serve", test))]
pub(crate) mod glyph_cycle;
pub mod help;
pub mod key_bytes;
pub mod key_route;
pub mod keymap;
pub mod keys;
pub mod layout;
pub mod notice;
#[cfg(any(feature = "tui", feature = "serve", test))]
pub(crate) mod octant_support;
pub mod render;
pub mod repeat;
pub mod replay_player;
pub mod results;
pub mod screen;
pub mod stats;
pub mod status;

pub use crate::replay::format::UiCommand;
pub use stats::FrameStats;
