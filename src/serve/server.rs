//! The accept loop: admits connections within the limits, runs each in its own task (so no
//! session's panic or error reaches the loop) under the login grace deadline, logs connect and
//! disconnect with the duration.
//!
//! A connection turned away at accept (per-address or start-up limit, server full) is told why
//! without any key exchange: one text line before the SSH version line (RFC 4253 §4.2 allows
//! such lines, but OpenSSH's `ssh` shows them only with `-v`), the version line, then an
//! unencrypted SSH_MSG_DISCONNECT carrying the reason, which plain `ssh` prints as
//! "Received disconnect from HOST port PORT:12: REASON". One refused later (server full at
//! login, login grace over) gets the disconnect message inside the encrypted session.

use std::io;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use russh::server::Config;
use russh::{compression, Preferred};
use tokio::net::TcpListener;
use tokio::sync::watch;
use tokio::task::JoinHandle;

use super::config::ServeConfig;
use super::leaderboard::database::{self, Database};
use super::leaderboard::writer::Leaderboard;
use super::leaderboard::RoundRecord;
use super::limits::{Caps, Limiter, Refusal};
use super::ops::drain::{AFTER_LAST_ROUND, RESTARTING, SHUTTING_DOWN};
use super::ops::health::{Health, Readiness};
use super::ops::lifecycle::Lifeline;
use super::ops::log::Log;
use super::ops::metrics::Reason;
use super::ops::stats::{ServeStats, StatsSnapshot};
use super::proxy_header::{read_header, Inbound, Source, HEADER_WAIT};
use super::served_map::ServedMap;
use super::session_hooks::BoardLine;
use super::ssh::auth::Backoff;
use super::ssh::handler::{ConnHandler, Shared};
use super::ssh::hostkey;
use super::world_task::spawn_rounds;
use crate::game::multi::players::Rules;
use crate::game::multi::round::RoundEnd;
use crate::play::avatars::with_avatar_sheet;
use crate::world::World;

/// Compression offered to clients, most preferred first: the delayed `zlib@openssh.com`
/// (what OpenSSH's `ssh -C` asks for), plain `zlib`, or none.
const COMPRESSION: &[compression::Name] = &[
    compression::ZLIB_LEGACY,
    compression::ZLIB,
    compression::NONE,
];

/// A server started by [`start`]; stop it with [`RunningServer::shutdown`].
pub struct RunningServer {
    addr: SocketAddr,
    stats: Arc<ServeStats>,
    limiter: Limiter,
    shutdown: watch::Sender<bool>,
    /// Closes the SSH port (draining, then shutdown).
    stop_accepting: watch::Sender<bool>,
    /// What sessions are told when they end with the server.
    farewell: watch::Sender<&'static str>,
    /// Rounds finished so far (a draining world waits for the next).
    rounds: watch::Receiver<u64>,
    ready: Arc<Readiness>,
    /// True once the SSH port is closed and its queue taken in.
    closed: watch::Receiver<bool>,
    /// Connections taken in and still waiting for their PROXY header (not yet in the limits).
    header_waits: Arc<AtomicU64>,
    accept: JoinHandle<()>,
    metrics_http: Option<JoinHandle<()>>,
    leaderboard: Option<Leaderboard>,
    /// The browser listener's address, when `--web` serves one (it closes with the SSH port).
    web: Option<SocketAddr>,
}

impl RunningServer {
    /// The address actually bound (useful with port 0).
    #[must_use]
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// The browser listener's address (useful with port 0), when `--web` serves one.
    #[must_use]
    pub fn web_addr(&self) -> Option<SocketAddr> {
        self.web
    }

    /// Totals so far.
    #[must_use]
    pub fn stats(&self) -> StatsSnapshot {
        self.stats.snapshot()
    }

    /// Connections (logging in, playing or watching) the limits count right now, so callers can
    /// wait for the server to have noticed an arrival or a departure instead of guessing a delay.
    #[must_use]
    pub fn live(&self) -> (usize, usize) {
        self.limiter.live()
    }

    /// Stops accepting, tells every session to end, and waits (up to a few seconds) for them
    /// and for the leaderboard's queued writes; returns the totals after that, so sessions that
    /// were still running count too.
    pub async fn shutdown(self) -> StatsSnapshot {
        let _ = self.stop_accepting.send(true);
        let _ = self.shutdown.send(true);
        let _ = self.accept.await;
        for _ in 0..50 {
            if self.stats.snapshot().sessions_live == 0 {
                break;
            }
            tokio::time::sleep(Duration::from_millis(40)).await;
        }
        if let Some(lb) = &self.leaderboard {
            lb.flush(Duration::from_secs(5)).await;
        }
        if let Some(http) = &self.metrics_http {
            http.abort();
        }
        self.stats.snapshot()
    }

    /// Rounds finished since the server started (each queued for the leaderboard).
    #[must_use]
    pub fn rounds_finished(&self) -> u64 {
        *self.rounds.borrow()
    }

    /// Whether a load balancer should send this world players now (what `/healthz` says).
    #[must_use]
    pub fn health(&self) -> Health {
        self.ready.health()
    }

    /// Drains the world before it stops: `/healthz` answers 503 from now on, the SSH port
    /// closes (connections already waiting in its queue are still taken in), and this waits
    /// until nobody is logging in or playing, or until a round ends (then [`AFTER_LAST_ROUND`]
    /// more, so its results are seen), or until `patience` has passed. Sessions go on
    /// meanwhile, their players told the world restarts soon;
    /// [`RunningServer::shutdown_restarting`] then ends them.
    pub async fn drain(&self, patience: Duration) {
        self.ready.drain();
        // Sessions tell their players now (over the status line), and say it again at the end.
        self.farewell.send_replace(RESTARTING);
        super::ops::metrics::draining();
        let _ = self.stop_accepting.send(true);
        let deadline = tokio::time::Instant::now() + patience;
        let mut rounds = self.rounds.clone();
        rounds.borrow_and_update();
        // Every connection the port took is counted before "nobody is here" can be believed.
        let mut closed = self.closed.clone();
        let _ = tokio::time::timeout_at(deadline, closed.wait_for(|c| *c)).await;
        loop {
            let arriving = self.header_waits.load(Ordering::Relaxed);
            if self.limiter.live() == (0, 0) && arriving == 0 {
                return;
            }
            tokio::select! {
                () = tokio::time::sleep_until(deadline) => return,
                r = rounds.changed() => {
                    if r.is_ok() {
                        let pause = tokio::time::Instant::now() + AFTER_LAST_ROUND;
                        tokio::time::sleep_until(pause.min(deadline)).await;
                    }
                    return;
                }
                () = tokio::time::sleep(Duration::from_millis(50)) => {}
            }
        }
    }

    /// [`RunningServer::shutdown`], telling every player "this world restarts: reconnect to
    /// continue" (after [`RunningServer::drain`]).
    pub async fn shutdown_restarting(self) -> StatsSnapshot {
        self.farewell.send_replace(RESTARTING);
        self.shutdown().await
    }
}

/// Binds, loads or creates the host key, starts the world and the accept loop (one map).
///
/// # Errors
/// A message when the address cannot be bound or the host key cannot be read or created.
pub async fn start(config: ServeConfig, world: World) -> Result<RunningServer, String> {
    start_maps(config, vec![ServedMap::from_world(world)]).await
}

/// [`start`] with rounds rotating over `maps` (at least one).
///
/// # Errors
/// A message when there is no map, the address cannot be bound, the host key cannot be read or
/// created, the leaderboard cannot be opened or the metrics listener cannot start.
pub async fn start_maps(
    config: ServeConfig,
    maps: Vec<ServedMap>,
) -> Result<RunningServer, String> {
    if maps.is_empty() {
        return Err("no map to serve".into());
    }
    let log = Log::with_format(config.quiet, config.log_format);
    let (key, notes) = hostkey::load_or_generate(&config.host_key, config.insecure_host_key)?;
    for n in notes {
        log.server(n);
    }
    let mode = config.mode.name();
    let leaderboard = match &config.db {
        Some(path) => {
            let served: Vec<(String, String)> = maps
                .iter()
                .map(|m| (m.hash.clone(), mode.to_owned()))
                .collect();
            // On a thread outside the runtime: PostgreSQL's blocking client runs a runtime of
            // its own (start-up only; the writer thread has it from then on).
            let started = std::thread::scope(|s| {
                s.spawn(|| Leaderboard::start(Database::open(path)?, &served, log))
                    .join()
                    .unwrap_or_else(|_| Err("leaderboard: opening it panicked".into()))
            })?;
            log.server(format_args!("leaderboard in {}", database::shown(path)));
            Some(started)
        }
        None => None,
    };
    let metrics = match config.metrics {
        Some(addr) => {
            let handle = super::ops::metrics::install()?;
            let http = TcpListener::bind(addr)
                .await
                .map_err(|e| format!("cannot serve metrics on {addr}: {e}"))?;
            let bound = http.local_addr().map_err(|e| e.to_string())?;
            log.server(format_args!(
                "metrics on http://{bound}/metrics, health on http://{bound}/healthz"
            ));
            Some((handle, http))
        }
        None => None,
    };
    let listener = TcpListener::bind(config.listen)
        .await
        .map_err(|e| format!("cannot listen on {}: {e}", config.listen))?;
    let addr = listener.local_addr().map_err(|e| e.to_string())?;
    let ssh = Arc::new(Config {
        methods: config.auth.methods(),
        keys: vec![key],
        // The least a rejection waits; the handler adds a delay growing per source address.
        auth_rejection_time: Duration::from_millis(300),
        auth_rejection_time_initial: Some(Duration::ZERO),
        // russh counts every rejected request, the `none` probe included.
        max_auth_attempts: config.max_auth_tries,
        // Before a shell starts the login grace time applies (enforced by serve_connection).
        inactivity_timeout: Some(config.idle_timeout),
        keepalive_interval: Some(Duration::from_secs(30)),
        keepalive_max: 3,
        // Few internal messages per connection: frames wait here at most this many deep.
        event_buffer_size: 4,
        nodelay: true,
        preferred: Preferred {
            compression: std::borrow::Cow::Borrowed(COMPRESSION),
            ..Preferred::default()
        },
        ..Config::default()
    });
    let limiter = Limiter::new(
        Caps {
            max_sessions: config.max_sessions,
            max_per_ip: config.max_per_ip,
            startups: config.max_startups,
            startups_per_ip: config.max_startups_per_ip,
        },
        config.seed,
    );
    let hashes: Vec<String> = maps.iter().map(|m| m.hash.clone()).collect();
    let worlds: Vec<Arc<World>> = maps
        .into_iter()
        .map(|m| Arc::new(with_avatar_sheet(m.world).0))
        .collect();
    let (world, avatar_sheet) = with_avatar_sheet(World::clone(&worlds[0]));
    let (shutdown_tx, shutdown_rx) = watch::channel(false);
    let (stop_accepting, stop_accepting_rx) = watch::channel(false);
    let (farewell, farewell_rx) = watch::channel(SHUTTING_DOWN);
    let (rounds_tx, rounds) = watch::channel(0u64);
    let ready = Arc::new(Readiness::new(limiter.clone()));
    let metrics_http = metrics.map(|(handle, http)| {
        tokio::spawn(super::ops::metrics_http::serve(
            http,
            handle,
            Arc::clone(&ready),
        ))
    });
    let stats = Arc::new(ServeStats::default());
    let rules = Rules {
        mode: config.mode,
        seed: config.seed,
        round_limit: config.round_limit.map(|d| d.as_secs_f64()),
        results_seconds: config.results_time.as_secs_f64(),
        shuffle: config.shuffle,
    };
    let mut recorder = round_recorder(&worlds, &hashes, mode, leaderboard.clone(), log);
    let on_round = move |end: &RoundEnd| {
        recorder(end);
        rounds_tx.send_modify(|n| *n += 1);
    };
    let shared = Arc::new(Shared {
        world: spawn_rounds(worlds, config.tick_hz, rules, on_round),
        world_data: Arc::new(world),
        avatar_sheet,
        stats: Arc::clone(&stats),
        log,
        shutdown: shutdown_rx.clone(),
        farewell: farewell_rx,
        limiter: limiter.clone(),
        backoff: Backoff::default(),
        boards: leaderboard.clone().map(|board| BoardLine {
            board,
            hashes: Arc::new(hashes),
            mode,
        }),
        config,
    });
    log.server(format_args!("listening on {addr}"));
    let next_id = Arc::new(AtomicU64::new(1));
    let web = start_web(&shared, &ready, &next_id, stop_accepting.subscribe()).await?;
    let (closed_tx, closed) = watch::channel(false);
    let header_waits = Arc::new(AtomicU64::new(0));
    let accept = tokio::spawn(accept_loop(
        listener,
        ssh,
        (shared, next_id),
        (stop_accepting_rx, closed_tx, Arc::clone(&header_waits)),
    ));
    Ok(RunningServer {
        addr,
        stats,
        limiter,
        shutdown: shutdown_tx,
        stop_accepting,
        farewell,
        rounds,
        ready,
        closed,
        header_waits,
        accept,
        metrics_http,
        leaderboard,
        web,
    })
}

/// Starts the browser listener when `--web` asks for one, sharing the SSH edge's world, limits,
/// log and leaderboard; it closes when `stop` does.
async fn start_web(
    shared: &Shared,
    ready: &Arc<Readiness>,
    next_id: &Arc<AtomicU64>,
    stop: watch::Receiver<bool>,
) -> Result<Option<SocketAddr>, String> {
    let Some(options) = shared.config.web.clone() else {
        return Ok(None);
    };
    let edge = super::web::edge::WebEdge {
        options,
        config: shared.config.clone(),
        world: shared.world.clone(),
        world_data: Arc::clone(&shared.world_data),
        avatar_sheet: shared.avatar_sheet,
        stats: Arc::clone(&shared.stats),
        log: shared.log,
        shutdown: shared.shutdown.clone(),
        farewell: shared.farewell.clone(),
        limiter: shared.limiter.clone(),
        boards: shared.boards.clone(),
        ready: Arc::clone(ready),
        next_id: Arc::clone(next_id),
    };
    Ok(Some(super::web::listener::start(edge, stop).await?.0))
}

/// What the world task does with a finished round: log it, count it, queue it for the
/// leaderboard (never waiting for the disk).
fn round_recorder(
    worlds: &[Arc<World>],
    hashes: &[String],
    mode: &'static str,
    leaderboard: Option<Leaderboard>,
    log: Log,
) -> impl FnMut(&RoundEnd) + Send + 'static {
    let names: Vec<String> = worlds.iter().map(|w| w.map.name.clone()).collect();
    let hashes = hashes.to_vec();
    move |end: &RoundEnd| {
        super::ops::metrics::round(mode);
        let (name, hash) = (&names[end.map], &hashes[end.map]);
        let players: Vec<serde_json::Value> = end
            .players
            .iter()
            .map(|p| {
                serde_json::json!({ "name": p.name, "points": p.points, "items": p.items,
                    "it_seconds": (p.it_seconds * 10.0).round() / 10.0,
                    "reached_exit": p.reached_exit })
            })
            .collect();
        log.round_end(
            name,
            hash,
            mode,
            super::leaderboard::rounded_seconds(end.seconds),
            serde_json::Value::from(players),
        );
        if let Some(lb) = &leaderboard {
            let ended_at = SystemTime::now()
                .duration_since(UNIX_EPOCH)
                .map_or(0, |d| d.as_secs() as i64);
            lb.record(RoundRecord {
                map_hash: hash.clone(),
                map_name: name.clone(),
                mode: mode.to_owned(),
                seconds: end.seconds,
                cleared: end.cleared,
                ended_at,
                players: end.players.clone(),
            });
        }
    }
}

/// Refused sockets at most lingering at once to deliver their reason (beyond, just closed).
const MAX_LINGERING: usize = 64;
/// How long a refused socket lingers so its reason line arrives before the close.
const LINGER: Duration = Duration::from_millis(500);
/// Connections at most waiting at once for their PROXY header (beyond, closed at accept).
const MAX_HEADER_WAITS: u64 = 256;

/// What the accept loop hands each connection.
struct Door {
    ssh: Arc<Config>,
    shared: Arc<Shared>,
    /// Session numbers, shared with the browser listener.
    next_id: Arc<AtomicU64>,
    lingering: Arc<AtomicU64>,
    /// Shared with [`RunningServer`]: a draining world waits for these too.
    header_waits: Arc<AtomicU64>,
}

async fn accept_loop(
    listener: TcpListener,
    ssh: Arc<Config>,
    (shared, next_id): (Arc<Shared>, Arc<AtomicU64>),
    (mut stop, closed, header_waits): (watch::Receiver<bool>, watch::Sender<bool>, Arc<AtomicU64>),
) {
    let door = Arc::new(Door {
        ssh,
        shared,
        next_id,
        lingering: Arc::new(AtomicU64::new(0)),
        header_waits,
    });
    loop {
        let (socket, tcp_peer) = tokio::select! {
            _ = stop.changed() => break,
            r = listener.accept() => match r {
                Ok(x) => x,
                Err(e) => {
                    // E.g. out of file descriptors: back off instead of spinning.
                    door.shared.log.server(format_args!("accept failed: {e}"));
                    tokio::time::sleep(Duration::from_millis(100)).await;
                    continue;
                }
            },
        };
        enter(&door, socket, tcp_peer);
    }
    // Connections the kernel already completed are taken in (a balancer counts them as
    // delivered); closing the port with them queued would reset them.
    while let Ok(Ok((socket, tcp_peer))) =
        tokio::time::timeout(Duration::ZERO, listener.accept()).await
    {
        enter(&door, socket, tcp_peer);
    }
    drop(listener);
    closed.send_replace(true);
}

/// Takes in one accepted connection: admitted at once, or after its PROXY header.
fn enter(door: &Arc<Door>, socket: tokio::net::TcpStream, tcp_peer: SocketAddr) {
    let accepted = Instant::now();
    if !door.shared.config.proxy_protocol {
        admit(door, socket, tcp_peer, Inbound::refusing_headers, accepted);
        return;
    }
    // Behind a balancer: the header names the client; every limit applies to it.
    if door.header_waits.load(Ordering::Relaxed) >= MAX_HEADER_WAITS {
        return;
    }
    door.header_waits.fetch_add(1, Ordering::Relaxed);
    let door = Arc::clone(door);
    tokio::spawn(async move {
        let mut socket = socket;
        let got = tokio::time::timeout(HEADER_WAIT, read_header(&mut socket)).await;
        match got {
            Ok(Ok((source, head))) => {
                let peer = match source {
                    Source::Client(peer) => peer,
                    Source::Local => tcp_peer,
                };
                let inbound = move |s| Inbound::after_header(s, head);
                admit(&door, socket, peer, inbound, accepted);
            }
            Ok(Err(e)) => bad_header(&door, socket, tcp_peer, &e),
            Err(_) => bad_header(&door, socket, tcp_peer, "no PROXY header in time"),
        }
        // Only now: admitted, the limits count it (a draining world never sees it in neither).
        door.header_waits.fetch_sub(1, Ordering::Relaxed);
    });
}

/// Closes a connection whose PROXY header is missing or malformed.
fn bad_header(door: &Door, socket: tokio::net::TcpStream, tcp_peer: SocketAddr, why: &str) {
    ServeStats::add(&door.shared.stats.refused, 1);
    super::ops::metrics::refused(Reason::Proxy);
    door.shared
        .log
        .refusal(None, tcp_peer, Reason::Proxy.label(), why);
    let _ = socket.try_write(format!("halfcast: {why}\r\n").as_bytes());
}

/// Admits a connection from `peer` within the limits and runs it in a task of its own, or
/// tells it why not.
fn admit(
    door: &Door,
    socket: tokio::net::TcpStream,
    peer: SocketAddr,
    inbound: impl FnOnce(tokio::net::TcpStream) -> Inbound<tokio::net::TcpStream>,
    accepted: Instant,
) {
    let shared = &door.shared;
    let pending = match shared.limiter.admit(peer.ip()) {
        Ok(s) => s,
        Err(why) => {
            ServeStats::add(&shared.stats.refused, 1);
            super::ops::metrics::refused(why.reason());
            let (logging_in, playing) = shared.limiter.live();
            shared.log.refusal(
                None,
                peer,
                why.reason().label(),
                format_args!("{why} ({logging_in} logging in, {playing} playing)"),
            );
            refuse(socket, why, &door.lingering);
            return;
        }
    };
    ServeStats::add(&shared.stats.connections, 1);
    super::ops::metrics::connected();
    let id = door.next_id.fetch_add(1, Ordering::Relaxed);
    let ssh = Arc::clone(&door.ssh);
    let shared = Arc::clone(shared);
    let tcp = socket.local_addr().ok().zip(socket.peer_addr().ok());
    let stream = inbound(socket);
    tokio::spawn(async move {
        shared.log.connect(id, peer);
        let life = Arc::new(Lifeline::default());
        if let Some((local, remote)) = tcp {
            life.set_tcp(local, remote);
        }
        let handler = ConnHandler::new(id, peer, Arc::clone(&shared), pending, Arc::clone(&life));
        let deadline = accepted + shared.config.login_grace;
        let result = serve_connection(
            ssh,
            stream,
            handler,
            &life,
            deadline,
            (shared.shutdown.clone(), shared.farewell.clone()),
        )
        .await;
        let secs = accepted.elapsed().as_secs_f64();
        let err = result.err();
        if err
            .as_deref()
            .is_some_and(|e| e.starts_with("login grace time over"))
        {
            super::ops::metrics::refused(Reason::Grace);
        }
        shared.log.disconnect(
            id,
            peer,
            secs,
            life.wire_bytes(),
            life.link(),
            err.as_deref(),
        );
    });
}

/// SSH_DISCONNECT_TOO_MANY_CONNECTIONS (RFC 4250 §4.2.2).
const TOO_MANY_CONNECTIONS: u32 = 12;

/// What a refused client is sent, all before any key exchange: the reason as a text line
/// (shown by `ssh -v`, netcat, paramiko's log), our version line, and the reason again as an
/// SSH_MSG_DISCONNECT in the binary packet format with no encryption and no MAC (RFC 4253 §6),
/// which is what every SSH client reads next and what plain `ssh` prints.
#[must_use]
pub fn refusal_bytes(why: &Refusal) -> Vec<u8> {
    let reason = format!("halfcast: {why}");
    let mut out = format!("{reason}\r\nSSH-2.0-halfcast\r\n").into_bytes();
    let mut payload = vec![1u8]; // SSH_MSG_DISCONNECT
    payload.extend_from_slice(&TOO_MANY_CONNECTIONS.to_be_bytes());
    for s in [reason.as_str(), ""] {
        payload.extend_from_slice(&(s.len() as u32).to_be_bytes());
        payload.extend_from_slice(s.as_bytes());
    }
    // Length field, padding-length byte, payload and padding make a multiple of 8, with at
    // least 4 bytes of padding.
    let mut padding = 8 - (4 + 1 + payload.len()) % 8;
    if padding < 4 {
        padding += 8;
    }
    let packet_len = (1 + payload.len() + padding) as u32;
    out.extend_from_slice(&packet_len.to_be_bytes());
    out.push(padding as u8);
    out.extend_from_slice(&payload);
    out.extend(std::iter::repeat_n(0u8, padding));
    out
}

/// Tells a refused client why (see [`refusal_bytes`]), then closes; the socket lingers briefly
/// (a bounded number at once) so the reason is not lost to a reset.
fn refuse(socket: tokio::net::TcpStream, why: Refusal, lingering: &Arc<AtomicU64>) {
    // A fresh socket's send buffer is empty: this never blocks, and a short write is dropped.
    let _ = socket.try_write(&refusal_bytes(&why));
    if lingering.load(Ordering::Relaxed) >= MAX_LINGERING as u64 {
        return;
    }
    lingering.fetch_add(1, Ordering::Relaxed);
    let lingering = Arc::clone(lingering);
    tokio::spawn(async move {
        use tokio::io::{AsyncReadExt, AsyncWriteExt};
        let mut socket = socket;
        let _ = tokio::time::timeout(LINGER, async {
            let _ = socket.shutdown().await;
            // Read (and discard) what the client still sends until it closes too.
            let mut buf = [0u8; 512];
            while matches!(socket.read(&mut buf).await, Ok(n) if n > 0) {}
        })
        .await;
        lingering.fetch_sub(1, Ordering::Relaxed);
    });
}

/// Runs one connection until it ends, killing it when the login grace time passes before it
/// plays, or when the server shuts down.
async fn serve_connection(
    ssh: Arc<Config>,
    socket: Inbound<tokio::net::TcpStream>,
    handler: ConnHandler,
    life: &Lifeline,
    deadline: Instant,
    (mut shutdown, farewell): (watch::Receiver<bool>, watch::Receiver<&'static str>),
) -> Result<(), String> {
    let deadline = tokio::time::Instant::from_std(deadline);
    let stream = life.wrap(socket);
    // russh reads the client's version line before handing the connection to its own task.
    let running =
        match tokio::time::timeout_at(deadline, russh::server::run_stream(ssh, stream, handler))
            .await
        {
            Err(_) => return Err("login grace time over before the version line".into()),
            Ok(Err(e)) => return Err(e.to_string()),
            Ok(Ok(r)) => r,
        };
    let handle = running.handle();
    tokio::pin!(running);
    let mut playing = life.playing();
    let mut grace_over = false;
    let mut stopping = false;
    loop {
        let waiting = !*playing.borrow() && !grace_over;
        tokio::select! {
            r = &mut running => {
                return match r {
                    Ok(()) if grace_over => Err("login grace time over".into()),
                    Ok(()) => Ok(()),
                    Err(_) if grace_over => Err("login grace time over".into()),
                    Err(_) if life.killed() => Err("closed by the server".into()),
                    Err(e) => Err(e.to_string()),
                }
            }
            _ = playing.changed(), if waiting => {}
            () = tokio::time::sleep_until(deadline), if waiting => {
                grace_over = true;
                goodbye(&handle, russh::Disconnect::ByApplication, "login grace time over").await;
                life.kill();
            }
            _ = shutdown.changed(), if !stopping => {
                stopping = true;
                // Give sessions a moment to restore the client's terminal, then hang up.
                tokio::time::sleep(Duration::from_millis(300)).await;
                let why = *farewell.borrow();
                goodbye(&handle, russh::Disconnect::ByApplication, why).await;
                life.kill();
            }
        }
    }
}

/// Sends a disconnect message if the connection takes it soon, and leaves it a moment to go out.
async fn goodbye(handle: &russh::server::Handle, reason: russh::Disconnect, why: &str) {
    let sent = tokio::time::timeout(
        Duration::from_millis(200),
        handle.disconnect(reason, why.into(), String::new()),
    )
    .await;
    if matches!(sent, Ok(Ok(()))) {
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
}

/// Runs a server until Ctrl-C or SIGTERM (the `halfcast serve` command). Ctrl-C stops it at
/// once; SIGTERM (systemd's stop and restart) drains it first for up to `config.drain`, and a
/// second signal while draining stops it at once.
///
/// # Errors
/// A message when the runtime, the address or the host key fail.
pub fn run_until_signal(config: ServeConfig, maps: Vec<ServedMap>) -> Result<(), String> {
    let mut rt = tokio::runtime::Builder::new_multi_thread();
    rt.enable_all().max_blocking_threads(MAX_BLOCKING_THREADS);
    if let Some(n) = config.threads {
        rt.worker_threads(n);
    }
    let rt = rt
        .build()
        .map_err(|e| format!("cannot start the async runtime: {e}"))?;
    rt.block_on(async move {
        let log = Log::with_format(config.quiet, config.log_format);
        let patience = config.drain;
        let mut signals = Signals::new().map_err(|e| e.to_string())?;
        let server = start_maps(config, maps).await?;
        let stats = match signals.next().await {
            Stop::Interrupt => {
                log.server("shutting down");
                server.shutdown().await
            }
            Stop::Terminate => {
                let (logging_in, playing) = server.live();
                log.server(format_args!(
                    "draining: the port is closed and /healthz says 503; {playing} playing, \
                     {logging_in} logging in; stopping when they are gone, a round ends or \
                     {} s pass",
                    patience.as_secs()
                ));
                tokio::select! {
                    () = server.drain(patience) => {}
                    _ = signals.next() => log.server("a second signal: stopping now"),
                }
                log.server("shutting down: players are told to reconnect");
                server.shutdown_restarting().await
            }
        };
        log.server(format_args!(
            "served {} connections ({} refused), {} frames, {} bytes",
            stats.connections, stats.refused, stats.frames_sent, stats.bytes_sent
        ));
        Ok(())
    })
}

/// Threads the runtime may start for blocking work (only the leaderboard's flush at shutdown
/// uses one), so that the process's threads are its workers plus a known few (systemd's
/// `TasksMax` in docs/deploy/halfcast@.service counts them).
pub const MAX_BLOCKING_THREADS: usize = 4;

/// Which signal asked the server to stop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stop {
    /// Ctrl-C (SIGINT): stop now.
    Interrupt,
    /// SIGTERM: drain, then stop.
    Terminate,
}

/// The signals the server stops on, installed before it listens (so none is missed).
struct Signals {
    #[cfg(unix)]
    term: tokio::signal::unix::Signal,
    #[cfg(unix)]
    int: tokio::signal::unix::Signal,
}

impl Signals {
    fn new() -> io::Result<Self> {
        #[cfg(unix)]
        {
            use tokio::signal::unix::{signal, SignalKind};
            Ok(Self {
                term: signal(SignalKind::terminate())?,
                int: signal(SignalKind::interrupt())?,
            })
        }
        #[cfg(not(unix))]
        {
            Ok(Self {})
        }
    }

    /// The next stop signal.
    async fn next(&mut self) -> Stop {
        #[cfg(unix)]
        {
            tokio::select! {
                _ = self.int.recv() => Stop::Interrupt,
                _ = self.term.recv() => Stop::Terminate,
            }
        }
        #[cfg(not(unix))]
        {
            let _ = tokio::signal::ctrl_c().await;
            Stop::Interrupt
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_refusal_is_a_line_a_version_and_a_well_formed_disconnect_packet() {
        let bytes = refusal_bytes(&Refusal::TooManyFromAddress);
        let text = "halfcast: too many connections from your address";
        let head = format!("{text}\r\nSSH-2.0-halfcast\r\n");
        assert!(bytes.starts_with(head.as_bytes()));
        let packet = &bytes[head.len()..];
        let len = u32::from_be_bytes(packet[..4].try_into().unwrap()) as usize;
        assert_eq!(packet.len(), 4 + len);
        assert_eq!(packet.len() % 8, 0);
        let padding = usize::from(packet[4]);
        assert!(padding >= 4);
        let payload = &packet[5..4 + len - padding];
        assert_eq!(payload[0], 1, "SSH_MSG_DISCONNECT");
        assert_eq!(u32::from_be_bytes(payload[1..5].try_into().unwrap()), 12);
        let n = u32::from_be_bytes(payload[5..9].try_into().unwrap()) as usize;
        assert_eq!(&payload[9..9 + n], text.as_bytes());
        assert_eq!(&payload[9 + n..], &[0, 0, 0, 0], "an empty language tag");
    }
}
