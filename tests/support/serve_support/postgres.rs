//! A throwaway PostgreSQL database for one test, on the server `.ci/run` starts (or the one
//! `HALFCAST_TEST_POSTGRES` names: an admin URL whose role may create databases). Tests print
//! a skip notice and return where no server answers.

use std::sync::atomic::{AtomicU32, Ordering};

/// The server tests use unless `HALFCAST_TEST_POSTGRES` says otherwise (`.ci/run` makes this
/// role and database).
pub const DEFAULT_ADMIN: &str = "postgres://halfcast:halfcast@127.0.0.1:5432/halfcast";

/// A database of its own, dropped when this is.
pub struct TestDatabase {
    admin: String,
    name: String,
    /// The URL a world or `halfcast scores` is given.
    pub url: String,
}

impl TestDatabase {
    /// A new, empty database; `None` (with a SKIPPED notice naming `test`) without a server.
    pub fn create(test: &str) -> Option<Self> {
        static NEXT: AtomicU32 = AtomicU32::new(0);
        let admin =
            std::env::var("HALFCAST_TEST_POSTGRES").unwrap_or_else(|_| DEFAULT_ADMIN.into());
        let name = format!(
            "halfcast_test_{}_{}",
            std::process::id(),
            NEXT.fetch_add(1, Ordering::Relaxed)
        );
        let (url, create) = (admin.clone(), format!("CREATE DATABASE {name}"));
        let made = off_runtime(move || {
            let mut client = connect(&url).map_err(|e| e.to_string())?;
            client
                .batch_execute(&create)
                .map_err(|e| format!("the test role may not create databases: {e}"))
        });
        if let Err(e) = made {
            eprintln!(
                "SKIPPED {test}: no PostgreSQL server for the tests ({e}); .ci/run starts one"
            );
            return None;
        }
        let (base, _) = admin.rsplit_once('/').expect("a URL with a database");
        let url = format!("{base}/{name}");
        Some(Self { admin, name, url })
    }

    /// Runs `sql` on this database (to look, or to meddle); the rows it returned or touched.
    pub fn execute(&self, sql: &str) -> u64 {
        let (url, sql) = (self.url.clone(), sql.to_owned());
        off_runtime(move || {
            let mut c = connect(&url).expect("the test database answers");
            c.execute(sql.as_str(), &[]).expect("the statement runs")
        })
    }
}

impl Drop for TestDatabase {
    fn drop(&mut self) {
        let (admin, name) = (self.admin.clone(), self.name.clone());
        off_runtime(move || {
            if let Ok(mut c) = connect(&admin) {
                let _ = c.batch_execute(&format!("DROP DATABASE IF EXISTS {name} WITH (FORCE)"));
            }
        });
    }
}

/// Runs `f` on a thread of its own: the blocking client starts a runtime of its own, which
/// tokio forbids on a thread already running async tests.
fn off_runtime<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::spawn(f).join().expect("the database thread")
}

fn connect(url: &str) -> Result<postgres::Client, postgres::Error> {
    let mut config: postgres::Config = url.parse()?;
    config.connect_timeout(std::time::Duration::from_secs(3));
    config.connect(postgres::NoTls)
}
