//! A database that refuses is a mistake, one that does not answer an outage: against a
//! PostgreSQL server of the test's own (`pg_cluster`), a wrong password, an unknown role, a
//! missing database, TLS the server does not offer or a port where another program (SSH)
//! answers stop `halfcast serve` at once with the
//! server's own words (one line, JSON under `--log-format json`) and a non-zero exit, while a
//! stopped server lets the world start and queue. `--db-start-on-error` starts on a refusal too;
//! the connected gauge and the error counters say what the database is doing from the first
//! try, the round ids in the log are the database's, and an outage while nobody plays is seen
//! (and timed) when it starts.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crate::serve_pg_outage::{play_rounds, player, Password, World};
use crate::serve_process::{free_port, spawn};
use crate::serve_support::http::{get, series};
use crate::serve_support::pg_cluster::{OwnCluster, PASSWORD, USER};
use crate::serve_support::PATIENCE;

/// A password file (mode 0600) holding `password`.
fn password_file(dir: &Path, name: &str, password: &str) -> PathBuf {
    use std::os::unix::fs::PermissionsExt;
    let path = dir.join(name);
    std::fs::write(&path, format!("{password}\n")).unwrap();
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o600)).unwrap();
    path
}

/// Starts a world that must not start; its exit code, its stderr lines, and how long it took.
fn refused_start(dir: &Path, args: &[&str]) -> (Option<i32>, Vec<String>, Duration) {
    let started = Instant::now();
    let (mut srv, log) = spawn(free_port(), &dir.join("hk"), args, &[]);
    let deadline = started + PATIENCE;
    let status = loop {
        if let Some(status) = srv.0.try_wait().unwrap() {
            break status;
        }
        assert!(
            Instant::now() < deadline,
            "the world started anyway: {:?}",
            log.try_iter().collect::<Vec<_>>()
        );
        std::thread::sleep(Duration::from_millis(20));
    };
    let took = started.elapsed();
    (status.code(), log.iter().collect(), took)
}

/// A port on which something greets as an SSH server does (and reads what it is sent, then
/// hangs up), as long as the test runs.
fn ssh_like_port() -> u16 {
    use std::io::{Read, Write};
    let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = l.local_addr().unwrap().port();
    std::thread::spawn(move || {
        for s in l.incoming() {
            let Ok(mut s) = s else { continue };
            let _ = s.write_all(b"SSH-2.0-OpenSSH_9.2p1 Debian-2+deb12u3\r\n");
            let _ = s.set_read_timeout(Some(Duration::from_millis(500)));
            let _ = s.read(&mut [0u8; 256]);
        }
    });
    port
}

#[test]
fn a_misconfigured_database_stops_the_start_with_its_cause() {
    let Some(pg) = OwnCluster::start("a misconfigured database") else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let wrong = password_file(dir.path(), "wrong", "not-the-password");
    let right = password_file(dir.path(), "right", PASSWORD);
    let (wrong, right) = (wrong.to_str().unwrap(), right.to_str().unwrap());
    let at = format!("127.0.0.1:{}", pg.port);
    let ssh = ssh_like_port();
    let cases = [
        (
            "a wrong password",
            pg.url(),
            wrong,
            "password authentication failed",
        ),
        (
            "an unknown role",
            format!("postgres://nobody@{at}/postgres"),
            right,
            r#"for user "nobody""#,
        ),
        (
            "a missing database",
            format!("postgres://{USER}@{at}/nosuchdb"),
            right,
            r#"database "nosuchdb" does not exist"#,
        ),
        (
            "TLS the server does not offer",
            format!("{}?sslmode=require", pg.url()),
            right,
            "server does not support TLS",
        ),
        (
            "a port where SSH answers",
            format!("postgres://{USER}@127.0.0.1:{ssh}/postgres"),
            right,
            "does not speak PostgreSQL (it answered \"SSH-2.0-",
        ),
    ];
    for (what, url, file, cause) in cases {
        let args = ["--quiet", "--db", &url, "--db-password-file", file];
        let (code, lines, took) = refused_start(dir.path(), &args);
        assert_eq!(code, Some(2), "{what}: {lines:?}");
        assert_eq!(lines.len(), 1, "{what}: one line: {lines:?}");
        assert!(
            lines[0].starts_with("error: leaderboard postgres://")
                && lines[0].contains(cause)
                && lines[0].contains("--db-start-on-error"),
            "{what}: {lines:?}"
        );
        assert!(!lines[0].contains(PASSWORD), "{lines:?}");
        eprintln!(
            "{what}: the start stopped after {:.2} s",
            took.as_secs_f64()
        );
    }
    // The same under a JSON log: one start_failed event with the cause.
    let url = pg.url();
    let args = [
        "--quiet",
        "--log-format",
        "json",
        "--db",
        &url,
        "--db-password-file",
        wrong,
    ];
    let (code, lines, _) = refused_start(dir.path(), &args);
    assert_eq!(code, Some(2));
    assert_eq!(lines.len(), 1, "{lines:?}");
    let v: serde_json::Value = serde_json::from_str(&lines[0]).expect("JSON");
    assert_eq!(v["event"], "start_failed");
    assert!(
        v["text"]
            .as_str()
            .unwrap()
            .contains("password authentication failed"),
        "{v}"
    );
}

/// A sample of `/metrics` on `w`.
fn metric(w: &World, name: &str) -> f64 {
    series(&get(w.metrics, "/metrics").1, name)
}

const CONNECTED: &str = "halfcast_leaderboard_connected";
const WRITE_ERRORS: &str = r#"halfcast_leaderboard_writes_total{result="error"}"#;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_outage_at_start_and_a_refusal_told_to_start_queue_and_are_seen_by_alarms() {
    let Some(pg) = OwnCluster::start("a world started on a database that fails") else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    // Down at start: it starts, says so, and the alarms see it before any round ends.
    pg.stop();
    let mut w = World::start(&pg, dir.path(), Password::File, &[]);
    w.until("'is away'", |w| w.said("is away"));
    w.until("failed tries counted", |w| metric(w, WRITE_ERRORS) >= 2.0);
    assert_eq!(metric(&w, CONNECTED), 0.0);
    pg.resume();
    w.until("connected again", |w| metric(w, CONNECTED) == 1.0);
    w.until("'back after'", |w| w.said("back after"));
    drop(w);

    // A refusal, told to start anyway: the same, until the password file is fixed.
    let file = pg.password_file();
    let good = std::fs::read_to_string(&file).unwrap();
    std::fs::write(&file, "not-the-password\n").unwrap();
    let dir = tempfile::tempdir().expect("tempdir");
    let mut w = World::start(&pg, dir.path(), Password::File, &["--db-start-on-error"]);
    w.until("'refuses'", |w| {
        w.said("refuses") && w.said("starting anyway")
    });
    w.until("failed tries counted", |w| metric(w, WRITE_ERRORS) >= 2.0);
    assert_eq!(metric(&w, CONNECTED), 0.0);
    let mut ann = player(&w, "ann").await;
    play_rounds(&mut w, &mut ann, 0, 1).await;
    drop(ann);
    w.until("the round queued", |w| w.pending() >= 1.0);
    std::fs::write(&file, good).unwrap();
    let played = w.settled();
    assert_eq!(metric(&w, CONNECTED), 1.0);
    assert!(w.said("back after"), "{:#?}", w.lines);
    assert_eq!(pg.number("SELECT COUNT(*) FROM rounds"), played as i64);
    let errors = metric(&w, WRITE_ERRORS);
    eprintln!("refusing database: {errors} failed tries counted until it was fixed");
}

/// The seconds in a "back after N s" line.
fn back_after(lines: &[String]) -> Option<f64> {
    lines.iter().find_map(|l| {
        let rest = l.split("back after ").nth(1)?;
        rest.split(' ').next()?.parse().ok()
    })
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn round_ids_in_the_log_are_the_databases_and_an_idle_outage_is_seen_when_it_starts() {
    let Some(pg) = OwnCluster::start("round ids and an idle outage") else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let mut w = World::start(&pg, dir.path(), Password::File, &["--log-format", "json"]);
    let mut ann = player(&w, "ann").await;
    play_rounds(&mut w, &mut ann, 0, 3).await;
    drop(ann);
    let played = w.settled();
    let mut logged: Vec<String> = w
        .lines
        .iter()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter(|v| v["event"] == "round_end")
        .map(|v| v["round"].as_str().expect("a round id").to_owned())
        .collect();
    let mut stored = pg.texts("SELECT uid FROM rounds");
    logged.sort();
    stored.sort();
    assert_eq!(logged.len(), played);
    assert_eq!(logged, stored, "the log's round ids are the database's");

    // Nobody plays, no round ends: the outage is still seen when it starts, and its length
    // is the database's time away.
    pg.stop();
    let stopped = Instant::now();
    w.until("the outage seen", |w| w.said("cannot write"));
    assert_eq!(metric(&w, CONNECTED), 0.0);
    let seen_after = stopped.elapsed();
    pg.resume();
    let down = stopped.elapsed();
    w.until("'back after'", |w| w.said("back after"));
    let back = back_after(&w.lines).expect("a 'back after N s' line");
    eprintln!(
        "idle outage: seen {:.1} s after PostgreSQL stopped; down {:.1} s (stop to started \
         again); the world said back after {back} s",
        seen_after.as_secs_f64(),
        down.as_secs_f64()
    );
    assert_eq!(w.rounds(), played, "no round ended meanwhile");
}
