//! The one thing a transport gives a play session: somewhere to put frames, and word of how they
//! are getting on. The SSH edge writes to a channel and asks the kernel and the client; a browser
//! edge sends WebSocket messages and counts the page's acknowledgements; a test scripts a link.

use std::future::Future;
use std::time::{Duration, Instant};

use super::link::LinkSample;

/// The client is gone: nothing more can be sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Gone;

/// What a session tells a client that reads more than frames (a browser page draws its own ray
/// debugger): where the 3D view is on its screen, and the ray it debugs.
#[derive(Debug, Clone, PartialEq)]
pub enum Note {
    /// The 3D view's cells in the screen grid (0-based), told whenever they change.
    View {
        x: u16,
        y: u16,
        cols: u16,
        rows: u16,
    },
    /// The ray this player debugs, in the terms `halfcast trace` takes it.
    Ray(RayQuery),
}

/// One column's ray as `halfcast trace` takes it: `--pos X,Y --angle A --column C --size
/// COLSxROWS --fov F` on the map played.
#[derive(Debug, Clone, PartialEq)]
pub struct RayQuery {
    pub pos: (f64, f64),
    /// Degrees, 0 east, 90 north.
    pub angle: f64,
    pub column: usize,
    /// The 3D view's size in cells.
    pub size: (u16, u16),
    /// The horizontal field of view in degrees.
    pub fov: f64,
    /// Which of the served maps (by its place in the rotation).
    pub map: usize,
}

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

    /// Whether the link holds the colour level below where it would be (a step down for the
    /// link), told before each frame: a transport that can shrink its frames (the browser's
    /// compression) does so rather than let the level drop. By default nothing changes.
    fn level_held_down(&mut self, by_link: bool) {
        let _ = by_link;
    }

    /// The wire's share of the encoder's bytes the transport could bring its frames to if the
    /// link needs them smaller than they go now (the browser's compression, while frames go
    /// raw), or `None`: pacing then asks [`FrameSink::shrink`] before it drops the colour level.
    fn could_shrink(&self) -> Option<f64> {
        None
    }

    /// The link does not carry frames this size at the least frame rate: make the next ones as
    /// small as [`FrameSink::could_shrink`] said.
    fn shrink(&mut self) {}

    /// Tells the client `note`; a terminal reads only frames, so by default nothing is sent.
    fn note(&mut self, note: Note) -> impl Future<Output = Result<(), Gone>> + Send {
        let _ = note;
        std::future::ready(Ok(()))
    }
}
