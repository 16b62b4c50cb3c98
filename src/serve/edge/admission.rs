//! Who may come in: a connection admitted within the limits and numbered, or refused with its
//! log line, metric and counter, the same for every transport and every kind of refusal.

use std::fmt::Display;
use std::net::SocketAddr;
use std::sync::atomic::Ordering;

use crate::serve::limits::{Pending, Playing, Refusal};
use crate::serve::ops::metrics::{self, Reason};
use crate::serve::ops::stats::ServeStats;
use crate::serve::shared::Shared;

/// Turns a connection away: logged (with its session number once it has one), counted by
/// reason, and added to the refused total. The transport tells its client in its own words.
pub fn refuse(
    shared: &Shared,
    id: Option<u64>,
    peer: SocketAddr,
    reason: Reason,
    why: impl Display,
) {
    ServeStats::add(&shared.stats.refused, 1);
    metrics::refused(reason);
    shared.log.refusal(id, peer, reason.label(), why);
}

/// A place logging in for a new connection from `peer`, or its refusal (already logged and
/// counted, with how many log in and play now).
///
/// # Errors
/// The refusal to tell the client (server full, too many from one address, start-up limit).
pub fn admit(shared: &Shared, peer: SocketAddr) -> Result<Pending, Refusal> {
    shared.limiter.admit(peer.ip()).inspect_err(|why| {
        let (logging_in, playing) = shared.limiter.live();
        let detail = format_args!("{why} ({logging_in} logging in, {playing} playing)");
        refuse(shared, None, peer, why.reason(), detail);
    })
}

/// The playing place for an admitted connection, or its refusal (already logged and counted).
///
/// # Errors
/// The refusal to tell the client (the server filled up while it logged in).
pub fn take_place(
    shared: &Shared,
    (id, peer): (Option<u64>, SocketAddr),
    pending: &Pending,
) -> Result<Playing, Refusal> {
    pending
        .promote()
        .inspect_err(|why| refuse(shared, id, peer, why.reason(), why))
}

/// An admitted connection counted and given its number (unique across transports); its first
/// log line.
pub fn connected(shared: &Shared, peer: SocketAddr) -> u64 {
    ServeStats::add(&shared.stats.connections, 1);
    metrics::connected();
    let id = shared.next_id.fetch_add(1, Ordering::Relaxed);
    shared.log.connect(id, peer);
    id
}
