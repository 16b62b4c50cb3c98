//! The leaderboard survives its database: PostgreSQL (a server of this test's own, see
//! `pg_cluster`) is stopped while rounds end, a world starts while it is down, it comes back,
//! and every round is there exactly once; then a world is killed with SIGKILL while its rounds
//! wait in the queue, restarted with the same options, and writes them. No step waits a fixed
//! time: each waits for what it needs to see (a log line, a metric, a row count).

use crate::serve_process::{free_port, spawn, Guard};
use crate::serve_support;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::mpsc::Receiver;
use std::time::{Duration, Instant};

use serve_support::http::{get, series};
use serve_support::pg_cluster::{OwnCluster, PASSWORD};
use serve_support::{header_has, Client, PATIENCE};

/// How a world gets the database's password (never on its command line).
#[derive(Clone, Copy)]
pub(crate) enum Password {
    /// `--db-password-file`.
    File,
    /// `PGPASSWORD`.
    Env,
}

/// One `halfcast serve` process on the test's database, and what it has logged.
pub(crate) struct World {
    pub(crate) guard: Guard,
    port: u16,
    pub(crate) metrics: u16,
    log: Receiver<String>,
    pub(crate) lines: Vec<String>,
}

/// Flags every world of this test has: quick rounds, the database, metrics.
fn world_args(pg: &OwnCluster, metrics: u16, password: Password) -> Vec<String> {
    let mut args: Vec<String> = [
        "--round-minutes",
        "0.005",
        "--results-seconds",
        "0.2",
        "--metrics",
        &metrics.to_string(),
        "--db",
        &pg.url(),
    ]
    .map(str::to_owned)
    .to_vec();
    if let Password::File = password {
        args.push("--db-password-file".into());
        args.push(pg.password_file().display().to_string());
    }
    args
}

impl World {
    /// Starts a world with its host key (and so, unless `extra` says otherwise, its queue) in
    /// `dir`, and waits until it listens.
    pub(crate) fn start(pg: &OwnCluster, dir: &Path, password: Password, extra: &[&str]) -> Self {
        let (port, metrics) = (free_port(), free_port());
        let mut args = world_args(pg, metrics, password);
        args.extend(extra.iter().map(|s| (*s).to_owned()));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let env: &[(&str, &str)] = match password {
            Password::File => &[],
            Password::Env => &[("PGPASSWORD", PASSWORD)],
        };
        let (guard, log) = spawn(port, &dir.join("hk"), &args, env);
        let mut w = Self {
            guard,
            port,
            metrics,
            log,
            lines: Vec::new(),
        };
        w.until("it listens", |w| w.said("listening on"));
        w
    }

    fn addr(&self) -> std::net::SocketAddr {
        format!("127.0.0.1:{}", self.port).parse().unwrap()
    }

    /// Takes in the lines logged so far.
    pub(crate) fn pump(&mut self) {
        self.lines.extend(self.log.try_iter());
    }

    /// Whether a line so far contains `text`.
    pub(crate) fn said(&self, text: &str) -> bool {
        self.lines.iter().any(|l| l.contains(text))
    }

    /// Lines so far containing `text`.
    pub(crate) fn count(&self, text: &str) -> usize {
        self.lines.iter().filter(|l| l.contains(text)).count()
    }

    /// Rounds ended so far (text or JSON log).
    pub(crate) fn rounds(&self) -> usize {
        self.count("round over on") + self.count(r#""event":"round_end""#)
    }

    /// `halfcast_leaderboard_pending_rounds` now.
    pub(crate) fn pending(&self) -> f64 {
        series(
            &get(self.metrics, "/metrics").1,
            "halfcast_leaderboard_pending_rounds",
        )
    }

    /// Waits (pumping the log) until `done`, or fails naming `what` and the log.
    pub(crate) fn until(&mut self, what: &str, mut done: impl FnMut(&Self) -> bool) {
        let deadline = Instant::now() + PATIENCE;
        loop {
            if let Ok(line) = self.log.recv_timeout(Duration::from_millis(20)) {
                self.lines.push(line);
            }
            self.pump();
            if done(self) {
                return;
            }
            assert!(
                Instant::now() < deadline,
                "waited too long for {what}; the log:\n{}",
                self.lines.join("\n")
            );
        }
    }

    /// Waits until the world has nobody playing (so no round can end), its rounds stopped
    /// ending and none waits to be written; its round count then.
    pub(crate) fn settled(&mut self) -> usize {
        let mut last = usize::MAX;
        self.until("the rounds to settle and be written", |w| {
            let m = get(w.metrics, "/metrics").1;
            let nobody = series(&m, r#"halfcast_sessions{state="playing"}"#) == 0.0;
            let now = w.rounds();
            let still = nobody && now == last && w.pending() == 0.0;
            last = now;
            still && {
                // Two looks a while apart: a round may be ending right now.
                std::thread::sleep(Duration::from_millis(300));
                true
            }
        });
        self.pump();
        self.rounds()
    }
}

/// The rounds the database holds, and how many distinct identities they have.
fn stored(pg: &OwnCluster) -> (i64, i64) {
    (
        pg.number("SELECT COUNT(*) FROM rounds"),
        pg.number("SELECT COUNT(DISTINCT uid) FROM rounds"),
    )
}

/// A player in `w` until dropped; waits until they see the game.
pub(crate) async fn player(w: &World, name: &str) -> Client {
    let mut c = Client::connect(w.addr(), name, 80, 24, "xterm-256color").await;
    assert!(c.until(|s| header_has(s, &format!("you are {name}"))).await);
    c
}

/// Plays on `c` until `w` has logged `n` rounds more than `from`.
pub(crate) async fn play_rounds(w: &mut World, c: &mut Client, from: usize, n: usize) {
    let deadline = Instant::now() + PATIENCE;
    loop {
        w.pump();
        if w.rounds() >= from + n {
            return;
        }
        assert!(Instant::now() < deadline, "rounds too slow: {}", w.rounds());
        c.drain_for(Duration::from_millis(50)).await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn rounds_survive_a_database_outage_a_start_without_it_and_a_kill_9_exactly_once() {
    let Some(pg) = OwnCluster::start("the leaderboard across a PostgreSQL outage") else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let (dir_a, dir_b) = (dir.path().join("a"), dir.path().join("b"));
    std::fs::create_dir_all(&dir_a).unwrap();
    std::fs::create_dir_all(&dir_b).unwrap();
    // World a: password from a file, queue beside its host key (the default).
    let mut a = World::start(&pg, &dir_a, Password::File, &[]);
    let mut ann = player(&a, "ann").await;
    play_rounds(&mut a, &mut ann, 0, 2).await;

    // The database goes away while rounds end: they queue, and the outage is logged once.
    pg.stop();
    let at_stop = a.rounds();
    play_rounds(&mut a, &mut ann, at_stop, 4).await;
    a.until("the backlog in the metrics", |w| w.pending() >= 2.0);
    assert!(queued_files(&dir_a.join("halfcast-queue")) >= 2);

    // World b starts while it is down (password from PGPASSWORD, its queue where it is told,
    // a JSON log): it says so, plays and queues.
    let queue_b = dir_b.join("elsewhere");
    let qb = queue_b.to_str().unwrap();
    let mut b = World::start(
        &pg,
        &dir_b,
        Password::Env,
        &["--queue-dir", qb, "--log-format", "json"],
    );
    assert!(
        b.said("is away") && b.lines.iter().all(|l| l.starts_with('{')),
        "{:#?}",
        b.lines
    );
    let mut bob = player(&b, "bob").await;
    play_rounds(&mut b, &mut bob, 0, 3).await;
    b.until("b's backlog", |w| w.pending() >= 2.0);
    assert!(queued_files(&queue_b) >= 2);

    // It comes back: both worlds write their backlogs, and every round is there once.
    pg.resume();
    drop((ann, bob));
    let (ra, rb) = (a.settled(), b.settled());
    assert_eq!(
        stored(&pg),
        ((ra + rb) as i64, (ra + rb) as i64),
        "a {ra}, b {rb}"
    );
    assert_eq!(
        a.count("cannot write"),
        1,
        "one line per outage: {:#?}",
        a.lines
    );
    assert!(a.count("cannot read") <= 1, "{:#?}", a.lines);
    assert!(a.said("back after") && b.said("back after"));
    assert_eq!(queued_files(&queue_b), 0);

    // Down again; a's rounds queue, and a is killed with SIGKILL while they wait.
    pg.stop();
    let mut cat = player(&a, "cat").await;
    let before = a.rounds();
    play_rounds(&mut a, &mut cat, before, 3).await;
    drop(cat);
    a.until("every new round in the queue", |w| {
        w.pending() as usize == w.rounds() - before
    });
    let queued = a.rounds() - before;
    let pid = a.guard.0.id().to_string();
    assert!(Command::new("kill")
        .args(["-KILL", &pid])
        .status()
        .unwrap()
        .success());
    let _ = a.guard.0.wait();
    assert_eq!(queued_files(&dir_a.join("halfcast-queue")), queued);

    // Restarted with the same options once the database is back: it finds them and writes
    // them.
    pg.resume();
    let mut again = World::start(&pg, &dir_a, Password::File, &[]);
    again.until("the queue found", |w| w.said("rounds queued in"));
    again.until("the queue written", |w| w.pending() == 0.0);
    let total = (ra + rb + queued) as i64;
    assert_eq!(stored(&pg), (total, total));
    eprintln!(
        "outage: world a {ra} rounds ({} from the database's stop on), world b {rb} (started \
         while it was down); {queued} queued by a when it was killed; {total} stored, once each",
        ra - at_stop
    );
    assert_eq!(queued_files(&dir_a.join("halfcast-queue")), 0);
}

/// Round files waiting in a queue directory.
fn queued_files(dir: &PathBuf) -> usize {
    std::fs::read_dir(dir).map_or(0, |d| {
        d.filter_map(Result::ok)
            .filter(|e| e.file_name().to_string_lossy().ends_with(".round.json"))
            .count()
    })
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_world_on_postgres_shows_no_password_in_its_command_line() {
    let Some(pg) = OwnCluster::start("no password in the process list") else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    for password in [Password::File, Password::Env] {
        let mut w = World::start(&pg, dir.path(), password, &[]);
        w.until("the leaderboard open", |w| w.said("leaderboard in"));
        let pid = w.guard.0.id();
        let cmdline = std::fs::read(format!("/proc/{pid}/cmdline")).expect("/proc/PID/cmdline");
        let cmdline = String::from_utf8_lossy(&cmdline).replace('\0', " ");
        assert!(cmdline.contains("--db postgres://"), "{cmdline}");
        assert!(!cmdline.contains(PASSWORD), "{cmdline}");
        // It did log in with it: a round is written.
        let before = pg.number("SELECT COUNT(*) FROM rounds");
        let mut ann = player(&w, "ann").await;
        play_rounds(&mut w, &mut ann, 0, 1).await;
        drop(ann);
        let played = w.settled();
        assert_eq!(
            pg.number("SELECT COUNT(*) FROM rounds"),
            before + played as i64
        );
    }
    // A URL with a password is refused before the world starts, without echoing it.
    let url = format!(
        "postgres://halfcast:{PASSWORD}@127.0.0.1:{}/postgres",
        pg.port
    );
    let (mut srv, log) = spawn(free_port(), &dir.path().join("hk"), &["--db", &url], &[]);
    let status = srv.0.wait().unwrap();
    assert_eq!(status.code(), Some(2));
    let said: String = log.iter().collect::<Vec<_>>().join("\n");
    assert!(
        said.contains("--db-password-file") && !said.contains(PASSWORD),
        "{said}"
    );
}
