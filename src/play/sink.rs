//! The one thing a transport gives a play session: somewhere to put frames, and word of how they
//! are getting on. The SSH edge writes to a channel and asks the kernel and the client; a browser
//! edge sends WebSocket messages and counts the page's acknowledgements; a test scripts a link.

use std::future::Future;
use std::time::{Duration, Instant};

use super::link::LinkSample;

/// The client is gone: nothing more can be sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Gone;

/// Where a session's frames go, and what is known of their arrival.
pub trait FrameSink: Send {
    /// Hands one frame's bytes to the transport; ready once it has taken them (they are on their
    /// way, not yet arrived). The session bounds the wait by its stall timeout.
    fn send(&mut self, frame: Vec<u8>) -> impl Future<Output = Result<(), Gone>> + Send;

    /// Bytes the transport has put on the wire so far: a frame has left once this passes what it
    /// was when the frame was handed over.
    fn written(&self) -> u64;

    /// What the transport measures of its link now (bytes in flight, round trip, delivery
    /// rate), or `None` if it cannot. Asked only when pacing needs it, as it may cost a system
    /// call.
    fn sample(&mut self) -> Option<LinkSample>;

    /// Whether the client itself has acknowledged enough of the frames sent for one more to go,
    /// frames being `period` apart. A transport without acknowledgements says yes.
    fn answered(&mut self, period: Duration, now: Instant) -> bool;

    /// The least round trip of the client's acknowledgements, once one came.
    fn acked_rtt(&self) -> Option<Duration>;

    /// Whether [`FrameSink::sample`] gives figures at all (the header shows the link's figures
    /// only then).
    fn measures(&self) -> bool;
}
