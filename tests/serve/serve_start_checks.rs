//! What a world says before its first player: every series docs/serving.md lists is on
//! `/metrics` already (at 0, the counters and the per-session gauges), and a start that fails
//! says why in one line, as JSON under `--log-format json` even when clap refuses a flag, and
//! refuses a database password file others may read, or a mistyped database URL.

use crate::serve_process::{free_port, spawn, spawn_server};
use crate::serve_support::http::get;

use std::process::Command;

/// The series names in docs/serving.md's table of series (`| \`halfcast_…\` …`).
fn documented_series() -> Vec<String> {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/serving.md"))
        .expect("docs/serving.md");
    let mut names = Vec::new();
    for row in doc.lines().filter(|l| l.starts_with("| `halfcast_")) {
        let first_cell = row.split(" | ").next().unwrap_or("");
        for token in first_cell.split('`').skip(1).step_by(2) {
            let name = token.split('{').next().unwrap_or(token);
            if name.starts_with("halfcast_") && !names.iter().any(|n| n == name) {
                names.push(name.to_owned());
            }
        }
    }
    names
}

/// The value of the sample `name` (with its labels, as written) on `/metrics`, if present.
fn sample(metrics: &str, name: &str) -> Option<f64> {
    metrics
        .lines()
        .filter(|l| !l.starts_with('#'))
        .find_map(|l| {
            let (n, v) = l.rsplit_once(' ')?;
            (n == name).then(|| v.parse().ok()).flatten()
        })
}

#[test]
fn every_documented_series_is_there_at_0_before_the_first_player() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (mport, web) = (free_port(), free_port());
    let (_srv, _port, _log) = spawn_server(
        dir.path(),
        &["--metrics", &mport.to_string(), "--web", &web.to_string()],
    );
    let (status, m) = get(mport, "/metrics");
    assert_eq!(status, 200);
    let names = documented_series();
    assert!(names.len() >= 18, "the table was read: {names:?}");
    for name in &names {
        let there = m.lines().any(|l| {
            l.strip_prefix(name.as_str())
                .is_some_and(|rest| rest.starts_with([' ', '{', '_']))
        });
        assert!(there, "{name} is documented but not on /metrics:\n{m}");
    }
    for zero in [
        r#"halfcast_transport_sessions{transport="ssh"}"#,
        r#"halfcast_transport_sessions{transport="web"}"#,
        r#"halfcast_refusals_total{reason="origin"}"#,
        r#"halfcast_refusals_total{reason="proxy"}"#,
        r#"halfcast_leaderboard_reads_total{result="error"}"#,
        r#"halfcast_leaderboard_writes_total{result="error"}"#,
        "halfcast_link_wait_seconds_count",
        "halfcast_frame_render_seconds_count",
        "halfcast_frame_encode_seconds_count",
        r#"halfcast_link_wait_seconds_bucket{le="+Inf"}"#,
        "halfcast_frames_sent_total",
    ] {
        assert_eq!(sample(&m, zero), Some(0.0), "{zero}:\n{m}");
    }
    // The SQLite file beside the host key answered.
    assert_eq!(
        sample(&m, "halfcast_leaderboard_connected"),
        Some(1.0),
        "{m}"
    );
}

/// Runs `halfcast ARGS` to its end; its exit code and stderr.
fn run(args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(args)
        .output()
        .expect("halfcast runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn a_flag_error_under_a_json_log_is_one_json_line() {
    for bad in [
        &["serve", "--max-sessions", "0", "--log-format", "json"][..],
        &["serve", "--log-format=json", "--no-such-flag"],
        &[
            "serve",
            "--log-format",
            "json",
            "--web-forwarded-header",
            "x-real-ip",
        ],
    ] {
        let (code, err) = run(bad);
        assert_eq!(code, Some(2), "{bad:?}: {err}");
        let lines: Vec<&str> = err.lines().collect();
        assert_eq!(lines.len(), 1, "{bad:?}: one line:\n{err}");
        let v: serde_json::Value = serde_json::from_str(lines[0]).expect("JSON");
        assert_eq!(v["event"], "start_failed", "{err}");
        let text = v["text"].as_str().unwrap();
        assert!(text.contains("--"), "names the flag: {text}");
    }
    // The text log keeps clap's own words.
    let (code, err) = run(&["serve", "--max-sessions", "0"]);
    assert_eq!(code, Some(2));
    assert!(
        err.starts_with("error: ") && err.contains("--max-sessions"),
        "{err}"
    );
}

#[cfg(unix)]
#[test]
fn a_database_password_file_others_may_read_is_refused_with_the_fix() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("db_password");
    std::fs::write(&file, "not-said\n").unwrap();
    std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o644)).unwrap();
    let f = file.to_str().unwrap();
    // No server answers at this address: refused before any try, so the password is never
    // sent.
    let url = "postgres://halfcast@127.0.0.1:9/halfcast";
    let hk = dir.path().join("hk");
    let hk = hk.to_str().unwrap();
    let (code, err) = run(&[
        "serve",
        "--quiet",
        "--host-key",
        hk,
        "--listen",
        "127.0.0.1:0",
        "--db",
        url,
        "--db-password-file",
        f,
    ]);
    assert_ne!(code, Some(0));
    assert!(
        err.contains("mode 0644") && err.contains(&format!("chmod 600 {f}")),
        "{err}"
    );
    assert!(
        !err.contains("not-said") && err.lines().count() == 1,
        "{err}"
    );
    let (code, err) = run(&["scores", "--db", url, "--db-password-file", f]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains(&format!("chmod 600 {f}")), "{err}");
    // Told to use it anyway, it gets as far as the (absent) server.
    let (code, err) = run(&[
        "scores",
        "--db",
        url,
        "--db-password-file",
        f,
        "--db-insecure-password-file",
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("cannot connect") && !err.contains("chmod"),
        "{err}"
    );
    // At mode 0600 it is used.
    std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o600)).unwrap();
    let (_, err) = run(&["scores", "--db", url, "--db-password-file", f]);
    assert!(
        err.contains("cannot connect") && !err.contains("chmod"),
        "{err}"
    );
}

#[test]
fn a_mistyped_database_url_stops_the_start_and_makes_no_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let hk = dir.path().join("hk");
    for url in [
        "postgres//halfcast@127.0.0.1/halfcast",
        "postgresql:/127.0.0.1/halfcast",
        "postgre://halfcast@127.0.0.1/halfcast",
    ] {
        let args = ["--quiet", "--db", url, "--log-format", "json"];
        let (mut srv, log) = spawn(free_port(), &hk, &args, &[]);
        let status = srv.0.wait().unwrap();
        let lines: Vec<String> = log.iter().collect();
        assert_eq!(status.code(), Some(2), "{url}: {lines:?}");
        assert_eq!(lines.len(), 1, "{lines:?}");
        assert!(
            lines[0].contains("start_failed") && lines[0].contains("postgres://USER@HOST"),
            "{lines:?}"
        );
        let first = url.split('/').next().unwrap();
        assert!(
            !std::path::Path::new(first).exists() && !dir.path().join(first).exists(),
            "{url} made no SQLite file or directory"
        );
    }
}
