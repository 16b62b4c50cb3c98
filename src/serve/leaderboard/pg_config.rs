//! Where a PostgreSQL leaderboard is and how to log in to it, the way libpq (`psql`,
//! `pg_dump`) finds out: the `--db postgres://…` URL first, then a password file named on the
//! command line (`--db-password-file`, for systemd's `LoadCredential=`), then the environment
//! (`PGSERVICE`'s entry in the service file, `PGHOST`, `PGPORT`, `PGUSER`, `PGDATABASE`,
//! `PGPASSWORD`, `PGCONNECT_TIMEOUT`), then the password file (`PGPASSFILE`, else
//! `~/.pgpass`). The password never has to be on a command line, where every local user reads
//! it; and a password file that others may read is refused, with the `chmod` that fixes it
//! (libpq ignores such a `.pgpass` with a warning; sshd refuses such a key), unless the operator
//! says to use it anyway (`--db-insecure-password-file`).

use std::path::{Path, PathBuf};
use std::time::Duration;

use postgres::Config;

use super::pg_text::{causes, shown};

/// How long connecting may take before it is an error, unless the URL or
/// `PGCONNECT_TIMEOUT` says otherwise.
const CONNECT_TIMEOUT: Duration = Duration::from_secs(5);

/// A resolved PostgreSQL target: what to connect to, and how it is shown (no password).
#[derive(Clone)]
pub struct PgTarget {
    /// The client's settings, password included.
    pub config: Config,
    /// The URL as logs and errors show it.
    pub shown: String,
}

impl std::fmt::Debug for PgTarget {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PgTarget")
            .field("shown", &self.shown)
            .finish()
    }
}

/// Whether `url` carries a password itself (`postgres://user:PASSWORD@…` or `?password=`).
#[must_use]
pub fn url_has_password(url: &str) -> bool {
    url.parse::<Config>()
        .is_ok_and(|c| c.get_password().is_some())
}

impl PgTarget {
    /// `url` completed from `password_file` and the process's environment, as libpq would;
    /// a password file others may read is refused unless `insecure`.
    ///
    /// # Errors
    /// The URL does not parse, or a password file cannot be read or others may read it.
    pub fn resolve(
        url: &str,
        password_file: Option<&Path>,
        insecure: bool,
    ) -> Result<Self, String> {
        Self::resolve_with(url, password_file, insecure, &|k| {
            std::env::var(k).ok().filter(|v| !v.is_empty())
        })
    }

    /// [`PgTarget::resolve`] with the environment read through `env`.
    ///
    /// # Errors
    /// As [`PgTarget::resolve`].
    pub fn resolve_with(
        url: &str,
        password_file: Option<&Path>,
        insecure: bool,
        env: &dyn Fn(&str) -> Option<String>,
    ) -> Result<Self, String> {
        let shown_url = shown(url);
        let mut config: Config = url.parse().map_err(|e| {
            format!(
                "leaderboard {shown_url}: not a PostgreSQL URL: {}",
                causes(&e)
            )
        })?;
        if config.get_password().is_none() {
            if let Some(path) = password_file {
                private_file("--db-password-file", path, insecure)?;
                config.password(
                    crate::serve::auth::password_from_file(path)
                        .map_err(|e| format!("--db-password-file: {e}"))?,
                );
            }
        }
        let service = env("PGSERVICE")
            .map(|name| service_entry(&name, env))
            .transpose()?
            .unwrap_or_default();
        let setting = |key: &str, var: &str| {
            service
                .iter()
                .find(|(k, _)| k == key)
                .map(|(_, v)| v.clone())
                .or_else(|| env(var))
        };
        if config.get_hosts().is_empty() {
            config.host(&setting("host", "PGHOST").unwrap_or_else(|| "localhost".into()));
        }
        if config.get_ports().is_empty() {
            if let Some(p) = setting("port", "PGPORT").and_then(|p| p.parse().ok()) {
                config.port(p);
            }
        }
        if config.get_user().is_none() {
            let user = setting("user", "PGUSER")
                .or_else(|| env("USER"))
                .or_else(|| env("LOGNAME"));
            if let Some(u) = user {
                config.user(&u);
            }
        }
        if config.get_dbname().is_none() {
            if let Some(d) = setting("dbname", "PGDATABASE") {
                config.dbname(&d);
            }
        }
        if config.get_connect_timeout().is_none() {
            let secs = setting("connect_timeout", "PGCONNECT_TIMEOUT").and_then(|s| s.parse().ok());
            config.connect_timeout(secs.map_or(CONNECT_TIMEOUT, Duration::from_secs));
        }
        if config.get_password().is_none() {
            if let Some(p) = setting("password", "PGPASSWORD") {
                config.password(p);
            } else if let Some(p) = from_pgpass(&config, insecure, env)? {
                config.password(p);
            }
        }
        Ok(Self {
            config,
            shown: shown_url,
        })
    }
}

/// The password file libpq reads: `PGPASSFILE`, else `~/.pgpass`.
fn pgpass_path(env: &dyn Fn(&str) -> Option<String>) -> Option<PathBuf> {
    env("PGPASSFILE")
        .map(PathBuf::from)
        .or_else(|| env("HOME").map(|h| Path::new(&h).join(".pgpass")))
}

/// The password of the first `host:port:database:user:password` line of the password file
/// matching `config` (`*` matches anything), if there is such a file.
///
/// # Errors
/// Others may read the file, and not `insecure`.
fn from_pgpass(
    config: &Config,
    insecure: bool,
    env: &dyn Fn(&str) -> Option<String>,
) -> Result<Option<String>, String> {
    let Some(path) = pgpass_path(env).filter(|p| p.is_file()) else {
        return Ok(None);
    };
    private_file("password file", &path, insecure)?;
    Ok(pgpass_entry(config, &path))
}

/// The password of `path`'s first line matching `config`.
fn pgpass_entry(config: &Config, path: &Path) -> Option<String> {
    let text = std::fs::read_to_string(path).ok()?;
    let host = match config.get_hosts().first()? {
        postgres::config::Host::Tcp(h) => h.clone(),
        #[cfg(unix)]
        postgres::config::Host::Unix(_) => "localhost".into(),
    };
    let port = config
        .get_ports()
        .first()
        .copied()
        .unwrap_or(5432)
        .to_string();
    let user = config.get_user()?;
    let db = config.get_dbname().unwrap_or(user);
    let wanted = [host.as_str(), port.as_str(), db, user];
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .map(pgpass_fields)
        .find(|f| f.len() == 5 && wanted.iter().zip(f).all(|(w, f)| f == "*" || f == w))
        .map(|f| f[4].clone())
}

/// A password file line's fields, split at `:` (`\:` and `\\` escape).
fn pgpass_fields(line: &str) -> Vec<String> {
    let mut fields = vec![String::new()];
    let mut chars = line.chars();
    while let Some(c) = chars.next() {
        match c {
            '\\' => fields
                .last_mut()
                .into_iter()
                .for_each(|f| f.extend(chars.next())),
            ':' if fields.len() < 5 => fields.push(String::new()),
            c => fields.last_mut().into_iter().for_each(|f| f.push(c)),
        }
    }
    fields
}

/// Refuses a password file (`what`, at `path`) that its group or others may use, naming its
/// mode and the `chmod` that fixes it, unless `insecure`. In systemd's credentials directory
/// (`LoadCredential=`), which is the service's alone, only bits for others refuse it: systemd
/// may grant the service its credential with an ACL, whose mask shows as group bits (as for the
/// host key).
///
/// # Errors
/// The refusal, one line.
pub fn private_file(what: &str, path: &Path, insecure: bool) -> Result<(), String> {
    let credentials = std::env::var_os("CREDENTIALS_DIRECTORY").map(PathBuf::from);
    private_file_in(what, path, insecure, credentials.as_deref())
}

/// [`private_file`] with systemd's credentials directory given (`None`: not under systemd).
///
/// # Errors
/// As [`private_file`].
pub fn private_file_in(
    what: &str,
    path: &Path,
    insecure: bool,
    credentials: Option<&Path>,
) -> Result<(), String> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let Ok(meta) = std::fs::metadata(path) else {
            return Ok(()); // reading it says what is wrong
        };
        let mode = meta.permissions().mode() & 0o777;
        let credential = credentials.is_some_and(|d| path.starts_with(d));
        let loose = if credential { 0o007 } else { 0o077 };
        if mode & loose != 0 && !insecure {
            let p = path.display();
            return Err(format!(
                "{what} {p}: its group or others may read it (mode {mode:04o}), so anyone on                  this host may learn the database's password; run `chmod 600 {p}` (or pass                  --db-insecure-password-file to use it anyway)"
            ));
        }
    }
    #[cfg(not(unix))]
    let _ = (what, path, insecure, credentials);
    Ok(())
}

/// The `key=value` settings of service `name`: from `PGSERVICEFILE` (else
/// `~/.pg_service.conf`), or else `PGSYSCONFDIR/pg_service.conf`.
fn service_entry(
    name: &str,
    env: &dyn Fn(&str) -> Option<String>,
) -> Result<Vec<(String, String)>, String> {
    let files = [
        env("PGSERVICEFILE")
            .map(PathBuf::from)
            .or_else(|| env("HOME").map(|h| Path::new(&h).join(".pg_service.conf"))),
        Some(
            Path::new(&env("PGSYSCONFDIR").unwrap_or_else(|| "/etc/postgresql-common".into()))
                .join("pg_service.conf"),
        ),
    ];
    for file in files.into_iter().flatten() {
        let Ok(text) = std::fs::read_to_string(&file) else {
            continue;
        };
        if let Some(entry) = service_in(&text, name) {
            return Ok(entry);
        }
    }
    Err(format!(
        "PGSERVICE={name}: no such service in the service files"
    ))
}

/// Service `name`'s settings in a service file's `text` (`[name]` then `key=value` lines).
fn service_in(text: &str, name: &str) -> Option<Vec<(String, String)>> {
    let mut inside = None;
    for line in text.lines().map(str::trim) {
        if let Some(section) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            if inside.is_some() {
                break;
            }
            if section == name {
                inside = Some(Vec::new());
            }
        } else if let (Some(entry), Some((k, v))) = (inside.as_mut(), line.split_once('=')) {
            if !line.starts_with('#') {
                entry.push((k.trim().to_owned(), v.trim().to_owned()));
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn resolve(url: &str, file: Option<&Path>, vars: &[(&str, &str)]) -> Config {
        let vars: HashMap<String, String> = vars
            .iter()
            .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
            .collect();
        PgTarget::resolve_with(url, file, false, &|k| vars.get(k).cloned())
            .unwrap()
            .config
    }

    fn password(c: &Config) -> Option<&str> {
        c.get_password().map(|p| std::str::from_utf8(p).unwrap())
    }

    #[test]
    fn the_password_comes_from_the_url_the_file_the_environment_then_pgpass() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("pw");
        std::fs::write(&file, "from-file\n").unwrap();
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o600)).unwrap();
        }
        let pgpass = dir.path().join("pgpass");
        std::fs::write(
            &pgpass,
            "# comment\nother:*:*:*:nope\ndb.example:5433:*:ann:a\\:b\\\\c\n",
        )
        .unwrap();
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            std::fs::set_permissions(&pgpass, std::fs::Permissions::from_mode(0o600)).unwrap();
        }
        let pass = pgpass.to_str().unwrap();
        let url = "postgres://ann@db.example:5433/halfcast";
        let c = resolve("postgres://ann:inurl@db.example/h", Some(&file), &[]);
        assert_eq!(password(&c), Some("inurl"));
        let c = resolve(url, Some(&file), &[("PGPASSWORD", "env")]);
        assert_eq!(password(&c), Some("from-file"));
        let c = resolve(url, None, &[("PGPASSWORD", "env"), ("PGPASSFILE", pass)]);
        assert_eq!(password(&c), Some("env"));
        let c = resolve(url, None, &[("PGPASSFILE", pass)]);
        assert_eq!(password(&c), Some("a:b\\c"));
        let c = resolve(
            "postgres://bob@db.example:5433/h",
            None,
            &[("PGPASSFILE", pass)],
        );
        assert_eq!(password(&c), None);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            std::fs::set_permissions(&pgpass, std::fs::Permissions::from_mode(0o644)).unwrap();
            let env = |k: &str| (k == "PGPASSFILE").then(|| pass.to_owned());
            let e = PgTarget::resolve_with(url, None, false, &env).unwrap_err();
            assert!(
                e.contains("mode 0644") && e.contains(&format!("chmod 600 {pass}")),
                "a password file others read is refused, saying how to fix it: {e}"
            );
            let c = PgTarget::resolve_with(url, None, true, &env)
                .unwrap()
                .config;
            assert_eq!(password(&c), Some("a:b\\c"), "unless told to use it anyway");
        }
    }

    #[cfg(unix)]
    #[test]
    fn a_password_file_others_may_read_is_refused_with_the_chmod_that_fixes_it() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("db_password");
        std::fs::write(&file, "secret\n").unwrap();
        let url = "postgres://ann@db.example/h";
        for mode in [0o644, 0o640, 0o604, 0o660] {
            std::fs::set_permissions(&file, std::fs::Permissions::from_mode(mode)).unwrap();
            let e = PgTarget::resolve_with(url, Some(&file), false, &|_| None).unwrap_err();
            assert!(
                e.starts_with("--db-password-file")
                    && e.contains(&format!("mode {mode:04o}"))
                    && e.contains(&format!("chmod 600 {}", file.display())),
                "{e}"
            );
            assert!(!e.contains("secret"), "{e}");
            let c = PgTarget::resolve_with(url, Some(&file), true, &|_| None).unwrap();
            assert_eq!(password(&c.config), Some("secret"));
        }
        for mode in [0o600, 0o400] {
            std::fs::set_permissions(&file, std::fs::Permissions::from_mode(mode)).unwrap();
            let c = PgTarget::resolve_with(url, Some(&file), false, &|_| None).unwrap();
            assert_eq!(password(&c.config), Some("secret"));
        }
        // A systemd credential: an ACL's group bits are no refusal there, others' bits are.
        std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o440)).unwrap();
        let what = "--db-password-file";
        assert!(private_file_in(what, &file, false, Some(dir.path())).is_ok());
        assert!(private_file_in(what, &file, false, None).is_err());
        std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o444)).unwrap();
        assert!(private_file_in(what, &file, false, Some(dir.path())).is_err());
    }

    #[test]
    fn the_environment_and_a_service_fill_what_the_url_leaves_out() {
        let c = resolve(
            "postgres://",
            None,
            &[
                ("PGHOST", "db.example"),
                ("PGPORT", "6543"),
                ("PGUSER", "ann"),
                ("PGDATABASE", "hc"),
            ],
        );
        assert_eq!(
            c.get_hosts(),
            [postgres::config::Host::Tcp("db.example".into())]
        );
        assert_eq!(c.get_ports(), [6543]);
        assert_eq!((c.get_user(), c.get_dbname()), (Some("ann"), Some("hc")));
        let dir = tempfile::tempdir().unwrap();
        let services = dir.path().join("services");
        std::fs::write(
            &services,
            "[other]\nhost=nope\n[fleet]\nhost=pg.example\nuser=fleet\npassword=svc\n",
        )
        .unwrap();
        let vars = [
            ("PGSERVICE", "fleet"),
            ("PGSERVICEFILE", services.to_str().unwrap()),
            ("PGUSER", "ann"),
        ];
        let c = resolve("postgres:///hc", None, &vars);
        assert_eq!(
            c.get_hosts(),
            [postgres::config::Host::Tcp("pg.example".into())]
        );
        assert_eq!((c.get_user(), password(&c)), (Some("fleet"), Some("svc")));
        let e = PgTarget::resolve_with("postgres://h/d", None, false, &|k| {
            (k == "PGSERVICE").then(|| "missing".to_owned())
        })
        .unwrap_err();
        assert!(e.contains("no such service"), "{e}");
    }

    #[test]
    fn a_password_in_the_url_is_seen() {
        assert!(url_has_password("postgres://ann:pw@h/db"));
        assert!(url_has_password("postgres://ann@h/db?password=pw"));
        assert!(!url_has_password("postgres://ann@h/db"));
    }
}
