//! Who may connect: anyone (the default), holders of one password, or listed public keys.

use std::collections::HashMap;
use std::fmt;
use std::net::IpAddr;
use std::path::Path;
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

use russh::keys::ssh_key::AuthorizedKeys;
use russh::keys::PublicKey;
use russh::{MethodKind, MethodSet};

use crate::input_file::read_regular_text;

/// Most bytes an `authorized_keys` file may hold (tens of thousands of keys).
pub const MAX_AUTHORIZED_KEYS_BYTES: u64 = 16 << 20;

/// Most bytes a password file may hold (only its first line is used).
pub const MAX_PASSWORD_FILE_BYTES: u64 = 64 << 10;

/// The authentication mode chosen on the command line.
#[derive(Clone, Default)]
pub enum AuthMode {
    /// No authentication: any user name gets in (`ssh -p 2222 host`).
    #[default]
    None,
    /// SSH password authentication against this one password.
    Password(String),
    /// Public-key authentication against the keys of an `authorized_keys` file.
    AuthorizedKeys(Vec<PublicKey>),
}

impl fmt::Debug for AuthMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::None => f.write_str("None"),
            Self::Password(_) => f.write_str("Password(<hidden>)"),
            Self::AuthorizedKeys(keys) => write!(f, "AuthorizedKeys({} keys)", keys.len()),
        }
    }
}

impl AuthMode {
    /// Reads an OpenSSH `authorized_keys` file (options before a key are accepted and ignored).
    ///
    /// # Errors
    /// A message naming the file and line when it cannot be read or a line is not a key, or when
    /// it holds no key at all.
    pub fn from_authorized_keys(path: &Path) -> Result<Self, String> {
        let text = read_regular_text(path, MAX_AUTHORIZED_KEYS_BYTES)
            .map_err(|e| format!("authorized keys {}: {e}", path.display()))?;
        let mut keys = Vec::new();
        for (n, line) in text.lines().enumerate() {
            let t = line.trim();
            if t.is_empty() || t.starts_with('#') {
                continue;
            }
            let entry = AuthorizedKeys::new(t)
                .next()
                .ok_or_else(|| format!("{}:{}: not a public key", path.display(), n + 1))?
                .map_err(|e| format!("{}:{}: not a public key ({e})", path.display(), n + 1))?;
            keys.push(entry.public_key().clone());
        }
        if keys.is_empty() {
            return Err(format!(
                "authorized keys {}: no keys in the file",
                path.display()
            ));
        }
        Ok(Self::AuthorizedKeys(keys))
    }

    /// The methods offered to clients.
    #[must_use]
    pub fn methods(&self) -> MethodSet {
        let kind = match self {
            Self::None => MethodKind::None,
            Self::Password(_) => MethodKind::Password,
            Self::AuthorizedKeys(_) => MethodKind::PublicKey,
        };
        MethodSet::from(&[kind][..])
    }

    /// Whether a client that sent no credentials gets in.
    #[must_use]
    pub fn allows_none(&self) -> bool {
        matches!(self, Self::None)
    }

    /// Whether `given` is the password (compared in time independent of where it differs).
    #[must_use]
    pub fn allows_password(&self, given: &str) -> bool {
        let Self::Password(want) = self else {
            return false;
        };
        let (a, b) = (want.as_bytes(), given.as_bytes());
        let mut diff = u8::from(a.len() != b.len());
        for i in 0..a.len().max(b.len()) {
            diff |= a.get(i).copied().unwrap_or(0) ^ b.get(i).copied().unwrap_or(0xff);
        }
        diff == 0
    }

    /// Whether `key` is one of the authorized keys (comments don't matter).
    #[must_use]
    pub fn allows_key(&self, key: &PublicKey) -> bool {
        match self {
            Self::AuthorizedKeys(keys) => keys.iter().any(|k| k.key_data() == key.key_data()),
            _ => false,
        }
    }
}

/// Failed logins per source address, to slow guessing down: each failure from an address waits
/// longer before its rejection is sent (see [`Backoff::delay_after`]); an address with no failure
/// for [`Backoff::FORGET`] starts over.
#[derive(Debug, Default)]
pub struct Backoff {
    /// Address → (recent failures, time of the last one).
    failures: Mutex<HashMap<IpAddr, (u32, Instant)>>,
}

impl Backoff {
    /// First failure's delay; each further one doubles it.
    pub const BASE: Duration = Duration::from_millis(100);
    /// The longest delay, reached after 8 failures in a row.
    pub const MAX: Duration = Duration::from_secs(10);
    /// Failures older than this are forgotten.
    pub const FORGET: Duration = Duration::from_secs(600);
    /// Addresses remembered at most (beyond, the stalest are forgotten), so memory is bounded.
    pub const CAPACITY: usize = 4096;

    /// How long the `n`th failure in a row (1-based) waits before the client hears it.
    #[must_use]
    pub fn delay_after(n: u32) -> Duration {
        let doublings = n.saturating_sub(1).min(16);
        (Self::BASE * (1u32 << doublings)).min(Self::MAX)
    }

    /// Records a failure from `ip` at `now`; returns how long to wait before rejecting.
    pub fn failed(&self, ip: IpAddr, now: Instant) -> Duration {
        let mut m = self.failures.lock().unwrap_or_else(PoisonError::into_inner);
        if m.len() >= Self::CAPACITY && !m.contains_key(&ip) {
            m.retain(|_, (_, last)| now.duration_since(*last) < Self::FORGET);
            if m.len() >= Self::CAPACITY {
                // Still full of recent guessers: drop the stalest half.
                let mut lasts: Vec<Instant> = m.values().map(|(_, t)| *t).collect();
                lasts.sort_unstable();
                let cut = lasts[lasts.len() / 2];
                m.retain(|_, (_, last)| *last > cut);
            }
        }
        let e = m.entry(ip).or_insert((0, now));
        if now.duration_since(e.1) >= Self::FORGET {
            e.0 = 0;
        }
        e.0 = e.0.saturating_add(1);
        e.1 = now;
        Self::delay_after(e.0)
    }

    /// Forgets `ip`'s failures (after it logged in).
    pub fn succeeded(&self, ip: IpAddr) {
        self.failures
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .remove(&ip);
    }

    /// Addresses remembered now.
    #[must_use]
    pub fn remembered(&self) -> usize {
        self.failures
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .len()
    }
}

/// Reads the password from a file: its first line, without the line ending.
///
/// # Errors
/// A message naming the file when it cannot be read or its first line is empty.
pub fn password_from_file(path: &Path) -> Result<String, String> {
    let text = read_regular_text(path, MAX_PASSWORD_FILE_BYTES)
        .map_err(|e| format!("password file {}: {e}", path.display()))?;
    let line = text.lines().next().unwrap_or("");
    if line.is_empty() {
        return Err(format!(
            "password file {}: the first line is empty",
            path.display()
        ));
    }
    Ok(line.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn backoff_doubles_per_failure_up_to_a_cap_and_forgets() {
        assert_eq!(Backoff::delay_after(1), Duration::from_millis(100));
        assert_eq!(Backoff::delay_after(2), Duration::from_millis(200));
        assert_eq!(Backoff::delay_after(6), Duration::from_millis(3200));
        assert_eq!(Backoff::delay_after(8), Backoff::MAX);
        assert_eq!(Backoff::delay_after(u32::MAX), Backoff::MAX);
        let b = Backoff::default();
        let (a, other): (IpAddr, IpAddr) =
            ("127.0.0.2".parse().expect("ip"), "::1".parse().expect("ip"));
        let t = Instant::now();
        let waits: Vec<Duration> = (0..4).map(|_| b.failed(a, t)).collect();
        assert_eq!(waits[3], Duration::from_millis(800), "{waits:?}");
        assert_eq!(b.failed(other, t), Backoff::BASE, "per address");
        assert_eq!(b.failed(a, t + Backoff::FORGET), Backoff::BASE, "forgotten");
        b.succeeded(a);
        assert_eq!(b.failed(a, t), Backoff::BASE);
    }

    #[test]
    fn backoff_memory_is_bounded() {
        let b = Backoff::default();
        let t = Instant::now();
        for i in 0..(Backoff::CAPACITY as u32 * 3) {
            b.failed(
                IpAddr::from(i.to_be_bytes()),
                t + Duration::from_millis(u64::from(i)),
            );
        }
        assert!(b.remembered() <= Backoff::CAPACITY, "{}", b.remembered());
    }

    #[test]
    fn password_file_gives_its_first_line() {
        let dir = tempfile::tempdir().expect("tempdir");
        let p = dir.path().join("pw");
        std::fs::write(&p, "open sesame\nsecond line\n").expect("write");
        assert_eq!(password_from_file(&p).expect("read"), "open sesame");
        std::fs::write(&p, "\n").expect("write");
        assert!(password_from_file(&p)
            .expect_err("empty")
            .contains("first line is empty"));
        assert!(password_from_file(&dir.path().join("none")).is_err());
    }

    const KEY: &str = "ssh-ed25519 AAAAC3NzaC1lZDI1NTE5AAAAIOMqqnkVzrm0SdG6UOoqKLsabgH5C9okWi0dh2l9GKJl user@host";

    #[test]
    fn password_must_match_exactly() {
        let m = AuthMode::Password("sesame".into());
        assert!(m.allows_password("sesame"));
        assert!(!m.allows_password("sesam"));
        assert!(!m.allows_password("sesame!"));
        assert!(!m.allows_password(""));
        assert!(!AuthMode::None.allows_password("sesame"));
        assert!(!format!("{m:?}").contains("sesame"));
    }

    #[test]
    fn authorized_keys_file_is_read_and_bad_lines_named() {
        let dir = tempfile::tempdir().expect("tempdir");
        let good = dir.path().join("ak");
        std::fs::write(&good, format!("# comment\n\nno-pty {KEY}\n")).expect("write");
        let m = AuthMode::from_authorized_keys(&good).expect("parse");
        let key = PublicKey::from_openssh(KEY).expect("key");
        assert!(m.allows_key(&key));
        let bad = dir.path().join("bad");
        std::fs::write(&bad, format!("{KEY}\nnonsense here\n")).expect("write");
        let err = AuthMode::from_authorized_keys(&bad).expect_err("bad line");
        assert!(err.contains(":2:"), "{err}");
        let empty = dir.path().join("empty");
        std::fs::write(&empty, "# nothing\n").expect("write");
        assert!(AuthMode::from_authorized_keys(&empty).is_err());
    }
}
