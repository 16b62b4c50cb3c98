//! The browser edge behind Caddy, with the Caddyfile docs/serving.md shows as it is (its site
//! address moved to a plain-HTTP loopback port, since a test has no domain to get a certificate
//! for): pages from 127.0.0.2 and 127.0.0.3 that send `Forwarded` and `X-Forwarded-For` lines of
//! their own are logged and limited by their own addresses. Skipped with a notice without Caddy
//! or extra loopback addresses.

use std::process::Command;

use crate::serve_haproxy::installed;
use crate::serve_process::{free_port, spawn_listening, spawn_server, Guard};
use crate::serve_support::many_loopback_addresses;
use crate::serve_web_haproxy::forged_addresses_never_count;

/// The Caddyfile after "With Caddy:" in docs/serving.md.
fn documented_caddyfile() -> String {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/serving.md"))
        .expect("docs/serving.md");
    let after = doc
        .split("With Caddy:\n")
        .nth(1)
        .expect("the Caddy example");
    let block = after.split("```\n").nth(1).expect("its code block");
    block.to_owned()
}

/// Caddy on `caddyfile`, once it listens on `front`.
fn caddy(caddyfile: &str, front: u16, dir: &std::path::Path) -> Guard {
    let path = dir.join("Caddyfile");
    std::fs::write(&path, caddyfile).unwrap();
    let mut caddy = Command::new("caddy");
    caddy
        .args(["run", "--adapter", "caddyfile", "--config"])
        .arg(&path)
        .env("HOME", dir)
        .env("XDG_DATA_HOME", dir.join("data"))
        .env("XDG_CONFIG_HOME", dir.join("config"));
    spawn_listening(caddy, front)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_documented_caddyfile_gives_the_real_client_whatever_headers_it_sends() {
    if !installed("caddy", "version") {
        eprintln!("SKIPPED: Caddy is not installed (apt-get install caddy)");
        return;
    }
    if !many_loopback_addresses() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let web = free_port();
    let w = web.to_string();
    let (_world, _ssh, log) = spawn_server(
        dir.path(),
        &[
            "--web",
            &w,
            "--web-trusted-proxy",
            "127.0.0.1",
            "--max-per-ip",
            "1",
        ],
    );
    let front = free_port();
    let shipped = documented_caddyfile();
    assert!(
        shipped.contains("game.example.org {") && shipped.contains("reverse_proxy 127.0.0.1:8080"),
        "the documented Caddyfile changed: {shipped}"
    );
    let moved = shipped
        .replace(
            "game.example.org {",
            &format!("{{\n    admin off\n}}\nhttp://127.0.0.1:{front} {{"),
        )
        .replace("127.0.0.1:8080", &format!("127.0.0.1:{web}"));
    let _proxy = caddy(&moved, front, dir.path());
    forged_addresses_never_count(front, &log).await;
}
