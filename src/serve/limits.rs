//! Admission control, in two populations: connections still logging in (TCP accept until the
//! shell starts) and sessions that play or watch.
//!
//! Logging-in connections are capped like OpenSSH's `MaxStartups start:rate:full` (beyond
//! `start` of them, a newcomer is refused with probability `rate`% rising linearly to 100% at
//! `full`) and per source address; only playing or watching sessions count toward
//! `--max-sessions`. A connection moves from the first population to the second with
//! [`Pending::promote`], and every slot frees its place when dropped.

use std::collections::HashMap;
use std::fmt;
use std::net::IpAddr;
use std::str::FromStr;
use std::sync::{Arc, Mutex, PoisonError};

/// Why a connection was turned away; its `Display` is the line the client is shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refusal {
    /// `--max-sessions` sessions already play or watch (the limit is carried for the message).
    Full(usize),
    /// `--max-per-ip` connections from this address, or its share of logging-in ones.
    TooManyFromAddress,
    /// Too many connections are logging in at once (`--max-startups`).
    TooManyStartups,
}

impl Refusal {
    /// The metrics and log label for this refusal.
    #[must_use]
    pub fn reason(&self) -> super::ops::metrics::Reason {
        use super::ops::metrics::Reason;
        match self {
            Self::Full(_) => Reason::Full,
            Self::TooManyFromAddress => Reason::PerAddress,
            Self::TooManyStartups => Reason::Startups,
        }
    }
}

impl fmt::Display for Refusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Full(n) => write!(f, "server full ({n} players), try later"),
            Self::TooManyFromAddress => f.write_str("too many connections from your address"),
            Self::TooManyStartups => f.write_str("too many connections logging in, try later"),
        }
    }
}

/// OpenSSH's `MaxStartups start:rate:full`: how many logging-in connections are let in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Startups {
    /// Up to this many, every newcomer is admitted.
    pub start: usize,
    /// Refusal probability (percent) for the first newcomer beyond `start`.
    pub rate: u32,
    /// At this many, every newcomer is refused.
    pub full: usize,
}

impl Startups {
    /// The chance in percent (0..=100) that a newcomer is refused while `pending` connections
    /// are logging in: 0 below `start`, `rate` at `start`, rising linearly to 100 at `full`.
    #[must_use]
    pub fn refusal_percent(&self, pending: usize) -> u32 {
        if pending < self.start {
            return 0;
        }
        if pending >= self.full {
            return 100;
        }
        let span = (self.full - self.start) as u64;
        let over = (pending - self.start) as u64;
        let extra = u64::from(100 - self.rate) * over / span;
        self.rate + u32::try_from(extra).unwrap_or(100)
    }
}

impl FromStr for Startups {
    type Err = String;

    /// `N` (refuse beyond N) or `start:rate:full` with start ≤ full, 1 ≤ rate ≤ 100.
    fn from_str(s: &str) -> Result<Self, String> {
        let num = |t: &str| -> Result<usize, String> {
            t.trim()
                .parse::<usize>()
                .map_err(|_| format!("{t:?} is not a whole number"))
        };
        let parts: Vec<&str> = s.split(':').collect();
        let st = match parts.as_slice() {
            [n] => {
                let n = num(n)?;
                Self {
                    start: n,
                    rate: 100,
                    full: n,
                }
            }
            [a, r, f] => Self {
                start: num(a)?,
                rate: u32::try_from(num(r)?).unwrap_or(u32::MAX),
                full: num(f)?,
            },
            _ => return Err(format!("{s:?}: expected N or start:rate:full")),
        };
        if st.start == 0 {
            return Err(format!("{s:?}: start must be at least 1"));
        }
        if st.full < st.start {
            return Err(format!("{s:?}: full must not be below start"));
        }
        if !(1..=100).contains(&st.rate) {
            return Err(format!("{s:?}: rate must be a percentage from 1 to 100"));
        }
        Ok(st)
    }
}

impl fmt::Display for Startups {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.start, self.rate, self.full)
    }
}

/// The caps an operator sets.
#[derive(Debug, Clone, Copy)]
pub struct Caps {
    /// Sessions playing or watching.
    pub max_sessions: usize,
    /// Connections (logging in or playing) from one address.
    pub max_per_ip: usize,
    /// Logging-in connections in all.
    pub startups: Startups,
    /// Logging-in connections from one address.
    pub startups_per_ip: usize,
}

#[derive(Debug, Default)]
struct Counts {
    pending: usize,
    playing: usize,
    /// Per address: (all connections, logging-in ones).
    per_ip: HashMap<IpAddr, (usize, usize)>,
    /// xorshift64 state for the random early refusal (seeded, so tests are repeatable).
    rng: u64,
}

impl Counts {
    fn roll_percent(&mut self) -> u32 {
        let mut x = self.rng;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.rng = x;
        u32::try_from(x % 100).unwrap_or(0)
    }

    fn release(&mut self, ip: IpAddr, pending: bool) {
        if pending {
            self.pending = self.pending.saturating_sub(1);
        } else {
            self.playing = self.playing.saturating_sub(1);
        }
        if let Some((all, p)) = self.per_ip.get_mut(&ip) {
            *all = all.saturating_sub(1);
            if pending {
                *p = p.saturating_sub(1);
            }
            if *all == 0 {
                self.per_ip.remove(&ip);
            }
        }
    }
}

/// Counts live connections in both populations.
#[derive(Debug, Clone)]
pub struct Limiter {
    caps: Caps,
    counts: Arc<Mutex<Counts>>,
}

/// A connection still logging in; dropping it frees its place.
#[derive(Debug)]
pub struct Pending {
    ip: IpAddr,
    limiter: Limiter,
}

/// A session that plays or watches; dropping it frees its place.
#[derive(Debug)]
pub struct Playing {
    ip: IpAddr,
    limiter: Limiter,
}

impl Limiter {
    /// A limiter with these caps; `seed` drives the random early refusal.
    #[must_use]
    pub fn new(caps: Caps, seed: u64) -> Self {
        let counts = Counts {
            rng: seed | 1,
            ..Counts::default()
        };
        Self {
            caps,
            counts: Arc::new(Mutex::new(counts)),
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Counts> {
        self.counts.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Admits a new TCP connection from `ip` into the logging-in population, or says why not.
    ///
    /// # Errors
    /// [`Refusal`] when a cap is reached or the random early refusal picks it.
    pub fn admit(&self, ip: IpAddr) -> Result<Pending, Refusal> {
        let mut c = self.lock();
        let (all, pending) = c.per_ip.get(&ip).copied().unwrap_or((0, 0));
        if all >= self.caps.max_per_ip || pending >= self.caps.startups_per_ip {
            return Err(Refusal::TooManyFromAddress);
        }
        // A full server still lets newcomers log in (within the caps above), so that they
        // hear "server full" in an SSH disconnect message, which clients print.
        let p = self.caps.startups.refusal_percent(c.pending);
        if p > 0 && (p >= 100 || c.roll_percent() < p) {
            return Err(Refusal::TooManyStartups);
        }
        c.pending += 1;
        let e = c.per_ip.entry(ip).or_insert((0, 0));
        e.0 += 1;
        e.1 += 1;
        drop(c);
        super::ops::metrics::logging_in(true);
        Ok(Pending {
            ip,
            limiter: self.clone(),
        })
    }

    /// (logging in, playing or watching) now.
    #[must_use]
    pub fn live(&self) -> (usize, usize) {
        let c = self.lock();
        (c.pending, c.playing)
    }

    /// Whether a session could start now (a check before one is asked for, e.g. at login).
    ///
    /// # Errors
    /// [`Refusal::Full`] when every session place is taken.
    pub fn has_room(&self) -> Result<(), Refusal> {
        if self.lock().playing >= self.caps.max_sessions {
            return Err(Refusal::Full(self.caps.max_sessions));
        }
        Ok(())
    }
}

impl Pending {
    /// Turns this logging-in connection into a playing session, if there is room.
    ///
    /// # Errors
    /// [`Refusal::Full`] (and the connection keeps its logging-in place until dropped).
    pub fn promote(&self) -> Result<Playing, Refusal> {
        let mut c = self.limiter.lock();
        if c.playing >= self.limiter.caps.max_sessions {
            return Err(Refusal::Full(self.limiter.caps.max_sessions));
        }
        c.playing += 1;
        if let Some(e) = c.per_ip.get_mut(&self.ip) {
            e.0 += 1;
        }
        drop(c);
        Ok(Playing {
            ip: self.ip,
            limiter: self.limiter.clone(),
        })
    }
}

impl Drop for Pending {
    fn drop(&mut self) {
        self.limiter.lock().release(self.ip, true);
        super::ops::metrics::logging_in(false);
    }
}

impl Drop for Playing {
    fn drop(&mut self) {
        self.limiter.lock().release(self.ip, false);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn caps(max_sessions: usize, max_per_ip: usize, startups: &str, per_ip: usize) -> Caps {
        Caps {
            max_sessions,
            max_per_ip,
            startups: startups.parse().expect("startups"),
            startups_per_ip: per_ip,
        }
    }

    fn ip(last: u8) -> IpAddr {
        IpAddr::from([127, 0, 0, last])
    }

    #[test]
    fn startups_parse_like_openssh() {
        let s: Startups = "10:30:60".parse().expect("parse");
        assert_eq!((s.start, s.rate, s.full), (10, 30, 60));
        assert_eq!(s.to_string(), "10:30:60");
        let n: Startups = "5".parse().expect("parse");
        assert_eq!((n.start, n.rate, n.full), (5, 100, 5));
        for bad in [
            "",
            "a",
            "10:30",
            "60:30:10",
            "10:0:60",
            "10:101:60",
            "0:30:60",
        ] {
            assert!(bad.parse::<Startups>().is_err(), "{bad:?} must be refused");
        }
    }

    #[test]
    fn refusal_rises_linearly_from_rate_at_start_to_all_at_full() {
        let s: Startups = "10:30:60".parse().expect("parse");
        assert_eq!(s.refusal_percent(0), 0);
        assert_eq!(s.refusal_percent(9), 0);
        assert_eq!(s.refusal_percent(10), 30);
        assert_eq!(s.refusal_percent(35), 65);
        assert_eq!(s.refusal_percent(59), 98);
        assert_eq!(s.refusal_percent(60), 100);
        assert_eq!(s.refusal_percent(1000), 100);
    }

    #[test]
    fn random_early_refusal_matches_its_probability() {
        // 20 logging in under 10:50:30 → 75% refused; seeded, so the count is repeatable.
        let l = Limiter::new(caps(100, 1000, "10:50:30", 1000), 7);
        let mut held = Vec::new();
        while held.len() < 20 {
            if let Ok(p) = l.admit(ip(1)) {
                held.push(p);
            }
        }
        let mut refused = 0;
        for _ in 0..1000 {
            match l.admit(ip(2)) {
                Ok(p) => drop(p),
                Err(r) => {
                    assert_eq!(r, Refusal::TooManyStartups);
                    refused += 1;
                }
            }
        }
        assert!((700..=800).contains(&refused), "{refused} of 1000 refused");
    }

    #[test]
    fn only_playing_sessions_count_toward_max_sessions() {
        let l = Limiter::new(caps(2, 8, "3", 3), 1);
        let a = l.admit(ip(1)).expect("a");
        let b = l.admit(ip(2)).expect("b");
        let c = l.admit(ip(3)).expect("c");
        assert_eq!(l.admit(ip(4)).err(), Some(Refusal::TooManyStartups));
        let pa = a.promote().expect("a plays");
        drop(a);
        let pb = b.promote().expect("b plays");
        drop(b);
        assert_eq!(l.live(), (1, 2));
        assert_eq!(c.promote().err(), Some(Refusal::Full(2)));
        assert_eq!(l.has_room(), Err(Refusal::Full(2)));
        drop(pa);
        assert!(c.promote().is_ok());
        drop(pb);
    }

    #[test]
    fn per_address_caps_hold_for_all_and_for_logging_in_connections() {
        let l = Limiter::new(caps(10, 3, "10", 2), 1);
        let a1 = l.admit(ip(1)).expect("1");
        let a2 = l.admit(ip(1)).expect("2");
        assert_eq!(l.admit(ip(1)).err(), Some(Refusal::TooManyFromAddress));
        let p1 = a1.promote().expect("plays");
        drop(a1);
        let a3 = l
            .admit(ip(1))
            .expect("3: one of the address's two is playing now");
        assert_eq!(l.admit(ip(1)).err(), Some(Refusal::TooManyFromAddress));
        assert!(l.admit(ip(2)).is_ok(), "another address is not affected");
        drop((a2, a3, p1));
        assert_eq!(l.live(), (0, 0));
        assert!(l.lock().per_ip.is_empty(), "no address is remembered");
    }

    #[test]
    fn refusals_read_as_reasons() {
        assert_eq!(
            Refusal::Full(32).to_string(),
            "server full (32 players), try later"
        );
        assert_eq!(
            Refusal::TooManyFromAddress.to_string(),
            "too many connections from your address"
        );
    }
}
