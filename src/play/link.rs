//! What a transport may know of its link to the client: the figures pacing reads before each
//! frame ([`super::pacing`]). The SSH edge reads them from the kernel; a transport that cannot
//! measure them gives none, and frames are paced on its own writes and acknowledgements alone.

use std::time::Duration;

/// One reading of a link's send side, in TCP's terms (what the kernel reports for a socket;
/// a transport without such figures reports none).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LinkSample {
    /// Bytes written to the socket and not yet acknowledged by the client (unsent included).
    pub outstanding: u64,
    /// Of those, bytes not yet sent at all.
    pub unsent: u64,
    /// Smoothed round trip.
    pub rtt: Duration,
    /// The kernel's latest delivery-rate sample, in bytes per second.
    pub delivery_rate: u64,
    /// Whether that sample was taken while the sender had too little to send (it then says less
    /// than the link could carry).
    pub app_limited: bool,
    /// Bytes acknowledged since the connection opened.
    pub acked: u64,
    /// The least round trip seen: the path's own delay, without queues (ours included).
    pub min_rtt: Duration,
}
