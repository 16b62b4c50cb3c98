//! The server: its worlds, leaderboard, metrics and listeners started from the operator's
//! settings ([`start_maps`]), drained and stopped ([`RunningServer`]), run until a signal
//! ([`run_until_signal`]). The SSH edge's accept loop is [`super::ssh::listener`].

use std::io;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use metrics_exporter_prometheus::PrometheusHandle;
use tokio::net::TcpListener;
use tokio::sync::watch;
use tokio::task::JoinHandle;

use super::config::ServeConfig;
use super::edge::hooks::BoardLine;
use super::leaderboard::database;
use super::leaderboard::writer::Leaderboard;
use super::leaderboard::RoundRecord;
use super::limits::{Caps, Limiter};
use super::ops::drain::{RESTARTING, SHUTTING_DOWN};
use super::ops::health::{Health, Readiness};
use super::ops::log::Log;
use super::ops::stats::{ServeStats, StatsSnapshot};
use super::round_phase::RoundPhase;
use super::served_map::ServedMap;
use super::shared::Shared;
use super::ssh::hostkey;
pub use super::ssh::listener::refusal_bytes;
use super::ssh::listener::{accept_loop, russh_config};
use super::world_task::spawn_rounds;
use crate::game::multi::players::Rules;
use crate::game::multi::round::RoundEnd;
use crate::play::avatars::with_avatar_sheet;
use crate::play::world_port::WorldHandle;
use crate::world::World;

/// Where the world's round stands (a draining world waits for its end), and the switch that
/// holds its results (no next round) while draining.
type Phase = (watch::Receiver<RoundPhase>, watch::Sender<bool>);

/// The metrics exporter's handle and the listener for `/metrics` and `/healthz`.
type MetricsListener = (PrometheusHandle, TcpListener);

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
    /// Rounds finished so far.
    rounds: watch::Receiver<u64>,
    /// Where the round stands (a draining world waits for its end), and the switch that
    /// holds its results (no next round) while draining.
    phase: Phase,
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
    /// closes (connections already waiting in its queue are still taken in), no new round
    /// starts, and this waits until nobody is logging in or playing, or until the round ends
    /// (then [`super::ops::drain::AFTER_LAST_ROUND`] more, so its results are seen; at once-ish when
    /// they already show), or until `patience` has passed ([`super::ops::drain_wait`]). Sessions go on
    /// meanwhile, their players told the world restarts soon;
    /// [`RunningServer::shutdown_restarting`] then ends them.
    pub async fn drain(&self, patience: Duration) {
        self.ready.drain();
        // Sessions tell their players now (over the status line), and say it again at the end.
        self.farewell.send_replace(RESTARTING);
        super::ops::metrics::draining();
        let _ = self.stop_accepting.send(true);
        let deadline = tokio::time::Instant::now() + patience;
        // No next round: the one in play (or whose results show) is the last.
        self.phase.1.send_replace(true);
        // Every connection the port took is counted before "nobody is here" can be believed.
        let mut closed = self.closed.clone();
        let _ = tokio::time::timeout_at(deadline, closed.wait_for(|c| *c)).await;
        let present = || {
            let (logging_in, playing) = self.limiter.live();
            let arriving = self.header_waits.load(Ordering::Relaxed) > 0;
            (
                logging_in + playing > 0 || arriving,
                logging_in > 0 || arriving,
            )
        };
        super::ops::drain_wait::until_round_over(self.phase.0.clone(), &present, deadline).await;
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
    // First: the leaderboard's backlog found at start shows in the metrics.
    let metrics = bind_metrics(config.metrics, log).await?;
    let mode = config.mode.name();
    let leaderboard = open_leaderboard(&config, &maps, log)?;
    let listener = TcpListener::bind(config.listen)
        .await
        .map_err(|e| format!("cannot listen on {}: {e}", config.listen))?;
    let addr = listener.local_addr().map_err(|e| e.to_string())?;
    let ssh = Arc::new(russh_config(&config, key));
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
    let ready = Arc::new(Readiness::new(limiter.clone()));
    let metrics_http = metrics.map(|(handle, http)| {
        tokio::spawn(super::ops::metrics_http::serve(
            http,
            handle,
            Arc::clone(&ready),
        ))
    });
    let stats = Arc::new(ServeStats::default());
    let maps = worlds.clone();
    let (handle, phase, rounds) = start_world(&config, worlds, &hashes, leaderboard.clone(), log);
    let shared = Arc::new(Shared {
        world: handle,
        world_data: Arc::new(world),
        avatar_sheet,
        maps,
        stats: Arc::clone(&stats),
        log,
        shutdown: shutdown_rx.clone(),
        farewell: farewell_rx,
        limiter: limiter.clone(),
        boards: leaderboard.clone().map(|board| BoardLine {
            board,
            hashes: Arc::new(hashes),
            mode,
        }),
        config,
        next_id: AtomicU64::new(1),
    });
    log.server(format_args!("listening on {addr}"));
    let web = start_web(&shared, &ready, stop_accepting.subscribe()).await?;
    let (closed_tx, closed) = watch::channel(false);
    let header_waits = Arc::new(AtomicU64::new(0));
    let accept = tokio::spawn(accept_loop(
        listener,
        ssh,
        shared,
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
        phase,
        ready,
        closed,
        header_waits,
        accept,
        metrics_http,
        leaderboard,
        web,
    })
}

/// The Prometheus recorder installed, and `/metrics` and `/healthz` bound, when asked for.
async fn bind_metrics(
    addr: Option<SocketAddr>,
    log: Log,
) -> Result<Option<MetricsListener>, String> {
    Ok(match addr {
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
    })
}

/// The lasting leaderboard, when `--db` names one: opened (or its outage queued for), with the
/// served maps' boards read.
fn open_leaderboard(
    config: &ServeConfig,
    maps: &[ServedMap],
    log: Log,
) -> Result<Option<Leaderboard>, String> {
    let mode = config.mode.name();
    Ok(match &config.db {
        Some(path) => {
            let served: Vec<(String, String)> = maps
                .iter()
                .map(|m| (m.hash.clone(), mode.to_owned()))
                .collect();
            let target = super::leaderboard::writer::Target {
                db: path.clone(),
                password_file: config.db_password_file.clone(),
                queue_dir: config.queue_dir.clone().unwrap_or_else(|| {
                    super::leaderboard::writer::default_queue_dir(&config.host_key)
                }),
            };
            // On a thread outside the runtime: PostgreSQL's blocking client runs a runtime of
            // its own (start-up only; the writer thread has it from then on).
            let started = std::thread::scope(|s| {
                s.spawn(|| Leaderboard::start(target, &served, log))
                    .join()
                    .unwrap_or_else(|_| Err("leaderboard: opening it panicked".into()))
            })?;
            log.server(format_args!("leaderboard in {}", database::shown(path)));
            Some(started)
        }
        None => None,
    })
}

/// The world task over `worlds`, recording each finished round; returns the sessions' line to
/// it, where its round stands with the switch that holds its results, and the count of rounds.
fn start_world(
    config: &ServeConfig,
    worlds: Vec<Arc<World>>,
    hashes: &[String],
    leaderboard: Option<Leaderboard>,
    log: Log,
) -> (WorldHandle, Phase, watch::Receiver<u64>) {
    let mode = config.mode.name();
    let (rounds_tx, rounds) = watch::channel(0u64);
    let rules = Rules {
        mode: config.mode,
        seed: config.seed,
        round_limit: config.round_limit.map(|d| d.as_secs_f64()),
        results_seconds: config.results_time.as_secs_f64(),
        shuffle: config.shuffle,
    };
    let mut recorder = round_recorder(&worlds, hashes, mode, leaderboard, log);
    let on_round = move |end: &RoundEnd| {
        recorder(end);
        rounds_tx.send_modify(|n| *n += 1);
    };
    let (hold, held) = watch::channel(false);
    let (handle, round_phase) = spawn_rounds(worlds, config.tick_hz, rules, on_round, held);
    let phase = (round_phase, hold);
    (handle, phase, rounds)
}

/// Starts the browser listener when `--web` asks for one, sharing the SSH edge's world, limits,
/// log and leaderboard; it closes when `stop` does.
async fn start_web(
    shared: &Arc<Shared>,
    ready: &Arc<Readiness>,
    stop: watch::Receiver<bool>,
) -> Result<Option<SocketAddr>, String> {
    let Some(options) = shared.config.web.clone() else {
        return Ok(None);
    };
    let edge = super::web::edge::WebEdge {
        options,
        shared: Arc::clone(shared),
        ready: Arc::clone(ready),
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
    let mut ids = super::leaderboard::round_id::RoundIds::new();
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
                uid: ids.next_id(),
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
