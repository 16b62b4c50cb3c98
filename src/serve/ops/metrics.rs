//! What the server reports to Prometheus (`--metrics ADDR`): the series' names in one place,
//! and the recorder whose text [`super::metrics_http`] serves.
//!
//! The server records through the `metrics` facade whether or not an exporter is installed;
//! without one every record is a no-op. Per-frame series go through handles made once per
//! session, so a frame costs a few atomic additions.

use std::time::Duration;

use metrics::{counter, describe_counter, describe_gauge, describe_histogram, gauge, histogram};
use metrics::{Counter, Histogram, Unit};
use metrics_exporter_prometheus::{Matcher, PrometheusBuilder, PrometheusHandle};

/// Sessions playing or watching now, by `state` ("playing", "watching").
pub const SESSIONS: &str = "halfcast_sessions";
/// Sessions playing or watching now, by `transport` ("ssh", "web").
pub const TRANSPORT_SESSIONS: &str = "halfcast_transport_sessions";
/// Connections accepted and still logging in (TCP accept to shell start).
pub const LOGGING_IN: &str = "halfcast_logging_in";
/// Connections accepted since start.
pub const CONNECTIONS: &str = "halfcast_connections_total";
/// Connections turned away, by `reason`: full, per-address, startups, auth, grace, stall,
/// proxy (a missing or bad PROXY header).
pub const REFUSALS: &str = "halfcast_refusals_total";
/// Sessions that panicked (a bug; each ended that session only), by `transport`.
pub const SESSION_FAILURES: &str = "halfcast_session_failures_total";
/// Frames sent to clients.
pub const FRAMES_SENT: &str = "halfcast_frames_sent_total";
/// Frame ticks skipped because a client was still taking the previous frame.
pub const FRAMES_SKIPPED: &str = "halfcast_frames_skipped_total";
/// Terminal bytes of the frames sent (before SSH's compression and encryption).
pub const PAYLOAD_BYTES: &str = "halfcast_payload_bytes_total";
/// Bytes written to clients' TCP sockets (SSH packets: compressed, encrypted, framed).
pub const WIRE_BYTES: &str = "halfcast_wire_bytes_total";
/// Time to cast one frame's 3D view and its overlays.
pub const RENDER_SECONDS: &str = "halfcast_frame_render_seconds";
/// Time to draw the panes and encode one frame to terminal bytes.
pub const ENCODE_SECONDS: &str = "halfcast_frame_encode_seconds";
/// Time of one world tick (every player's step, the level, the round's rules).
pub const TICK_SECONDS: &str = "halfcast_world_tick_seconds";
/// Rounds finished, by `mode`.
pub const ROUNDS: &str = "halfcast_rounds_total";
/// Leaderboard writes, by `result` ("ok": a round written; "error": a try that failed, its
/// round kept in the queue; "dropped": a round lost, the writer's queues being full).
pub const DB_WRITES: &str = "halfcast_leaderboard_writes_total";
/// Rounds waiting to be written to the leaderboard (the database away, or its disk full).
pub const PENDING_ROUNDS: &str = "halfcast_leaderboard_pending_rounds";

/// How long a frame ready to be drawn waited for the client's link to take the last one (zero
/// for most frames on a fast link): the lag a slow link adds to what the player sees.
pub const LINK_WAIT_SECONDS: &str = "halfcast_link_wait_seconds";
/// Colour level steps a session's link called for, by `direction` ("down", "up").
pub const LINK_LEVEL_STEPS: &str = "halfcast_link_level_steps_total";

/// Histogram buckets for the timing series, in seconds (0.1 ms to 0.5 s).
const BUCKETS: &[f64] = &[
    0.0001, 0.00025, 0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5,
];

/// Why a connection was turned away, as the `reason` label says it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reason {
    /// `--max-sessions` reached.
    Full,
    /// `--max-per-ip` or the per-address share of logging-in connections.
    PerAddress,
    /// `--max-startups`.
    Startups,
    /// A failed authentication attempt.
    Auth,
    /// The login grace time ran out.
    Grace,
    /// The client stopped taking output.
    Stall,
    /// A missing or malformed PROXY protocol header (or one sent without `--proxy-protocol`).
    Proxy,
    /// A WebSocket upgrade from another site's page (`--web`'s Origin check).
    Origin,
}

impl Reason {
    /// Every reason, for the series that exist at 0 from the start.
    pub const ALL: [Reason; 7] = [
        Reason::Full,
        Reason::PerAddress,
        Reason::Startups,
        Reason::Auth,
        Reason::Grace,
        Reason::Stall,
        Reason::Proxy,
    ];

    /// The label value.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Reason::Full => "full",
            Reason::PerAddress => "per-address",
            Reason::Startups => "startups",
            Reason::Auth => "auth",
            Reason::Grace => "grace",
            Reason::Stall => "stall",
            Reason::Proxy => "proxy",
            Reason::Origin => "origin",
        }
    }
}

/// Makes the Prometheus recorder the process's recorder; [`super::metrics_http`] serves what
/// the returned handle renders (`/metrics`) beside `/healthz`.
///
/// # Errors
/// A message when a recorder is already installed.
pub fn install() -> Result<PrometheusHandle, String> {
    let handle = PrometheusBuilder::new()
        .set_buckets_for_metric(Matcher::Suffix("_seconds".into()), BUCKETS)
        .and_then(PrometheusBuilder::install_recorder)
        .map_err(|e| format!("cannot record metrics: {e}"))?;
    describe();
    describe_fleet();
    zeroes();
    Ok(handle)
}

/// Every series, each label value included, at 0 from the start: `increase()` and `rate()`
/// then see a world's first refusal or failed write as the step from 0 it is, not as a new
/// series with no past.
fn zeroes() {
    for why in Reason::ALL {
        counter!(REFUSALS, "reason" => why.label()).absolute(0);
    }
    for transport in ["ssh", "web"] {
        counter!(SESSION_FAILURES, "transport" => transport).absolute(0);
    }
    for result in ["ok", "error", "dropped"] {
        counter!(DB_WRITES, "result" => result).absolute(0);
    }
    for mode in ["coop", "tag"] {
        counter!(ROUNDS, "mode" => mode).absolute(0);
    }
    for answer in ["accepting", "draining", "full"] {
        counter!(HEALTH_CHECKS, "answer" => answer).absolute(0);
    }
    for state in ["playing", "watching"] {
        gauge!(SESSIONS, "state" => state).set(0.0);
    }
    for direction in ["down", "up"] {
        counter!(LINK_LEVEL_STEPS, "direction" => direction).absolute(0);
    }
    for name in [
        CONNECTIONS,
        FRAMES_SENT,
        FRAMES_SKIPPED,
        PAYLOAD_BYTES,
        WIRE_BYTES,
    ] {
        counter!(name).absolute(0);
    }
    gauge!(LOGGING_IN).set(0.0);
    gauge!(PENDING_ROUNDS).set(0.0);
}

/// Help lines for every series.
fn describe() {
    describe_gauge!(SESSIONS, "Sessions playing or watching now, by state.");
    describe_gauge!(
        TRANSPORT_SESSIONS,
        "Sessions playing or watching now, by transport."
    );
    describe_gauge!(LOGGING_IN, "Connections accepted and still logging in.");
    describe_counter!(CONNECTIONS, "Connections accepted.");
    describe_counter!(REFUSALS, "Connections turned away, by reason.");
    describe_counter!(
        SESSION_FAILURES,
        "Sessions that panicked, by transport (each ended that session only)."
    );
    describe_counter!(FRAMES_SENT, "Frames sent to clients.");
    describe_counter!(
        FRAMES_SKIPPED,
        "Frame ticks skipped while a client was still taking the previous frame."
    );
    describe_counter!(
        PAYLOAD_BYTES,
        Unit::Bytes,
        "Terminal bytes of frames sent, before SSH."
    );
    describe_counter!(
        WIRE_BYTES,
        Unit::Bytes,
        "Bytes written to client sockets (SSH packets)."
    );
    describe_histogram!(RENDER_SECONDS, Unit::Seconds, "3D view cast per frame.");
    describe_histogram!(
        ENCODE_SECONDS,
        Unit::Seconds,
        "Panes and encoding per frame."
    );
    describe_histogram!(TICK_SECONDS, Unit::Seconds, "One world tick.");
    describe_histogram!(
        LINK_WAIT_SECONDS,
        Unit::Seconds,
        "How long a frame ready to be drawn waited for the client's link."
    );
    describe_counter!(
        LINK_LEVEL_STEPS,
        "Colour level steps a session's link called for, by direction."
    );
    describe_counter!(ROUNDS, "Rounds finished, by mode.");
    describe_counter!(DB_WRITES, "Leaderboard writes, by result.");
    describe_gauge!(
        PENDING_ROUNDS,
        "Rounds queued for the leaderboard, not yet written."
    );
}

/// A connection was turned away.
pub fn refused(why: Reason) {
    counter!(REFUSALS, "reason" => why.label()).increment(1);
}

/// A session over `transport` panicked.
pub fn session_failed(transport: &'static str) {
    counter!(SESSION_FAILURES, "transport" => transport).increment(1);
}

/// A connection was accepted.
pub fn connected() {
    counter!(CONNECTIONS).increment(1);
}

/// One more (`up`) or one fewer connection logging in.
pub fn logging_in(up: bool) {
    let g = gauge!(LOGGING_IN);
    if up {
        g.increment(1.0);
    } else {
        g.decrement(1.0);
    }
}

/// One more (`up`) or one fewer session over `transport` ("ssh", "web").
pub fn transport_session(transport: &'static str, up: bool) {
    let g = gauge!(TRANSPORT_SESSIONS, "transport" => transport);
    if up {
        g.increment(1.0);
    } else {
        g.decrement(1.0);
    }
}

/// One more (`up`) or one fewer session playing (or watching, for a spectator).
pub fn session(spectator: bool, up: bool) {
    let g = gauge!(SESSIONS, "state" => if spectator { "watching" } else { "playing" });
    if up {
        g.increment(1.0);
    } else {
        g.decrement(1.0);
    }
}

/// One world tick took `d`.
pub fn world_tick(d: Duration) {
    histogram!(TICK_SECONDS).record(d.as_secs_f64());
}

/// A round of `mode` finished.
pub fn round(mode: &'static str) {
    counter!(ROUNDS, "mode" => mode).increment(1);
}

/// A leaderboard write ended with `result` ("ok", "error", "dropped").
pub fn db_write(result: &'static str) {
    counter!(DB_WRITES, "result" => result).increment(1);
}

/// `n` rounds wait for the leaderboard.
pub fn pending_rounds(n: usize) {
    gauge!(PENDING_ROUNDS).set(n as f64);
}

/// The per-frame series, resolved once per session.
#[derive(Clone)]
pub struct FrameMetrics {
    sent: Counter,
    skipped: Counter,
    payload: Counter,
    render: Histogram,
    encode: Histogram,
    link_wait: Histogram,
}

impl FrameMetrics {
    /// Handles to the frame series of the installed recorder (no-ops without one).
    #[must_use]
    pub fn new() -> Self {
        Self {
            sent: counter!(FRAMES_SENT),
            skipped: counter!(FRAMES_SKIPPED),
            payload: counter!(PAYLOAD_BYTES),
            render: histogram!(RENDER_SECONDS),
            encode: histogram!(ENCODE_SECONDS),
            link_wait: histogram!(LINK_WAIT_SECONDS),
        }
    }

    /// A frame of `bytes` went out.
    pub fn sent(&self, bytes: usize) {
        self.sent.increment(1);
        self.payload.increment(bytes as u64);
    }

    /// `n` frame ticks were skipped.
    pub fn skipped(&self, n: u64) {
        if n > 0 {
            self.skipped.increment(n);
        }
    }

    /// A frame ready to be drawn waited `d` for the link.
    pub fn link_wait(&self, d: Duration) {
        self.link_wait.record(d.as_secs_f64());
    }

    /// The link called for a step of the colour level, down or up.
    pub fn level_step(&self, down: bool) {
        counter!(LINK_LEVEL_STEPS, "direction" => if down { "down" } else { "up" }).increment(1);
    }

    /// A frame took `render` to cast and `encode` to draw and encode.
    pub fn timed(&self, render: Duration, encode: Duration) {
        self.render.record(render.as_secs_f64());
        self.encode.record(encode.as_secs_f64());
    }
}

impl Default for FrameMetrics {
    fn default() -> Self {
        Self::new()
    }
}

/// The wire-bytes counter, for a connection's socket wrapper.
pub fn wire_bytes() -> Counter {
    counter!(WIRE_BYTES)
}

/// `/healthz` requests answered, by `answer` ("accepting", "draining", "full"): a balancer's
/// checks, kept apart from the players' connections.
pub const HEALTH_CHECKS: &str = "halfcast_health_checks_total";
/// Always 1, labelled with the build's `version` and `commit`: which release, and which build
/// of it, each world of a fleet runs.
pub const BUILD_INFO: &str = "halfcast_build_info";
/// The git commit this binary was built from (build.rs: `HALFCAST_COMMIT` if set, else `git
/// rev-parse HEAD` in a checkout), or "unknown" (a crates.io package has no `.git`).
pub const COMMIT: &str = env!("HALFCAST_COMMIT");
/// Whether the world is draining before it stops (1) or accepting players (0).
pub const DRAINING: &str = "halfcast_draining";

/// Help lines for the fleet's series (health checks, build, process).
fn describe_fleet() {
    describe_counter!(
        HEALTH_CHECKS,
        "Health checks answered on /healthz, by answer."
    );
    describe_gauge!(
        BUILD_INFO,
        "Always 1; the build's version and git commit as labels."
    );
    describe_gauge!(DRAINING, "1 while the world drains before stopping.");
    describe_gauge!(
        "process_resident_memory_bytes",
        Unit::Bytes,
        "Resident memory."
    );
    describe_gauge!(
        "process_virtual_memory_bytes",
        Unit::Bytes,
        "Virtual memory."
    );
    describe_gauge!(
        "process_cpu_seconds_total",
        Unit::Seconds,
        "User and system CPU time."
    );
    describe_gauge!("process_open_fds", "Open file descriptors.");
    describe_gauge!("process_max_fds", "Limit on open file descriptors.");
    describe_gauge!("process_threads", "Threads.");
    describe_gauge!(
        "process_start_time_seconds",
        Unit::Seconds,
        "Start time, in Unix seconds."
    );
    gauge!(BUILD_INFO, "version" => env!("CARGO_PKG_VERSION"), "commit" => COMMIT).set(1.0);
    gauge!(DRAINING).set(0.0);
}

/// A `/healthz` request was answered with `answer`.
pub fn health_check(answer: &'static str) {
    counter!(HEALTH_CHECKS, "answer" => answer).increment(1);
}

/// The world started draining.
pub fn draining() {
    gauge!(DRAINING).set(1.0);
}

/// Brings the series read at scrape time up to date (the process's own figures).
pub fn before_scrape() {
    let p = super::process_stats::ProcessStats::read();
    for (name, v) in [
        ("process_resident_memory_bytes", p.resident_bytes),
        ("process_virtual_memory_bytes", p.virtual_bytes),
        ("process_cpu_seconds_total", p.cpu_seconds),
        ("process_open_fds", p.open_fds),
        ("process_max_fds", p.max_fds),
        ("process_threads", p.threads),
        ("process_start_time_seconds", p.start_time),
    ] {
        if let Some(v) = v {
            gauge!(name).set(v);
        }
    }
}
