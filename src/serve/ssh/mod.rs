//! The SSH edge: russh's connections turned into play sessions. [`handler`] answers the
//! protocol (auth, pty, resize, refusals), [`auth`] and [`hostkey`] say who may connect and who
//! we are, [`ask_colour`] asks a terminal what it draws, [`session`] runs a play session over the
//! channel with [`sink`] as its frame sink, whose arrival figures come from the kernel
//! ([`link_probe`]); [`lifeline`] is one connection's kill switch and byte counts. Admission,
//! the session's run and its end are the one way in ([`crate::serve::edge`]).

pub(crate) mod ask_colour;
pub mod auth;
pub(crate) mod handler;
pub(crate) mod hostkey;
pub(crate) mod lifeline;
pub(crate) mod link_probe;
pub(crate) mod listener;
pub(crate) mod session;
pub(crate) mod sink;
