//! The page's acknowledgements as link figures. A browser gives no back-pressure (a WebSocket
//! `send` completes when the bytes reach the socket, not when the page has drawn them), so the
//! page acks each frame once drawn, and the figures pacing reads from the kernel over SSH are
//! made here from those acks: bytes in flight are bytes sent less bytes acked, the round trip is
//! an ack's, the delivery rate a frame's bytes over its round trip.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

use crate::play::acks::Echoes;
use crate::play::link::LinkSample;

/// Frames at most remembered unacknowledged (pacing keeps far fewer in flight).
const MAX_UNACKED: usize = 64;
/// Weight of the newest round trip in the smoothed one.
const RTT_SMOOTHING: f64 = 0.125;

/// One frame sent and not yet acknowledged.
#[derive(Debug, Clone, Copy)]
struct Sent {
    n: u64,
    /// Bytes sent up to and with this frame.
    through: u64,
    at: Instant,
}

#[derive(Debug, Default)]
struct Book {
    sent: VecDeque<Sent>,
    frames: u64,
    bytes: u64,
    acked_n: u64,
    acked_bytes: u64,
    srtt: Option<Duration>,
    min_rtt: Option<Duration>,
    rate: u64,
}

/// Frames sent to one page and its acknowledgements, shared by the sink and the reader.
#[derive(Debug, Clone, Default)]
pub struct AckBook {
    book: Arc<Mutex<Book>>,
}

/// An acknowledgement that cannot be one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BadAck;

impl AckBook {
    /// Records frame `n` of `bytes` sent at `at`.
    pub fn sent(&self, n: u64, bytes: u64, at: Instant) {
        let mut b = self.book.lock().unwrap_or_else(PoisonError::into_inner);
        b.frames = n;
        b.bytes += bytes;
        let through = b.bytes;
        b.sent.push_back(Sent { n, through, at });
        if b.sent.len() > MAX_UNACKED {
            b.sent.pop_front();
        }
    }

    /// The page drew frame `n` (and so every frame before it) at `now`; tells `echoes` for the
    /// session's acknowledgement gate.
    ///
    /// # Errors
    /// [`BadAck`] for a frame that was never sent.
    pub fn acked(&self, n: u64, now: Instant, echoes: &Echoes) -> Result<(), BadAck> {
        let mut b = self.book.lock().unwrap_or_else(PoisonError::into_inner);
        if n > b.frames || n == 0 {
            return Err(BadAck);
        }
        if n <= b.acked_n {
            return Ok(());
        }
        let mut last = None;
        while b.sent.front().is_some_and(|s| s.n <= n) {
            last = b.sent.pop_front();
        }
        let Some(frame) = last else {
            b.acked_n = n;
            return Ok(());
        };
        let rtt = now.saturating_duration_since(frame.at);
        let size = frame.through - b.acked_bytes;
        b.acked_n = n;
        b.acked_bytes = frame.through;
        b.min_rtt = Some(b.min_rtt.map_or(rtt, |m| m.min(rtt)));
        b.srtt = Some(b.srtt.map_or(rtt, |s| {
            s.mul_f64(1.0 - RTT_SMOOTHING) + rtt.mul_f64(RTT_SMOOTHING)
        }));
        let secs = rtt.as_secs_f64().max(1e-4);
        b.rate = (size as f64 / secs) as u64;
        echoes.answered(n, rtt);
        Ok(())
    }

    /// The link as the acks tell it now.
    #[must_use]
    pub fn sample(&self) -> LinkSample {
        let b = self.book.lock().unwrap_or_else(PoisonError::into_inner);
        LinkSample {
            outstanding: b.bytes - b.acked_bytes,
            unsent: 0,
            rtt: b.srtt.unwrap_or_default(),
            delivery_rate: b.rate,
            // A frame's bytes over its round trip are at most what the link carries.
            app_limited: true,
            acked: b.acked_bytes,
            min_rtt: b.min_rtt.unwrap_or_default(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn acks_turn_into_bytes_in_flight_round_trips_and_a_rate() {
        let book = AckBook::default();
        let echoes = Echoes::default();
        let t = Instant::now();
        book.sent(1, 10_000, t);
        book.sent(2, 5_000, t + Duration::from_millis(10));
        assert_eq!(book.sample().outstanding, 15_000);
        assert_eq!(book.acked(3, t, &echoes), Err(BadAck));
        assert_eq!(book.acked(0, t, &echoes), Err(BadAck));
        book.acked(1, t + Duration::from_millis(100), &echoes)
            .unwrap();
        let s = book.sample();
        assert_eq!((s.outstanding, s.acked), (5_000, 10_000));
        assert_eq!(s.min_rtt, Duration::from_millis(100));
        assert_eq!(s.delivery_rate, 100_000);
        book.acked(2, t + Duration::from_millis(60), &echoes)
            .unwrap();
        let s = book.sample();
        assert_eq!(s.outstanding, 0);
        assert_eq!(s.min_rtt, Duration::from_millis(50));
        // An old ack again changes nothing.
        book.acked(1, t + Duration::from_secs(1), &echoes).unwrap();
        assert_eq!(book.sample().min_rtt, Duration::from_millis(50));
    }
}
