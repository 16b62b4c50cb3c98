//! `halfcast serve`: the SSH server's flags, turned into its configuration.

use std::net::SocketAddr;
use std::path::{Path, PathBuf};

use clap::Args;
use halfcast::serve::log::LogFormat;
use halfcast::serve::ServedMap;

use super::Failure;

/// The environment variable a password may come from (kept out of the process list).
pub(crate) const PASSWORD_ENV: &str = "HALFCAST_PASSWORD";

#[derive(Args, Debug)]
pub(crate) struct ServeArgs {
    /// The .cub maps rounds play, one per round in turn (default: the embedded map).
    #[arg(value_name = "MAP")]
    pub(crate) maps: Vec<PathBuf>,
    /// Treat a missing or unreadable texture as an error instead of a warning.
    #[arg(long)]
    pub(crate) strict: bool,
    /// Play the maps in a random order (a new order each pass, drawn from --seed).
    #[arg(long)]
    pub(crate) shuffle: bool,
    /// Seed for --shuffle and the creatures (default: a fresh one each start).
    #[arg(long)]
    pub(crate) seed: Option<u64>,
    /// A round lasts at most this many minutes (coop: otherwise until the exit; tag: 3).
    #[arg(long, value_name = "N", value_parser = parse_minutes)]
    pub(crate) round_minutes: Option<f64>,
    /// How long a round's results show before the next round, in seconds.
    #[arg(long, value_name = "SECONDS", value_parser = parse_results_seconds)]
    pub(crate) results_seconds: Option<f64>,
    /// The leaderboard's SQLite file (default: halfcast.sqlite beside the host key; `none`
    /// keeps no leaderboard), or a postgres://USER@HOST/DB URL shared by worlds on several
    /// hosts (its password from --db-password-file, PGPASSWORD or ~/.pgpass: never the URL).
    #[arg(long, value_name = "FILE|URL")]
    pub(crate) db: Option<PathBuf>,
    /// The PostgreSQL password on this file's first line (systemd: LoadCredential=).
    #[arg(long, value_name = "FILE")]
    pub(crate) db_password_file: Option<PathBuf>,
    /// Where rounds wait, on disk, while the leaderboard is away (default: halfcast-queue
    /// beside the host key); a world started with the same directory writes them.
    #[arg(long, value_name = "DIR")]
    pub(crate) queue_dir: Option<PathBuf>,
    /// Serve Prometheus metrics on http://ADDR/metrics (a bare port listens on 127.0.0.1).
    #[arg(long, value_name = "ADDR", value_parser = parse_metrics_addr)]
    pub(crate) metrics: Option<SocketAddr>,
    /// Serve players in a browser: the page at http://ADDR/ and its WebSocket, in the same
    /// world as the SSH port (a bare port listens on 127.0.0.1; TLS is a proxy's job).
    #[arg(long, value_name = "ADDR", value_parser = parse_metrics_addr)]
    pub(crate) web: Option<SocketAddr>,
    /// Another site whose page may open the game's WebSocket (e.g. https://example.org);
    /// repeatable. The page served by --web itself always may.
    #[arg(long, value_name = "ORIGIN", requires = "web")]
    pub(crate) web_origin: Vec<String>,
    /// A reverse proxy in front of --web whose X-Forwarded-For / Forwarded header names the
    /// player's address; repeatable.
    #[arg(long, value_name = "IP", requires = "web")]
    pub(crate) web_trusted_proxy: Vec<std::net::IpAddr>,
    /// Compress the page's frames: auto (while its link holds them back), always, or never.
    #[arg(long, value_enum, default_value = "auto", requires = "web")]
    pub(crate) web_compress: halfcast::serve::web::Compress,
    /// Every connection starts with a PROXY protocol v1 or v2 header (behind HAProxy or
    /// another balancer); its address is the one limits, logs and metrics use.
    #[arg(long)]
    pub(crate) proxy_protocol: bool,
    /// The log's form on stderr: text lines, or one JSON object per event.
    #[arg(long, default_value = "text", value_parser = parse_log_format)]
    pub(crate) log_format: LogFormat,
    /// Address to listen on (port 0 picks a free one; the log says which).
    #[arg(long, default_value = "127.0.0.1:2222")]
    pub(crate) listen: std::net::SocketAddr,
    /// Ed25519 host key: read if it exists, else generated there with mode 0600.
    #[arg(long, default_value = "halfcast_host_ed25519")]
    pub(crate) host_key: PathBuf,
    /// Use a host key file that others may read (refused by default, as sshd does).
    #[arg(long)]
    pub(crate) insecure_host_key: bool,
    /// Require this password; every local user can read it in the process list, so prefer
    /// --password-file or the HALFCAST_PASSWORD environment variable.
    #[arg(long, conflicts_with_all = ["authorized_keys", "password_file"])]
    pub(crate) password: Option<String>,
    /// Require the password on this file's first line.
    #[arg(long, conflicts_with = "authorized_keys")]
    pub(crate) password_file: Option<PathBuf>,
    /// Accept only the public keys in this OpenSSH authorized_keys file.
    #[arg(long)]
    pub(crate) authorized_keys: Option<PathBuf>,
    /// Most sessions playing or watching at once (connections still logging in don't count).
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub(crate) max_sessions: u32,
    /// Most connections (logging in or playing) from one IP address.
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub(crate) max_per_ip: u32,
    /// Connections still logging in, as OpenSSH's MaxStartups: beyond START of them refuse
    /// RATE % of newcomers, rising to all at FULL (or N: refuse beyond N).
    #[arg(long, default_value = "10:30:60", value_name = "START:RATE:FULL")]
    pub(crate) max_startups: String,
    /// Most connections still logging in from one IP address.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub(crate) max_startups_per_ip: u32,
    /// Seconds from TCP connect to a playing session before the connection is closed.
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u64).range(1..=3_600))]
    pub(crate) login_grace: u64,
    /// Seconds a client may take no output (it stopped reading) before it is disconnected.
    #[arg(long, default_value_t = 30, value_parser = clap::value_parser!(u64).range(1..=3_600))]
    pub(crate) stall_timeout: u64,
    /// Failed authentication requests allowed on one connection.
    #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u32).range(1..=100))]
    pub(crate) max_auth_tries: u32,
    /// Close a connection after this many seconds without a keystroke.
    #[arg(long, default_value_t = 600, value_parser = clap::value_parser!(u64).range(1..=86_400))]
    pub(crate) idle_timeout: u64,
    /// Frames per second per session (slow links get fewer).
    #[arg(long, default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..=240))]
    pub(crate) fps: u32,
    /// No connect/disconnect log on stderr.
    #[arg(long)]
    pub(crate) quiet: bool,
    /// On SIGTERM, stop accepting (/healthz says 503) and let the round in play end for at
    /// most this many seconds before players are told to reconnect (0: at once).
    #[arg(long, default_value_t = 30, value_parser = clap::value_parser!(u64).range(0..=3_600))]
    pub(crate) drain_seconds: u64,
    /// Worker threads (default: one per core); the process runs these plus at most 6 more
    /// (main, leaderboard, blocking pool), which is what systemd's TasksMax must allow.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1_024))]
    pub(crate) threads: Option<u32>,
    /// The game: coop (shared points, anyone's exit ends the round) or tag (one player is
    /// "it"; touching passes it on; the least time as "it" wins).
    #[arg(long, default_value = "coop", value_parser = parse_mode)]
    pub(crate) mode: halfcast::game::multi::round::Mode,
}

fn parse_mode(s: &str) -> Result<halfcast::game::multi::round::Mode, String> {
    s.parse()
}

fn parse_log_format(s: &str) -> Result<LogFormat, String> {
    s.parse()
}

/// Minutes, more than 0 and at most a day (fractions allowed: 0.5 is thirty seconds).
fn parse_minutes(s: &str) -> Result<f64, String> {
    let v = super::options::parse_finite(s)?;
    if v > 0.0 && v <= 1440.0 {
        Ok(v)
    } else {
        Err(format!(
            "{v} minutes: a round lasts more than 0 and at most 1440 minutes"
        ))
    }
}

/// Seconds, at least 0.1 and at most an hour.
fn parse_results_seconds(s: &str) -> Result<f64, String> {
    let v = super::options::parse_finite(s)?;
    if (0.1..=3600.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!(
            "{v} seconds: results show from 0.1 to 3600 seconds"
        ))
    }
}

/// `HOST:PORT`, or a bare `PORT` on the loopback address.
pub(crate) fn parse_metrics_addr(s: &str) -> Result<SocketAddr, String> {
    if let Ok(port) = s.parse::<u16>() {
        return Ok(SocketAddr::from(([127, 0, 0, 1], port)));
    }
    s.parse()
        .map_err(|_| format!("'{s}' is neither HOST:PORT nor a port number"))
}

/// Every map, read and checked before the server listens; all the errors at once.
fn load_maps(paths: &[PathBuf], strict: bool) -> Result<Vec<ServedMap>, Failure> {
    if paths.is_empty() {
        return Ok(vec![ServedMap::embedded()]);
    }
    let mut maps = Vec::new();
    let mut errors = Vec::new();
    for p in paths {
        match ServedMap::from_file(p, strict) {
            Ok((m, warnings)) => {
                for w in warnings {
                    eprintln!("{w}");
                }
                maps.push(m);
            }
            Err(e) => errors.push(e),
        }
    }
    if errors.is_empty() {
        Ok(maps)
    } else {
        Err(Failure::input(errors.join("\nerror: ")))
    }
}

/// The leaderboard file: `--db`, `none` for none, else beside the host key.
fn db_path(db: Option<&Path>, host_key: &Path) -> Option<PathBuf> {
    match db {
        Some(p) if p == Path::new("none") => None,
        Some(p) => Some(p.to_path_buf()),
        None => Some(
            host_key
                .parent()
                .unwrap_or_else(|| Path::new(""))
                .join(halfcast::serve::leaderboard::DEFAULT_FILE),
        ),
    }
}

/// Refuses a `--db` URL that carries a password: a world runs for weeks, and all that time
/// every local user could read the password in its command line (`ps`, /proc/PID/cmdline).
/// Refused rather than warned about, since a warning is read once and the leak goes on; the
/// message says where the password goes instead.
fn no_password_in_url(db: Option<&Path>) -> Result<(), Failure> {
    use halfcast::serve::leaderboard::{database, pg_config};
    match db.and_then(database::postgres_url) {
        Some(url) if pg_config::url_has_password(url) => Err(Failure::input(format!(
            "--db {}: a password in the URL is readable by every local user in the process \
             list; give it in --db-password-file FILE (systemd: LoadCredential=), PGPASSWORD, \
             or ~/.pgpass (PGPASSFILE), and drop it from the URL",
            database::shown(Path::new(url))
        ))),
        _ => Ok(()),
    }
}

/// The authentication mode from the flags and the environment; warns about `--password`.
fn auth_mode(args: &ServeArgs) -> Result<halfcast::serve::auth::AuthMode, Failure> {
    use halfcast::serve::auth::{password_from_file, AuthMode};
    let env = std::env::var(PASSWORD_ENV).ok().filter(|p| !p.is_empty());
    let password = if let Some(p) = &args.password {
        if p.is_empty() {
            return Err(Failure::input("--password must not be empty"));
        }
        eprintln!(
            "halfcast serve: warning: --password is visible to every local user in the process \
             list; use --password-file or {PASSWORD_ENV}"
        );
        Some(p.clone())
    } else if let Some(path) = &args.password_file {
        Some(password_from_file(path).map_err(Failure::input)?)
    } else {
        env
    };
    match (password, &args.authorized_keys) {
        (Some(_), Some(_)) => Err(Failure::input(format!(
            "{PASSWORD_ENV} is set and --authorized-keys given: choose one way to log in"
        ))),
        (Some(p), None) => Ok(AuthMode::Password(p)),
        (None, Some(path)) => AuthMode::from_authorized_keys(path).map_err(Failure::input),
        (None, None) => Ok(AuthMode::None),
    }
}

/// `halfcast serve`; under `--log-format json` a failure to start is written as a JSON event
/// too (with its cause), so a log shipper sees why a world never came up.
pub(crate) fn serve(args: ServeArgs) -> Result<(), Failure> {
    let format = args.log_format;
    match start_and_run(args) {
        Err(f) if format == LogFormat::Json => {
            halfcast::serve::log::Log::with_format(false, format).failed_to_start(&f.message);
            Err(Failure {
                code: f.code,
                message: String::new(),
            })
        }
        done => done,
    }
}

fn start_and_run(args: ServeArgs) -> Result<(), Failure> {
    use halfcast::serve::limits::Startups;
    use halfcast::serve::{run_until_signal, ServeConfig};
    use std::time::Duration;
    let startups: Startups = args
        .max_startups
        .parse()
        .map_err(|e| Failure::input(format!("--max-startups {e}")))?;
    let auth = auth_mode(&args)?;
    let maps = load_maps(&args.maps, args.strict)?;
    let db = db_path(args.db.as_deref(), &args.host_key);
    no_password_in_url(db.as_deref())?;
    let mut config = ServeConfig::local(args.listen, args.host_key);
    config.db = db;
    config.db_password_file = args.db_password_file;
    config.queue_dir = args.queue_dir;
    config.metrics = args.metrics;
    config.proxy_protocol = args.proxy_protocol;
    config.web = args.web.map(|listen| halfcast::serve::web::WebOptions {
        listen,
        origins: args.web_origin.clone(),
        trusted_proxies: args.web_trusted_proxy.clone(),
        compress: args.web_compress,
    });
    config.log_format = args.log_format;
    config.shuffle = args.shuffle;
    if let Some(secs) = args.results_seconds {
        config.results_time = Duration::from_secs_f64(secs);
    }
    config.round_limit = args
        .round_minutes
        .map(|m| Duration::from_secs_f64(m * 60.0));
    config.auth = auth;
    config.insecure_host_key = args.insecure_host_key;
    config.max_sessions = args.max_sessions as usize;
    config.max_per_ip = args.max_per_ip as usize;
    config.max_startups = startups;
    config.max_startups_per_ip = args.max_startups_per_ip as usize;
    config.login_grace = Duration::from_secs(args.login_grace);
    config.stall_timeout = Duration::from_secs(args.stall_timeout);
    config.max_auth_tries = args.max_auth_tries as usize;
    config.idle_timeout = Duration::from_secs(args.idle_timeout);
    config.fps = args.fps;
    config.quiet = args.quiet;
    config.drain = Duration::from_secs(args.drain_seconds);
    config.threads = args.threads.map(|n| n as usize);
    config.mode = args.mode;
    let mut seed = [0u8; 8];
    // Unpredictable refusals where the OS has randomness; the fixed seed otherwise.
    if let Some(s) = args.seed {
        config.seed = s;
    } else if getrandom::fill(&mut seed).is_ok() {
        config.seed = u64::from_ne_bytes(seed);
    }
    run_until_signal(config, maps).map_err(Failure::input)
}
