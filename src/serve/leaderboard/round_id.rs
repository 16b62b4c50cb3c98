//! A round's identity: a world's random prefix (drawn at start) and a count, so two worlds, or
//! one world before and after a restart, never give two rounds one identity. The stores keep it
//! unique, which is what lets a queued round be sent again without being counted twice.

/// Hands out round identities for one world.
#[derive(Debug)]
pub struct RoundIds {
    prefix: String,
    next: u64,
}

impl RoundIds {
    /// A new series: 64 random bits from the OS (the clock and the process id where it has
    /// none).
    #[must_use]
    pub fn new() -> Self {
        let mut bytes = [0u8; 8];
        let random = if getrandom::fill(&mut bytes).is_ok() {
            u64::from_ne_bytes(bytes)
        } else {
            let nanos = std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos() as u64);
            nanos ^ u64::from(std::process::id()).rotate_left(40)
        };
        Self {
            prefix: format!("{random:016x}"),
            next: 0,
        }
    }

    /// The next round's identity (`0123456789abcdef-7`).
    pub fn next_id(&mut self) -> String {
        self.next += 1;
        format!("{}-{}", self.prefix, self.next)
    }
}

impl Default for RoundIds {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identities_differ_within_and_across_series() {
        let (mut a, mut b) = (RoundIds::new(), RoundIds::new());
        let ids = [a.next_id(), a.next_id(), b.next_id()];
        assert_ne!(ids[0], ids[1]);
        assert_ne!(ids[0], ids[2], "two worlds' first rounds");
        assert!(ids[0].ends_with("-1") && ids[1].ends_with("-2"));
    }
}
