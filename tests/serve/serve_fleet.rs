//! A fleet of worlds that players meet as one server, behind a real HAProxy with the shipped
//! snippet (serve_haproxy.rs starts it): one host key whichever world answers, a returning
//! OpenSSH player with a real known_hosts file never refused, a world restarted (SIGTERM,
//! drained, started again) while players keep connecting without one failed connection, and
//! the balancer's health checks absent from the worlds' player logs and connection counters.

use crate::serve_haproxy::{deploy, haproxy, installed, tools, world, World};
use crate::serve_process::{spawn, Guard};
use crate::serve_support;

use std::path::Path;
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

use serve_support::http::{get, series};
use serve_support::openssh::SshPty;
use serve_support::{connect_raw, header_has, Client, PATIENCE};

/// Two worlds in `dir/w1` and `dir/w2` with one host key (the first world's, copied with its
/// mode 0600 to the second, as every instance of the unit loads the same credential).
fn two_worlds(dir: &Path, extra: &[&str]) -> [(Guard, World, mpsc::Receiver<String>); 2] {
    let (d1, d2) = (dir.join("w1"), dir.join("w2"));
    std::fs::create_dir_all(&d1).unwrap();
    std::fs::create_dir_all(&d2).unwrap();
    let first = world(&d1, extra);
    std::fs::copy(d1.join("hk"), d2.join("hk")).expect("copy the host key");
    let second = world(&d2, extra);
    [first, second]
}

/// The key's base64 blob as `ssh-keygen -y` derives it from the private key file.
fn public_blob(key: &Path) -> String {
    let out = Command::new("ssh-keygen")
        .arg("-y")
        .arg("-f")
        .arg(key)
        .output()
        .expect("ssh-keygen runs");
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    text.split_whitespace().nth(1).expect("a key").to_owned()
}

/// Log lines of a world that mark a connection to its SSH port.
fn connects(lines: &[String]) -> usize {
    lines.iter().filter(|l| l.ends_with("] connected")).count()
}

#[test]
fn one_host_key_through_the_balancer_and_a_returning_openssh_player_is_never_refused() {
    if !tools() {
        return;
    }
    let present = |tool: &str| Command::new(tool).output().is_ok();
    if !present("ssh-keyscan") || !present("ssh-keygen") {
        eprintln!(
            "SKIPPED: ssh-keyscan or ssh-keygen is not installed (apt-get install openssh-client)"
        );
        return;
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let [(_g1, w1, log1), (_g2, w2, log2)] = two_worlds(dir.path(), &["--db", "none"]);
    let (_haproxy, front) = haproxy(dir.path(), w1, w2);
    let key = public_blob(&dir.path().join("w1/hk"));

    // ssh-keyscan through the balancer, ten times over IPv4 and IPv6: one key, whichever world
    // answers.
    for i in 0..10 {
        let host = if i % 2 == 0 { "127.0.0.1" } else { "::1" };
        let out = Command::new("ssh-keyscan")
            .args(["-T", "10", "-t", "ed25519", "-p", &front.to_string(), host])
            .output()
            .expect("ssh-keyscan runs");
        let text = String::from_utf8_lossy(&out.stdout);
        let keys: Vec<&str> = text
            .lines()
            .filter_map(|l| l.split_whitespace().nth(2))
            .collect();
        assert_eq!(keys, [key.as_str()], "scan {i}: {text}");
    }

    // A returning player: OpenSSH with a real known_hosts file (the first login adds the key,
    // every later one checks it), ten logins, never refused.
    let known = dir.path().join("known_hosts");
    for i in 0..10 {
        let mut ssh = SshPty::spawn_checking(front, Some(&known), &[], (80, 24));
        let mut screen = vt100::Parser::new(24, 80, 0);
        let mut said = Vec::new();
        let deadline = Instant::now() + PATIENCE;
        while !header_has(screen.screen(), "you are ann") {
            let left = deadline.checked_duration_since(Instant::now());
            let got = left.and_then(|l| ssh.rx.recv_timeout(l).ok());
            let Some(b) = got else {
                panic!("login {i} never played: {}", String::from_utf8_lossy(&said));
            };
            said.extend_from_slice(&b);
            screen.process(&b);
        }
        let text = String::from_utf8_lossy(&said);
        assert!(
            !text.contains("IDENTIFICATION HAS CHANGED"),
            "login {i}: {text}"
        );
        let _ = ssh.child.kill();
        let _ = ssh.child.wait();
    }
    let lines = std::fs::read_to_string(&known).expect("known_hosts written");
    assert_eq!(lines.lines().count(), 1, "{lines}");
    assert!(lines.contains(&key), "{lines}");

    // Both worlds answered, and each counts exactly the connections it logged: 20 in all
    // (10 scans, 10 logins), none of them HAProxy's health checks, which have their own
    // counter and go to the metrics port.
    let deadline = Instant::now() + PATIENCE;
    let checked = |w: World| {
        series(
            &get(w.metrics, "/metrics").1,
            r#"halfcast_health_checks_total{answer="accepting"}"#,
        )
    };
    while checked(w1) < 2.0 || checked(w2) < 2.0 {
        assert!(
            Instant::now() < deadline,
            "HAProxy never checked both worlds"
        );
        std::thread::sleep(Duration::from_millis(200));
    }
    let mut total = 0.0;
    let mut all = Vec::new();
    for (w, log) in [(w1, &log1), (w2, &log2)] {
        let lines: Vec<String> = log.try_iter().collect();
        all.extend(lines.iter().cloned());
        let counted = series(&get(w.metrics, "/metrics").1, "halfcast_connections_total");
        assert!(
            counted >= 1.0,
            "world on {} never answered: {lines:#?}",
            w.ssh
        );
        assert_eq!(counted, connects(&lines) as f64, "{lines:#?}");
        assert!(
            lines.iter().all(|l| !l.contains("no PROXY header")),
            "a health check reached the SSH port: {lines:#?}"
        );
        total += counted;
    }
    assert_eq!(total, 20.0, "{all:#?}");
}

/// One player's try through the balancer: connect, log in, see the game, leave.
async fn attempt(addr: std::net::SocketAddr) -> Result<(), String> {
    let handle = tokio::time::timeout(PATIENCE, connect_raw(addr, None))
        .await
        .map_err(|_| "connect timed out".to_owned())?
        .map_err(|e| format!("connect: {e}"))?;
    let mut c = tokio::time::timeout(PATIENCE, Client::start(handle, "ann", "xterm", 80, 24))
        .await
        .map_err(|_| "login timed out".to_owned())??;
    if !c.until(|s| header_has(s, "you are ann")).await {
        return Err(format!("never played: {}", c.screen.screen().contents()));
    }
    let _ = c
        .handle
        .disconnect(russh::Disconnect::ByApplication, "", "")
        .await;
    Ok(())
}

/// Starts world `w` again on its own ports with its host key in `dir`; returns it once it
/// listens, with its log.
fn restart(dir: &Path, w: World, extra: &[&str]) -> (Guard, mpsc::Receiver<String>) {
    let m = w.metrics.to_string();
    let mut flags = vec!["--proxy-protocol", "--metrics", &m];
    flags.extend_from_slice(extra);
    let (guard, log) = spawn(w.ssh, &dir.join("hk"), &flags, &[]);
    let deadline = Instant::now() + PATIENCE;
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let line = log.recv_timeout(left).expect("the restarted world listens");
        if line.contains("listening on") {
            return (guard, log);
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_world_restarted_while_players_keep_connecting_fails_no_connection() {
    if !tools() {
        return;
    }
    const ATTEMPTS: usize = 100;
    const WORKERS: usize = 4;
    // Every player here comes from 127.0.0.1, and while world 1 is away all WORKERS log in to
    // world 2 at once: the per-address start-up cap (3 by default) must allow that, or world 2
    // turns the fourth away as it would a flood from one address.
    let flags = [
        "--db",
        "none",
        "--drain-seconds",
        "5",
        "--max-startups-per-ip",
        "8",
    ];
    let dir = tempfile::tempdir().expect("tempdir");
    let [(g1, w1, old_log1), (_g2, w2, log2)] = two_worlds(dir.path(), &flags);
    let (_haproxy, front) = haproxy(dir.path(), w1, w2);
    let addr: std::net::SocketAddr = format!("127.0.0.1:{front}").parse().unwrap();

    // Players keep connecting: WORKERS at a time, a pause between tries, ATTEMPTS in all.
    let started = Instant::now();
    let next = Arc::new(AtomicUsize::new(0));
    let done = Arc::new(AtomicUsize::new(0));
    let results = Arc::new(Mutex::new(Vec::new()));
    let mut workers = Vec::new();
    for _ in 0..WORKERS {
        let (next, done, results) = (Arc::clone(&next), Arc::clone(&done), Arc::clone(&results));
        workers.push(tokio::spawn(async move {
            while next.fetch_add(1, Ordering::Relaxed) < ATTEMPTS {
                let at = started.elapsed();
                let r = attempt(addr).await;
                results.lock().unwrap().push((at, r));
                done.fetch_add(1, Ordering::Relaxed);
                tokio::time::sleep(Duration::from_millis(250)).await;
            }
        }));
    }

    // A quarter of the way in, world 1 is restarted as systemd restarts it: SIGTERM, drained,
    // exited, started again on the same ports with the same key.
    while done.load(Ordering::Relaxed) < ATTEMPTS / 4 {
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let w1dir = dir.path().join("w1");
    let (down, up, _g1, log1) = tokio::task::spawn_blocking(move || {
        let mut g1 = g1;
        let down = started.elapsed();
        let pid = g1.0.id().to_string();
        let sent = Command::new("kill").args(["-TERM", &pid]).status();
        assert!(sent.is_ok_and(|s| s.success()), "SIGTERM sent");
        let deadline = Instant::now() + PATIENCE;
        while g1.0.try_wait().unwrap().is_none() {
            assert!(Instant::now() < deadline, "world 1 never stopped");
            std::thread::sleep(Duration::from_millis(20));
        }
        // Down for a moment, as a slow start-up would be.
        std::thread::sleep(Duration::from_millis(500));
        let (g1, log1) = restart(&w1dir, w1, &flags);
        (down, started.elapsed(), g1, log1)
    })
    .await
    .expect("restart");
    for w in workers {
        w.await.expect("worker");
    }
    let results = std::mem::take(&mut *results.lock().unwrap());
    assert_eq!(results.len(), ATTEMPTS);
    let failed: Vec<_> = results.iter().filter(|(_, r)| r.is_err()).collect();
    let during = results
        .iter()
        .filter(|(at, _)| *at >= down && *at <= up)
        .count();
    let after = results.iter().filter(|(at, _)| *at > up).count();
    eprintln!(
        "restart: world 1 down {:.2} s to {:.2} s; {during} attempts while it was away, \
         {after} after; {} failed of {ATTEMPTS}",
        down.as_secs_f64(),
        up.as_secs_f64(),
        failed.len()
    );
    let old: Vec<String> = old_log1.try_iter().collect();
    let tail = &old[old.len().saturating_sub(30)..];
    let refused: Vec<String> = log2.try_iter().filter(|l| l.contains("refused")).collect();
    assert!(
        failed.is_empty(),
        "failed connections: {failed:#?}\nthe restarted world's last lines: {tail:#?}\n\
         world 2's refusals: {refused:#?}"
    );
    assert!(during >= 3, "too few attempts over the restart: {during}");
    assert!(after >= 10, "too few attempts after the restart: {after}");

    // The restarted world rejoins: HAProxy's checks find it healthy and send it players again.
    let deadline = Instant::now() + PATIENCE;
    let mut tries = 0;
    loop {
        attempt(addr).await.expect("a later player");
        tries += 1;
        let lines: Vec<String> = log1.try_iter().collect();
        if connects(&lines) > 0 {
            break;
        }
        assert!(
            Instant::now() < deadline,
            "the restarted world got no player in {tries} tries"
        );
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
}

#[test]
fn the_snippet_passes_haproxys_check_beside_the_distributions_own_config() {
    let distro = Path::new("/etc/haproxy/haproxy.cfg");
    if !installed("haproxy", "-v") || !distro.exists() {
        eprintln!("SKIPPED: HAProxy or its /etc/haproxy/haproxy.cfg is not installed");
        return;
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let snippet = dir.path().join("halfcast.cfg");
    std::fs::write(&snippet, deploy("haproxy-halfcast.cfg")).unwrap();
    let out = Command::new("haproxy")
        .arg("-c")
        .arg("-f")
        .arg(distro)
        .arg("-f")
        .arg(&snippet)
        .output()
        .expect("haproxy -c runs");
    assert!(out.status.success(), "{out:?}");
    // The distribution's global section is what runs: the snippet brings none of its own.
    assert!(!deploy("haproxy-halfcast.cfg")
        .lines()
        .any(|l| l.trim_start().starts_with("global")));
}
