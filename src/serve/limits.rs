//! Admission control: at most N connections in all and M from one address, checked at accept.

use std::collections::HashMap;
use std::net::IpAddr;
use std::sync::{Arc, Mutex, PoisonError};

/// Why a connection was turned away.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refusal {
    Full,
    TooManyFromAddress,
}

#[derive(Debug, Default)]
struct Counts {
    total: usize,
    per_ip: HashMap<IpAddr, usize>,
}

/// Counts live connections; a [`Slot`] holds one place until dropped.
#[derive(Debug, Clone)]
pub struct Limiter {
    max_total: usize,
    max_per_ip: usize,
    counts: Arc<Mutex<Counts>>,
}

/// One admitted connection; dropping it frees the place.
#[derive(Debug)]
pub struct Slot {
    ip: IpAddr,
    counts: Arc<Mutex<Counts>>,
}

impl Limiter {
    /// A limiter for `max_total` connections, `max_per_ip` of them from one address.
    #[must_use]
    pub fn new(max_total: usize, max_per_ip: usize) -> Self {
        Self {
            max_total,
            max_per_ip,
            counts: Arc::default(),
        }
    }

    /// Admits a connection from `ip`, or says why not.
    ///
    /// # Errors
    /// [`Refusal`] when a limit is reached.
    pub fn admit(&self, ip: IpAddr) -> Result<Slot, Refusal> {
        let mut c = self.counts.lock().unwrap_or_else(PoisonError::into_inner);
        if c.total >= self.max_total {
            return Err(Refusal::Full);
        }
        let n = c.per_ip.entry(ip).or_insert(0);
        if *n >= self.max_per_ip {
            return Err(Refusal::TooManyFromAddress);
        }
        *n += 1;
        c.total += 1;
        Ok(Slot {
            ip,
            counts: Arc::clone(&self.counts),
        })
    }

    /// Connections admitted and not yet closed.
    #[must_use]
    pub fn live(&self) -> usize {
        self.counts
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .total
    }
}

impl Drop for Slot {
    fn drop(&mut self) {
        let mut c = self.counts.lock().unwrap_or_else(PoisonError::into_inner);
        c.total = c.total.saturating_sub(1);
        if let Some(n) = c.per_ip.get_mut(&self.ip) {
            *n = n.saturating_sub(1);
            if *n == 0 {
                c.per_ip.remove(&self.ip);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn totals_and_per_address_limits_hold_and_free_on_drop() {
        let l = Limiter::new(3, 2);
        let a: IpAddr = "127.0.0.1".parse().expect("ip");
        let b: IpAddr = "127.0.0.2".parse().expect("ip");
        let s1 = l.admit(a).expect("1");
        let _s2 = l.admit(a).expect("2");
        assert_eq!(l.admit(a).err(), Some(Refusal::TooManyFromAddress));
        let _s3 = l.admit(b).expect("3");
        assert_eq!(l.admit(b).err(), Some(Refusal::Full));
        drop(s1);
        assert_eq!(l.live(), 2);
        assert!(l.admit(a).is_ok());
    }
}
