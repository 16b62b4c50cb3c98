//! The server's identity: an Ed25519 host key, generated once and reused so clients never see a
//! changed host key on restart.

use std::fs;
use std::io::Write;
use std::path::Path;

use russh::keys::ssh_key::private::Ed25519Keypair;
use russh::keys::ssh_key::LineEnding;
use russh::keys::{HashAlg, PrivateKey};

/// Most bytes a host key file may hold (an OpenSSH RSA-16384 key is about 12 KB).
pub const MAX_HOST_KEY_BYTES: u64 = 1 << 20;

/// Reads the OpenSSH private key at `path`, or creates a new Ed25519 key there (mode 0600).
///
/// Returns the key and notes for the log (generated, fingerprint, loose permissions).
/// A key file that group or others may read is refused, as sshd does, unless `insecure`.
///
/// # Errors
/// A message naming the path when the file cannot be read, parsed or created, is encrypted, or
/// is readable by others (without `insecure`).
pub fn load_or_generate(path: &Path, insecure: bool) -> Result<(PrivateKey, Vec<String>), String> {
    let credentials = std::env::var_os(CREDENTIALS_DIRECTORY).map(std::path::PathBuf::from);
    load_or_generate_with(path, insecure, credentials.as_deref())
}

/// The environment variable naming the directory of systemd's credentials for the service
/// (`LoadCredential=`): how every world of a fleet gets the one host key.
pub const CREDENTIALS_DIRECTORY: &str = "CREDENTIALS_DIRECTORY";

/// [`load_or_generate`], with systemd's credentials directory given (`None`: not under systemd).
///
/// A key in that directory is systemd's copy of the fleet's key: the directory is the
/// service's alone, and systemd may grant the service read access with an ACL, whose mask
/// shows as group-read bits, so only bits for others refuse it there. It is never generated
/// there (a missing one is a unit missing its `LoadCredential=`).
///
/// # Errors
/// As [`load_or_generate`].
pub fn load_or_generate_with(
    path: &Path,
    insecure: bool,
    credentials: Option<&Path>,
) -> Result<(PrivateKey, Vec<String>), String> {
    let mut notes = Vec::new();
    let credential = credentials.is_some_and(|dir| path.starts_with(dir));
    let key = match crate::input_file::read_regular_text(path, MAX_HOST_KEY_BYTES) {
        Ok(text) => {
            let loose = loose_mode(path).filter(|m| !credential || m & 0o007 != 0);
            if let Some(mode) = loose {
                if !insecure {
                    return Err(format!(
                        "host key {} is readable by others (mode {mode:03o}); run chmod 600 {0} \
                         (or pass --insecure-host-key)",
                        path.display()
                    ));
                }
                notes.push(format!(
                    "warning: host key {} is readable by others (mode {mode:03o}), used because of \
                     --insecure-host-key",
                    path.display()
                ));
            }
            let key = PrivateKey::from_openssh(text.as_bytes()).map_err(|e| {
                format!(
                    "host key {}: not an OpenSSH private key ({e})",
                    path.display()
                )
            })?;
            if key.is_encrypted() {
                return Err(format!(
                    "host key {}: encrypted keys are not supported",
                    path.display()
                ));
            }
            key
        }
        Err(e) if e.is_not_found() && credential => {
            return Err(format!(
                "host key {}: no such credential; the unit needs \
                 LoadCredential=host_key:/etc/halfcast/host_ed25519 (docs/serving.md)",
                path.display()
            ))
        }
        Err(e) if e.is_not_found() => {
            let key = generate()?;
            write_private(path, &key)?;
            notes.push(format!("generated a new host key at {}", path.display()));
            key
        }
        Err(e) => return Err(format!("host key {}: {e}", path.display())),
    };
    notes.push(format!(
        "host key {} {}",
        key.algorithm().as_str(),
        key.public_key().fingerprint(HashAlg::Sha256)
    ));
    Ok((key, notes))
}

fn generate() -> Result<PrivateKey, String> {
    let mut seed = [0u8; 32];
    getrandom::fill(&mut seed).map_err(|e| format!("no randomness for a host key: {e}"))?;
    Ok(PrivateKey::from(Ed25519Keypair::from_seed(&seed)))
}

/// Writes a new file readable by its owner only; never overwrites an existing one.
fn write_private(path: &Path, key: &PrivateKey) -> Result<(), String> {
    let text = key
        .to_openssh(LineEnding::LF)
        .map_err(|e| format!("cannot encode the host key: {e}"))?;
    let mut opts = fs::OpenOptions::new();
    opts.write(true).create_new(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        opts.mode(0o600);
    }
    let mut f = opts
        .open(path)
        .map_err(|e| format!("cannot create host key {}: {e}", path.display()))?;
    f.write_all(text.as_bytes())
        .and_then(|()| f.sync_all())
        .map_err(|e| format!("cannot write host key {}: {e}", path.display()))
}

/// The file's permission bits if group or others may read it (Unix only).
fn loose_mode(path: &Path) -> Option<u32> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = fs::metadata(path).ok()?.permissions().mode() & 0o777;
        (mode & 0o077 != 0).then_some(mode)
    }
    #[cfg(not(unix))]
    {
        let _ = path;
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_once_then_reused_with_owner_only_permissions() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("host_ed25519");
        let (a, notes) = load_or_generate(&path, false).expect("generate");
        assert!(notes.iter().any(|n| n.starts_with("generated")));
        let (b, notes) = load_or_generate(&path, false).expect("load");
        assert!(!notes.iter().any(|n| n.starts_with("generated")));
        assert_eq!(a.public_key(), b.public_key());
        assert_eq!(a.algorithm(), russh::keys::Algorithm::Ed25519);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = fs::metadata(&path).expect("meta").permissions().mode() & 0o777;
            assert_eq!(mode, 0o600);
        }
    }

    #[cfg(unix)]
    #[test]
    fn a_key_readable_by_others_is_refused_unless_insecure() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("host_ed25519");
        let (a, _) = load_or_generate(&path, false).expect("generate");
        fs::set_permissions(&path, fs::Permissions::from_mode(0o644)).expect("chmod");
        let err = load_or_generate(&path, false).expect_err("0644 is refused");
        assert_eq!(
            err,
            format!(
                "host key {0} is readable by others (mode 644); run chmod 600 {0} (or pass --insecure-host-key)",
                path.display()
            )
        );
        let (b, notes) = load_or_generate(&path, true).expect("insecure allows it");
        assert_eq!(a.public_key(), b.public_key());
        assert!(notes[0].starts_with("warning:"), "{notes:?}");
    }

    #[cfg(unix)]
    #[test]
    fn a_systemd_credential_may_show_its_acl_mask_but_is_never_generated() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().expect("tempdir");
        let creds = dir.path().join("credentials");
        fs::create_dir(&creds).unwrap();
        let path = creds.join("host_key");
        let e = load_or_generate_with(&path, false, Some(&creds)).expect_err("not generated");
        assert!(
            e.contains("no such credential") && e.contains("LoadCredential="),
            "{e}"
        );
        assert!(!path.exists());
        // systemd's copy, readable through an ACL: mode 0440 (the mask in the group bits).
        let (a, _) = load_or_generate(&dir.path().join("fleet_key"), false).expect("generate");
        fs::copy(dir.path().join("fleet_key"), &path).unwrap();
        fs::set_permissions(&path, fs::Permissions::from_mode(0o440)).unwrap();
        let (b, _) = load_or_generate_with(&path, false, Some(&creds)).expect("a credential");
        assert_eq!(a.public_key(), b.public_key());
        // Outside the credentials directory the same mode is refused, as before; and others'
        // read bits are refused inside it too.
        assert!(load_or_generate_with(&path, false, None).is_err());
        fs::set_permissions(&path, fs::Permissions::from_mode(0o444)).unwrap();
        assert!(load_or_generate_with(&path, false, Some(&creds)).is_err());
    }

    #[test]
    fn garbage_key_file_is_a_clear_error() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("bad");
        fs::write(&path, "hello").expect("write");
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            fs::set_permissions(&path, fs::Permissions::from_mode(0o600)).expect("chmod");
        }
        let err = load_or_generate(&path, false).expect_err("must fail");
        assert!(err.contains("not an OpenSSH private key"), "{err}");
        let missing_dir = dir.path().join("no/such/dir/key");
        assert!(load_or_generate(&missing_dir, false).is_err());
    }
}
