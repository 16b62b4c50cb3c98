//! `halfcast serve --web`: the browser edge's protocol with a WebSocket client that plays as the
//! page does: the page and /healthz, frames and their acknowledgements, keys with true release,
//! resize, bad messages closed with a reason, the Origin check, the server's limits, a trusted
//! proxy's client address, and an SSH player in the same world.

use std::net::SocketAddr;
use std::time::Duration;

use halfcast::serve::web::WebOptions;
use halfcast::serve::{RunningServer, ServeConfig};
use tempfile::TempDir;
use tokio_tungstenite::tungstenite::protocol::frame::coding::CloseCode;

use crate::serve_support::web::{open, upgrade, WebClient};
use crate::serve_support::{header_has, live_becomes, row_text, server, status_has, Client};

/// A server with the browser listener on a free port, `tweak`ed.
async fn web_server(tweak: impl FnOnce(&mut ServeConfig)) -> (RunningServer, TempDir, SocketAddr) {
    let (srv, dir) = server(|c| {
        c.web = Some(WebOptions::new("127.0.0.1:0".parse().unwrap()));
        tweak(c);
    })
    .await;
    let addr = srv.web_addr().expect("the web listener runs");
    (srv, dir, addr)
}

async fn play(addr: SocketAddr, name: &str) -> WebClient {
    open(addr, &format!("name={name}&cols=80&rows=24"), None)
        .await
        .expect("upgraded")
}

/// The text of the view's rows, for telling a still view from a moving one.
fn view_text(s: &vt100::Screen) -> String {
    (2..20).map(|r| s.contents_between(r, 0, r, 48)).collect()
}

fn view_colours(s: &vt100::Screen) -> Vec<String> {
    let mut out = Vec::new();
    for r in 2..20 {
        for c in 0..48 {
            if let Some(cell) = s.cell(r, c) {
                out.push(format!("{:?}{:?}", cell.fgcolor(), cell.bgcolor()));
            }
        }
    }
    out
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_its_script_and_health_are_served() {
    let (srv, _dir, addr) = web_server(|_| {}).await;
    let port = addr.port();
    let (page, (tables, link, info), health, missing) = tokio::task::spawn_blocking(move || {
        use crate::serve_support::http::get;
        (
            get(port, "/"),
            (
                get(port, "/js/tables.js"),
                get(port, "/js/link.js"),
                get(port, "/info.json"),
            ),
            get(port, "/healthz"),
            get(port, "/nothing"),
        )
    })
    .await
    .unwrap();
    assert_eq!(page.0, 200);
    assert!(page.1.contains("<canvas id=\"pixels\">"), "{}", page.1);
    assert!(
        !page.1.contains("http://") && !page.1.contains("https://"),
        "no CDN"
    );
    // The page's script is ES modules (contract 5): the tables, the connection.
    assert!(page.1.contains("src=\"js/main.js\""), "{}", page.1);
    assert_eq!(tables.0, 200);
    assert!(tables.1.starts_with("export const PALETTE = [[0,0,0],"));
    assert_eq!(link.0, 200);
    assert!(link.1.contains("new WebSocket("));
    let info: serde_json::Value = serde_json::from_str(&info.1).expect("/info.json is JSON");
    assert_eq!(info["players"], 0, "{info}");
    assert_eq!(info["mode"], "coop", "{info}");
    assert!(
        info["world"].as_str().is_some_and(|w| !w.is_empty()),
        "{info}"
    );
    assert_eq!(health, (200, "accepting\n".to_owned()));
    assert_eq!(missing.0, 404);
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn frames_wait_for_the_pages_acknowledgement() {
    let (srv, _dir, addr) = web_server(|_| {}).await;
    let mut page = play(addr, "wendy").await;
    page.acking = false;
    let first = page.frame(Duration::from_secs(20)).await.unwrap();
    assert!(first.is_some_and(|f| !f.is_empty()));
    // Not acknowledged: no second frame, however long the world moves on (the gate gives up on
    // a page only after five seconds without any acknowledgement).
    page.key("d", true).await;
    let held = page.frame(Duration::from_millis(1500)).await.unwrap();
    assert!(
        held.is_none(),
        "a frame went before the first was acknowledged"
    );
    page.send(r#"{"ack":1}"#).await;
    page.acking = true;
    assert!(page.frame(Duration::from_secs(20)).await.unwrap().is_some());
    page.key("d", false).await;
    assert!(
        page.until(|s| header_has(s, "you are wendy") && status_has(s, "truecolor (browser)"))
            .await,
        "{}\n{}",
        row_text(page.screen.screen(), 0),
        row_text(page.screen.screen(), 23)
    );
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_held_key_turns_the_view_and_its_release_stops_it() {
    let (srv, _dir, addr) = web_server(|_| {}).await;
    let mut page = play(addr, "turner").await;
    assert!(page.until(|s| header_has(s, "you are turner")).await);
    page.drain_for(Duration::from_millis(300)).await;
    let before = view_colours(page.screen.screen());
    page.key("ArrowRight", true).await;
    assert!(
        page.until(|s| view_colours(s) != before).await,
        "holding a key never turned the view"
    );
    page.key("ArrowRight", false).await;
    // After the release the view settles: two looks some frames apart see the same picture.
    let mut settled = false;
    for _ in 0..40 {
        page.drain_for(Duration::from_millis(250)).await;
        let a = view_colours(page.screen.screen());
        page.drain_for(Duration::from_millis(250)).await;
        if view_colours(page.screen.screen()) == a {
            settled = true;
            break;
        }
    }
    assert!(settled, "the view kept turning after the key's release");
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_resize_redraws_at_the_new_size() {
    let (srv, _dir, addr) = web_server(|_| {}).await;
    let mut page = play(addr, "stretch").await;
    assert!(page.until(|s| status_has(s, "quit")).await);
    page.screen.set_size(40, 160);
    page.send(r#"{"size":[160,40]}"#).await;
    // Wide enough, the status line names the input mode, as it does for kitty-protocol terminals.
    assert!(
        page.until(|s| status_has(s, "quit") && status_has(s, "browser keys"))
            .await,
        "{:?}",
        row_text(page.screen.screen(), 39)
    );
    assert!(!view_text(page.screen.screen()).is_empty());
    srv.shutdown().await;
}

/// A click on the page's view: the server says where the view is, freezes this player on the
/// clicked column, and answers with the ray in `halfcast trace`'s terms, which `trace` draws.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_clicked_column_comes_back_as_a_ray_that_trace_draws() {
    let (srv, dir, addr) = web_server(|_| {}).await;
    let mut page = play(addr, "learner").await;
    let view = page.note("view").await.expect("the view's place");
    assert!(page.until(|s| header_has(s, "you are learner")).await);
    let (cols, rows) = (
        view["cols"].as_u64().unwrap(),
        view["rows"].as_u64().unwrap(),
    );
    assert!(cols > 20 && rows > 5, "{view}");
    page.send(r#"{"ray":17}"#).await;
    let ray = page.note("ray").await.expect("the ray");
    assert_eq!(ray["column"], 17, "{ray}");
    assert_eq!(ray["size"], serde_json::json!([cols, rows]), "{ray}");
    assert!(ray.get("map").is_none(), "one map: none named");
    let pos = format!("{},{}", ray["pos"][0], ray["pos"][1]);
    let out = dir.path().join("ray.svg");
    let trace = std::process::Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(["trace", "--pos", &pos, "--angle", &ray["angle"].to_string()])
        .args(["--column", "17", "--size", &format!("{cols}x{rows}")])
        .args(["--fov", &ray["fov"].to_string(), "-o"])
        .arg(&out)
        .output()
        .expect("trace runs");
    assert!(trace.status.success(), "{trace:?}");
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(
        svg.contains("data-perp="),
        "a figure with its perpendicular distance"
    );
    // The view froze for this player: a held key no longer turns it.
    page.drain_for(Duration::from_millis(300)).await;
    let before = view_text(page.screen.screen());
    page.send(r#"{"key":"d","down":true}"#).await;
    page.drain_for(Duration::from_millis(500)).await;
    page.send(r#"{"key":"d","down":false}"#).await;
    assert_eq!(
        view_text(page.screen.screen()),
        before,
        "the view stays frozen"
    );
    // Leaving the debugger lets the view turn again.
    page.send(r#"{"ray":null}"#).await;
    page.drain_for(Duration::from_millis(300)).await;
    page.send(r#"{"key":"d","down":true}"#).await;
    assert!(
        page.until(|s| view_text(s) != before).await,
        "turning again"
    );
    srv.shutdown().await;
}

/// A page asking for more than an SSH pty may claim is drawn at the same bounds, and told so.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_page_gets_no_more_than_an_ssh_client_and_is_told_so() {
    let (srv, _dir, addr) = web_server(|_| {}).await;
    let mut page = play(addr, "greedy").await;
    assert!(page.until(|s| status_has(s, "quit")).await);
    let (cols, rows) = halfcast::play::size::clamp_size(u32::MAX, u32::MAX);
    page.screen.set_size(rows, cols);
    page.send(r#"{"size":[100000,100000]}"#).await;
    let told = format!("clamped to {cols}x{rows}");
    assert!(
        page.until(|s| header_has(s, &told)).await,
        "{:?}",
        row_text(page.screen.screen(), 0)
    );
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_messages_close_with_a_reason_and_the_server_goes_on() {
    let (srv, _dir, addr) = web_server(|_| {}).await;
    let cases: Vec<(String, CloseCode, &str)> = vec![
        ("{\"ack\":99}".into(), CloseCode::Policy, "never sent"),
        ("{\"size\":[0,5]}".into(), CloseCode::Policy, "out of range"),
        (
            "{\"key\":\"Hyper\",\"down\":true}".into(),
            CloseCode::Policy,
            "unknown key",
        ),
        ("rm -rf /".into(), CloseCode::Policy, "not a message"),
        ("x".repeat(10_000), CloseCode::Size, "too big"),
    ];
    for (msg, code, words) in cases {
        let mut page = play(addr, "bad").await;
        page.frame(Duration::from_secs(20)).await.unwrap();
        page.send(&msg).await;
        let closed = page.closed().await;
        assert_eq!(closed.code, Some(code), "{closed:?} for {:.40}", msg);
        assert!(closed.reason.contains(words), "{closed:?}");
    }
    // Binary from the page, and a flood of keys.
    let mut page = play(addr, "bin").await;
    page.frame(Duration::from_secs(20)).await.unwrap();
    use futures_util::SinkExt;
    let _ = page
        .ws
        .send(tokio_tungstenite::tungstenite::Message::Binary(
            vec![1, 2, 3].into(),
        ))
        .await;
    assert_eq!(page.closed().await.code, Some(CloseCode::Unsupported));
    let mut page = play(addr, "flood").await;
    page.frame(Duration::from_secs(20)).await.unwrap();
    for _ in 0..1000 {
        page.key("w", true).await;
    }
    let closed = page.closed().await;
    assert_eq!(closed.code, Some(CloseCode::Policy), "{closed:?}");
    // Nobody's mistakes ended the world: a good page still plays.
    let mut good = play(addr, "good").await;
    assert!(good.until(|s| header_has(s, "you are good")).await);
    assert!(live_becomes(&srv, (0, 1)).await, "{:?}", srv.live());
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn another_sites_page_is_refused_unless_named() {
    let (srv, _dir, addr) = web_server(|c| {
        if let Some(w) = c.web.as_mut() {
            w.origins = vec!["https://friends.example".into()];
        }
    })
    .await;
    let evil = open(addr, "name=x", Some("https://evil.example")).await;
    assert_eq!(evil.err(), Some(403));
    let own = format!("http://{addr}");
    let mut ours = open(addr, "name=own", Some(&own)).await.expect("own page");
    assert!(ours.frame(Duration::from_secs(20)).await.unwrap().is_some());
    let mut friend = open(addr, "name=friend", Some("https://friends.example"))
        .await
        .expect("named origin");
    assert!(friend
        .frame(Duration::from_secs(20))
        .await
        .unwrap()
        .is_some());
    assert_eq!(srv.stats().refused, 1);
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_servers_limits_apply_to_pages() {
    let (srv, _dir, addr) = web_server(|c| {
        c.max_sessions = 2;
        c.idle_timeout = Duration::from_secs(2);
    })
    .await;
    let mut a = play(addr, "a").await;
    let mut b = play(addr, "b").await;
    a.frame(Duration::from_secs(20)).await.unwrap();
    b.frame(Duration::from_secs(20)).await.unwrap();
    // Full: a third page is told so as the close reason.
    let mut c = play(addr, "c").await;
    let closed = c.closed().await;
    assert_eq!(closed.code, Some(CloseCode::Again), "{closed:?}");
    assert!(closed.reason.contains("server full"), "{closed:?}");
    // Idle: a page that sends no key is closed after the idle timeout, saying why.
    let closed = a.closed().await;
    assert!(closed.reason.contains("idle"), "{closed:?}");
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn per_address_limits_use_a_trusted_proxys_client_address() {
    let (srv, _dir, addr) = web_server(|c| {
        c.max_per_ip = 1;
        if let Some(w) = c.web.as_mut() {
            w.trusted_proxies = vec!["127.0.0.1".parse().unwrap()];
        }
    })
    .await;
    let via = |ip: &'static str| async move {
        use tokio_tungstenite::tungstenite::client::IntoClientRequest;
        let mut req = format!("ws://{addr}/ws?name=p&cols=80&rows=24")
            .into_client_request()
            .unwrap();
        req.headers_mut()
            .insert("X-Forwarded-For", ip.parse().unwrap());
        let tcp = tokio::net::TcpStream::connect(addr).await.unwrap();
        upgrade(req, tcp).await.expect("upgraded")
    };
    let mut one = via("203.0.113.1").await;
    let mut two = via("203.0.113.2").await;
    assert!(one.frame(Duration::from_secs(20)).await.unwrap().is_some());
    assert!(two.frame(Duration::from_secs(20)).await.unwrap().is_some());
    let mut again = via("203.0.113.1").await;
    let closed = again.closed().await;
    assert!(
        closed
            .reason
            .contains("too many connections from your address"),
        "{closed:?}"
    );
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ssh_and_browser_players_see_each_other() {
    let (srv, _dir, addr) = web_server(|_| {}).await;
    let mut page = play(addr, "webby").await;
    let mut ssh = Client::connect(srv.local_addr(), "sshy", 100, 20, "xterm-256color").await;
    assert!(
        ssh.until(|s| header_has(s, "webby")).await,
        "{}",
        row_text(ssh.screen.screen(), 0)
    );
    assert!(
        page.until(|s| header_has(s, "sshy")).await,
        "{}",
        row_text(page.screen.screen(), 0)
    );
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_draining_world_closes_the_web_port_and_tells_its_pages() {
    let (srv, _dir, addr) = web_server(|_| {}).await;
    let mut page = play(addr, "stayer").await;
    assert!(page.until(|s| header_has(s, "you are stayer")).await);
    srv.drain(Duration::from_millis(200)).await;
    assert!(
        tokio::net::TcpStream::connect(addr).await.is_err(),
        "the web port still takes connections while draining"
    );
    let stats = srv.shutdown_restarting().await;
    assert!(stats.connections >= 1);
    let closed = page.closed().await;
    assert!(closed.reason.contains("restarts"), "{closed:?}");
}

/// GET /metrics on `port`: the text format's lines.
fn metrics_text(port: u16) -> String {
    crate::serve_support::http::get(port, "/metrics").1
}

#[test]
fn the_command_line_serves_the_page_and_metrics_and_log_name_the_transport() {
    use crate::serve_process::{free_port, spawn_server};
    let dir = tempfile::tempdir().expect("tempdir");
    let (web_port, metrics_port) = (free_port(), free_port());
    let web = format!("127.0.0.1:{web_port}");
    let metrics = format!("127.0.0.1:{metrics_port}");
    let (_server, port, rx) = spawn_server(
        dir.path(),
        &["--web", &web, "--metrics", &metrics, "--log-format", "json"],
    );
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    let addr: SocketAddr = web.parse().unwrap();
    rt.block_on(async {
        let mut page = None;
        for _ in 0..100 {
            if tokio::net::TcpStream::connect(addr).await.is_ok() {
                page = Some(play(addr, "metered").await);
                break;
            }
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        let mut page = page.expect("the web port opens");
        assert!(page.until(|s| header_has(s, "you are metered")).await);
        let ssh_addr = format!("127.0.0.1:{port}").parse().unwrap();
        let mut ssh = Client::connect(ssh_addr, "shelly", 80, 24, "xterm-256color").await;
        assert!(ssh.until(|s| header_has(s, "shelly")).await);
        let text = tokio::task::spawn_blocking(move || metrics_text(metrics_port))
            .await
            .unwrap();
        assert!(
            text.contains(r#"halfcast_transport_sessions{transport="web"} 1"#),
            "{text}"
        );
        assert!(
            text.contains(r#"halfcast_transport_sessions{transport="ssh"} 1"#),
            "{text}"
        );
        let health = tokio::task::spawn_blocking(move || {
            crate::serve_support::http::get(web_port, "/healthz")
        })
        .await
        .unwrap();
        assert_eq!(health, (200, "accepting\n".to_owned()));
    });
    let mut seen = Vec::new();
    let deadline = std::time::Instant::now() + crate::serve_support::PATIENCE;
    while std::time::Instant::now() < deadline {
        match rx.recv_timeout(Duration::from_millis(200)) {
            Ok(line) => seen.push(line),
            Err(_) if seen.iter().any(|l| l.contains(r#""transport":"ssh""#)) => break,
            Err(_) => {}
        }
    }
    let login = |t: &str| {
        seen.iter().any(|l| {
            l.contains(r#""event":"login""#) && l.contains(&format!(r#""transport":"{t}""#))
        })
    };
    assert!(login("web") && login("ssh"), "{seen:#?}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_page_that_stops_acknowledging_is_dropped_as_a_stalled_reader() {
    let (srv, _dir, addr) = web_server(|c| c.stall_timeout = Duration::from_secs(2)).await;
    let mut page = play(addr, "sleepy").await;
    assert!(page.frame(Duration::from_secs(20)).await.unwrap().is_some());
    // From now on frames are read but never acknowledged, as a page frozen in a background tab
    // whose socket is still open; a held key keeps the world wanting new frames.
    page.acking = false;
    page.key("d", true).await;
    let closed = page.closed().await;
    assert!(closed.reason.contains("took no frame"), "{closed:?}");
    assert!(live_becomes(&srv, (0, 0)).await, "{:?}", srv.live());
    srv.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_spectating_page_follows_an_ssh_player_and_tab_switches() {
    let (srv, _dir, addr) = web_server(|_| {}).await;
    let mut watcher = open(addr, "spectate&cols=120&rows=40", None)
        .await
        .expect("upgraded");
    assert!(
        watcher
            .until(|s| header_has(s, "waiting for players"))
            .await
    );
    let mut ann = Client::connect(srv.local_addr(), "ann", 60, 16, "xterm-direct").await;
    let mut bob = play(addr, "bob").await;
    assert!(ann.until(|s| header_has(s, "2 here")).await);
    assert!(bob.until(|s| header_has(s, "2 here")).await);
    assert!(
        watcher
            .until(|s| header_has(s, "watching ann") || header_has(s, "watching bob"))
            .await,
        "{}",
        row_text(watcher.screen.screen(), 0)
    );
    let first = if header_has(watcher.screen.screen(), "watching ann") {
        "bob"
    } else {
        "ann"
    };
    watcher.key("Tab", true).await;
    watcher.key("Tab", false).await;
    assert!(
        watcher
            .until(|s| header_has(s, &format!("watching {first}")))
            .await,
        "{}",
        row_text(watcher.screen.screen(), 0)
    );
    // A spectator is not a player.
    assert!(header_has(watcher.screen.screen(), "2 here"));
    srv.shutdown().await;
}
