//! Who may connect: anyone (the default), holders of one password, or listed public keys.

use std::fmt;
use std::path::Path;

use russh::keys::ssh_key::AuthorizedKeys;
use russh::keys::PublicKey;
use russh::{MethodKind, MethodSet};

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
        let text = std::fs::read_to_string(path)
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

#[cfg(test)]
mod tests {
    use super::*;

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
