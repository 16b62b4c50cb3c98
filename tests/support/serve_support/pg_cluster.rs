//! A PostgreSQL server of a test's own, in a temporary directory on a free port, which the test
//! may stop and start (an outage) without touching the server other tests share. Made with
//! Debian's `initdb` and `pg_ctl` (/usr/lib/postgresql/*/bin), run as the `postgres` user when
//! the tests run as root (initdb refuses root). Logging in takes a password (scram-sha-256),
//! so the worlds' way of getting it is tested too. Tests print a skip notice without the
//! binaries.

use std::path::PathBuf;
use std::process::{Command, Output};

use tempfile::TempDir;

/// The role a world logs in as.
pub const USER: &str = "halfcast";
/// Its password.
pub const PASSWORD: &str = "outage-pw";

/// A running (or stopped) server of one test's own; stopped and removed when dropped.
pub struct OwnCluster {
    dir: TempDir,
    bin: PathBuf,
    as_postgres: bool,
    /// Where it listens, on 127.0.0.1.
    pub port: u16,
}

/// The newest `/usr/lib/postgresql/N/bin` holding `initdb` and `pg_ctl`.
fn binaries() -> Option<PathBuf> {
    let mut found: Vec<(u32, PathBuf)> = std::fs::read_dir("/usr/lib/postgresql")
        .ok()?
        .filter_map(Result::ok)
        .filter_map(|e| {
            let v = e.file_name().to_str()?.parse().ok()?;
            let bin = e.path().join("bin");
            (bin.join("initdb").is_file() && bin.join("pg_ctl").is_file()).then_some((v, bin))
        })
        .collect();
    found.sort();
    found.pop().map(|(_, b)| b)
}

impl OwnCluster {
    /// A new server, started; `None` (with a SKIPPED notice naming `test`) where it cannot be
    /// made here.
    pub fn start(test: &str) -> Option<Self> {
        let skip = |why: String| {
            eprintln!("SKIPPED {test}: {why}");
            None
        };
        let Some(bin) = binaries() else {
            return skip(
                "no initdb/pg_ctl under /usr/lib/postgresql (.ci/run installs them)".into(),
            );
        };
        let as_postgres = nix_is_root();
        let dir = tempfile::tempdir().expect("tempdir");
        std::fs::write(dir.path().join("pw"), format!("{PASSWORD}\n")).expect("pwfile");
        // Its owner's alone, as a world requires of a --db-password-file.
        {
            use std::os::unix::fs::PermissionsExt;
            let private = std::fs::Permissions::from_mode(0o600);
            std::fs::set_permissions(dir.path().join("pw"), private).expect("chmod 600");
        }
        if as_postgres {
            let owned = Command::new("chown")
                .args(["-R", "postgres:"])
                .arg(dir.path())
                .status();
            if !owned.is_ok_and(|s| s.success()) {
                return skip("running as root, and no `postgres` user to run initdb as".into());
            }
        }
        let port = quiet_port();
        let me = Self {
            dir,
            bin,
            as_postgres,
            port,
        };
        let data = me.data();
        let pw = me.dir.path().join("pw");
        let init = me.run(
            "initdb",
            &[
                "-D",
                data.to_str().unwrap(),
                "-U",
                USER,
                "--pwfile",
                pw.to_str().unwrap(),
                "-A",
                "scram-sha-256",
                "--no-sync",
            ],
        );
        if !init.status.success() {
            return skip(format!(
                "initdb failed: {}",
                String::from_utf8_lossy(&init.stderr)
            ));
        }
        me.resume();
        Some(me)
    }

    fn data(&self) -> PathBuf {
        self.dir.path().join("data")
    }

    /// Runs one of the server's programs (as `postgres` when we are root).
    fn run(&self, program: &str, args: &[&str]) -> Output {
        let path = self.bin.join(program);
        let mut cmd = if self.as_postgres {
            let mut c = Command::new("runuser");
            c.args(["-u", "postgres", "--"]).arg(&path);
            c
        } else {
            Command::new(&path)
        };
        cmd.args(args)
            .current_dir(self.dir.path())
            .output()
            .unwrap_or_else(|e| panic!("{program} runs: {e}"))
    }

    /// Starts the server (again) and waits until it takes connections.
    pub fn resume(&self) {
        let options = format!(
            "-p {} -k {} -c listen_addresses=127.0.0.1 -c fsync=off",
            self.port,
            self.dir.path().display()
        );
        let log = self.dir.path().join("log");
        let out = self.run(
            "pg_ctl",
            &[
                "-D",
                self.data().to_str().unwrap(),
                "-l",
                log.to_str().unwrap(),
                "-o",
                &options,
                "-w",
                "-t",
                "60",
                "start",
            ],
        );
        assert!(
            out.status.success(),
            "pg_ctl start: {}{}",
            String::from_utf8_lossy(&out.stderr),
            std::fs::read_to_string(&log).unwrap_or_default()
        );
    }

    /// Stops the server (its clients' connections cut, as a restart or a crash of it would)
    /// and waits until it has.
    pub fn stop(&self) {
        let out = self.run(
            "pg_ctl",
            &[
                "-D",
                self.data().to_str().unwrap(),
                "-m",
                "fast",
                "-w",
                "stop",
            ],
        );
        assert!(
            out.status.success(),
            "pg_ctl stop: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }

    /// The URL a world is given: no password in it.
    pub fn url(&self) -> String {
        format!("postgres://{USER}@127.0.0.1:{}/postgres", self.port)
    }

    /// A file holding the password (for `--db-password-file`), readable by this process.
    pub fn password_file(&self) -> PathBuf {
        self.dir.path().join("pw")
    }

    /// The value of a one-number query (`SELECT COUNT(*) …`) on the server.
    pub fn number(&self, sql: &str) -> i64 {
        let (url, sql) = (
            format!("{}?password={PASSWORD}", self.url()),
            sql.to_owned(),
        );
        std::thread::spawn(move || {
            let mut c = postgres::Client::connect(&url, postgres::NoTls).expect("connects");
            c.query_one(sql.as_str(), &[])
                .expect("the query runs")
                .get(0)
        })
        .join()
        .expect("the query thread")
    }
}

impl OwnCluster {
    /// The first column of every row of a query returning text (`SELECT uid FROM rounds`).
    pub fn texts(&self, sql: &str) -> Vec<String> {
        let (url, sql) = (
            format!("{}?password={PASSWORD}", self.url()),
            sql.to_owned(),
        );
        std::thread::spawn(move || {
            let mut c = postgres::Client::connect(&url, postgres::NoTls).expect("connects");
            c.query(sql.as_str(), &[])
                .expect("the query runs")
                .iter()
                .map(|r| r.get(0))
                .collect()
        })
        .join()
        .expect("the query thread")
    }
}

impl Drop for OwnCluster {
    fn drop(&mut self) {
        let _ = self.run(
            "pg_ctl",
            &[
                "-D",
                self.data().to_str().unwrap(),
                "-m",
                "immediate",
                "-w",
                "stop",
            ],
        );
    }
}

/// Whether this process runs as root.
fn nix_is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| o.stdout.starts_with(b"0\n"))
}

/// A port free now below the range the OS hands out for port 0 (32768 and up on Linux): the
/// server gives it up while stopped, and a world asking for a free port then must not get it.
fn quiet_port() -> u16 {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.subsec_nanos());
    let start = (nanos ^ std::process::id().rotate_left(7)) % 12_000;
    (0..12_000)
        .map(|i| 20_000 + ((start + i) % 12_000) as u16)
        .find(|&p| std::net::TcpListener::bind(("127.0.0.1", p)).is_ok())
        .expect("a free port below 32000")
}
