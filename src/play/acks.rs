//! End-to-end acknowledgement of frames: the client answers for each frame once it has read it,
//! and the next frame goes only when enough were answered for the path's own round trip. The
//! transport says how the client answers: over SSH, a request that wants a reply, answered only
//! once everything before it was read (`cancel-tcpip-forward` for no forward, RFC 4254 §7.1, sent
//! behind a load balancer where the kernel's figures see only the first hop); a browser page acks
//! each frame it drew. A client that never answers the first one within [`FIRST_PATIENCE`] is
//! paced without acknowledgements.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How long the first echo may take before the client is taken not to answer them.
pub const FIRST_PATIENCE: Duration = Duration::from_secs(5);
/// The most frames a long path may keep in flight end to end.
const MAX_IN_FLIGHT: u64 = 4;

/// Echo state shared by a session and the tasks waiting for its echoes.
#[derive(Debug, Default)]
pub struct Echoes {
    /// The highest frame number the client has answered for.
    answered: AtomicU64,
    /// The least round trip of an echo, in microseconds (0: none yet).
    least_rtt_us: AtomicU64,
}

impl Echoes {
    /// The client answered the echo sent after frame `n`, `rtt` after it went.
    pub fn answered(&self, n: u64, rtt: Duration) {
        self.answered.fetch_max(n, Ordering::Relaxed);
        let us = (rtt.as_micros() as u64).max(1);
        let _ = self
            .least_rtt_us
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |old| {
                (old == 0 || us < old).then_some(us)
            });
    }
}

/// One session's view of its echoes: which frames went, which were answered.
#[derive(Debug)]
pub struct EchoGate {
    shared: Arc<Echoes>,
    sent: u64,
    first_sent: Option<Instant>,
    /// False once the client has shown it does not answer.
    on: bool,
}

impl EchoGate {
    /// A gate for a new session.
    #[must_use]
    pub fn new() -> Self {
        Self {
            shared: Arc::default(),
            sent: 0,
            first_sent: None,
            on: true,
        }
    }

    /// A gate that never holds a frame (echoes unused).
    #[must_use]
    pub fn off() -> Self {
        Self {
            on: false,
            ..Self::new()
        }
    }

    /// Whether echoes are still used (the client answers them).
    #[must_use]
    pub fn on(&self) -> bool {
        self.on
    }

    /// Records a frame handed over at `now`; returns its number and the shared state for the
    /// task that sends its echo and waits for the answer.
    pub fn sent(&mut self, now: Instant) -> (u64, Arc<Echoes>) {
        self.sent += 1;
        self.first_sent.get_or_insert(now);
        (self.sent, Arc::clone(&self.shared))
    }

    /// Whether the next frame may go as far as the client's answers say, with frames `period`
    /// apart: at most one more than the path's own round trip holds (at least one unanswered,
    /// at most [`MAX_IN_FLIGHT`]).
    pub fn clear(&mut self, period: Duration, now: Instant) -> bool {
        if !self.on {
            return true;
        }
        let answered = self.shared.answered.load(Ordering::Relaxed);
        if answered == 0
            && self
                .first_sent
                .is_some_and(|t| now.duration_since(t) >= FIRST_PATIENCE)
        {
            // No answer to the first echo: this client does not answer them.
            self.on = false;
            return true;
        }
        self.sent.saturating_sub(answered) < self.allowed(period)
    }

    /// Frames that may be unanswered at once.
    fn allowed(&self, period: Duration) -> u64 {
        let rtt_us = self.shared.least_rtt_us.load(Ordering::Relaxed);
        let period_us = period.as_micros().max(1) as u64;
        (1 + rtt_us / period_us).min(MAX_IN_FLIGHT)
    }

    /// The state the client's answers are told to, for a transport whose answers arrive on a
    /// task of their own (a browser page's acknowledgements, read beside the session).
    #[must_use]
    pub fn shared(&self) -> Arc<Echoes> {
        Arc::clone(&self.shared)
    }

    /// The least round trip an echo took, once one was answered.
    #[must_use]
    pub fn least_rtt(&self) -> Option<Duration> {
        match self.shared.least_rtt_us.load(Ordering::Relaxed) {
            0 => None,
            us => Some(Duration::from_micros(us)),
        }
    }
}

impl Default for EchoGate {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PERIOD: Duration = Duration::from_millis(33);

    #[test]
    fn one_frame_may_be_unanswered_on_a_short_path() {
        let t = Instant::now();
        let mut g = EchoGate::new();
        assert!(g.clear(PERIOD, t));
        let (n, shared) = g.sent(t);
        assert_eq!(n, 1);
        assert!(!g.clear(PERIOD, t), "frame 1 unanswered");
        shared.answered(1, Duration::from_millis(2));
        assert!(g.clear(PERIOD, t));
        assert_eq!(g.least_rtt(), Some(Duration::from_millis(2)));
    }

    #[test]
    fn a_long_path_keeps_as_many_frames_in_flight_as_its_round_trip_holds() {
        let t = Instant::now();
        let mut g = EchoGate::new();
        let (_, shared) = g.sent(t);
        // 100 ms round trip at 33 ms a frame: three more frames while the first is answered.
        shared.answered(1, Duration::from_millis(100));
        for _ in 0..4 {
            assert!(g.clear(PERIOD, t));
            g.sent(t);
        }
        assert!(!g.clear(PERIOD, t), "four unanswered is the most");
        shared.answered(3, Duration::from_millis(400));
        assert!(
            g.clear(PERIOD, t),
            "a slow answer does not raise the least round trip"
        );
    }

    #[test]
    fn a_client_that_never_answers_is_paced_without_echoes() {
        let t = Instant::now();
        let mut g = EchoGate::new();
        g.sent(t);
        assert!(!g.clear(PERIOD, t + Duration::from_secs(1)));
        assert!(g.on());
        assert!(g.clear(PERIOD, t + FIRST_PATIENCE));
        assert!(!g.on());
    }
}
