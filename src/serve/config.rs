//! What an operator can set for `halfcast serve`, and the hard bounds no client can push past.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;

use super::limits::Startups;
use super::ssh::auth::AuthMode;

/// The size used when a client opens a shell without asking for a pty first.
pub const DEFAULT_SIZE: (u16, u16) = (80, 24);

/// `--max-startups` by default: OpenSSH's `10:30:100` with the all-refused point lower, since a
/// game server has fewer people logging in at once than a shell server.
pub const DEFAULT_STARTUPS: Startups = Startups {
    start: 10,
    rate: 30,
    full: 60,
};

/// Everything `serve` needs besides the world; built by the CLI, or by tests with `ServeConfig::local`.
#[derive(Debug, Clone)]
pub struct ServeConfig {
    /// Where to listen; port 0 picks a free port (tests).
    pub listen: SocketAddr,
    /// Ed25519 host key file: read if present, generated (0600) otherwise.
    pub host_key: PathBuf,
    /// How clients prove who they are (nothing, by default).
    pub auth: AuthMode,
    /// Sessions that play or watch at once; one more is told "server full".
    pub max_sessions: usize,
    /// Connections (logging in or playing) from one IP address; more are refused at accept.
    pub max_per_ip: usize,
    /// Connections still logging in (accept until the shell starts), as OpenSSH's
    /// `MaxStartups start:rate:full`.
    pub max_startups: Startups,
    /// Connections still logging in from one IP address.
    pub max_startups_per_ip: usize,
    /// From TCP accept to a playing session at most this long (OpenSSH's `LoginGraceTime`).
    pub login_grace: Duration,
    /// A client that takes no output for this long is disconnected (it stopped reading).
    pub stall_timeout: Duration,
    /// Failed authentications allowed on one connection (OpenSSH's `MaxAuthTries`).
    pub max_auth_tries: usize,
    /// Use a host key file others may read (sshd refuses such a key; so do we, by default).
    pub insecure_host_key: bool,
    /// Seed for the random early refusal of logging-in connections.
    pub seed: u64,
    /// A connection with no keystroke for this long is closed.
    pub idle_timeout: Duration,
    /// World ticks per second (movement, collisions, snapshots).
    pub tick_hz: u32,
    /// Frames per second each session aims for; slower links get fewer (latest frame wins).
    pub fps: u32,
    /// Silence the connect/disconnect log on stderr.
    pub quiet: bool,
    /// The game everybody plays: coop or tag.
    pub mode: crate::game::multi::round::Mode,
    /// Rounds last at most this long (`--round-minutes`; tag's default is 3 minutes).
    pub round_limit: Option<Duration>,
    /// How long a round's results show before the next round.
    pub results_time: Duration,
    /// Play the maps in a random order drawn from `seed` (`--shuffle`).
    pub shuffle: bool,
    /// The leaderboard's SQLite file, or a `postgres://` URL (`--db`); `None` keeps no
    /// leaderboard.
    pub db: Option<PathBuf>,
    /// A file whose first line is the PostgreSQL password (`--db-password-file`); else libpq's
    /// conventions (`PGPASSWORD`, `~/.pgpass`, …) apply.
    pub db_password_file: Option<PathBuf>,
    /// Use a PostgreSQL password file (`--db-password-file`, `~/.pgpass`) that others may read
    /// (`--db-insecure-password-file`; refused by default).
    pub db_insecure_password_file: bool,
    /// Start, and queue rounds, even when the database refuses at start (a wrong password, no
    /// such database: `--db-start-on-error`); by default only an outage is ridden out.
    pub db_start_on_error: bool,
    /// Where rounds wait while the leaderboard is away (`--queue-dir`; `None`: beside the host
    /// key).
    pub queue_dir: Option<PathBuf>,
    /// Where to serve Prometheus metrics (`--metrics`); `None` serves none.
    pub metrics: Option<SocketAddr>,
    /// Every connection starts with a PROXY protocol header naming the client's address.
    pub proxy_protocol: bool,
    /// Text lines or one JSON object per event (`--log-format`).
    pub log_format: super::ops::log::LogFormat,
    /// On SIGTERM, how long the world may drain (its round ending) before it stops
    /// (`--drain-seconds`).
    pub drain: Duration,
    /// Worker threads of `halfcast serve`'s runtime (`--threads`; `None`: one per core).
    pub threads: Option<usize>,
    /// Players in a browser (`--web`): the page and its WebSocket; `None` serves none.
    pub web: Option<super::web::WebOptions>,
}

impl ServeConfig {
    /// Defaults for a loopback server on `listen` with its host key at `host_key`.
    #[must_use]
    pub fn local(listen: SocketAddr, host_key: PathBuf) -> Self {
        Self {
            listen,
            host_key,
            auth: AuthMode::None,
            max_sessions: 32,
            max_per_ip: 8,
            max_startups: DEFAULT_STARTUPS,
            max_startups_per_ip: 3,
            login_grace: Duration::from_secs(20),
            stall_timeout: Duration::from_secs(30),
            max_auth_tries: 6,
            insecure_host_key: false,
            seed: 0x5eed,
            idle_timeout: Duration::from_secs(600),
            tick_hz: 30,
            fps: 30,
            quiet: false,
            mode: crate::game::multi::round::Mode::Coop,
            round_limit: None,
            results_time: Duration::from_secs_f64(crate::game::multi::round::RESULTS_SECONDS),
            shuffle: false,
            db: None,
            db_password_file: None,
            db_insecure_password_file: false,
            db_start_on_error: false,
            queue_dir: None,
            metrics: None,
            proxy_protocol: false,
            log_format: super::ops::log::LogFormat::Text,
            drain: super::ops::drain::DEFAULT_DRAIN,
            threads: None,
            web: None,
        }
    }
}
