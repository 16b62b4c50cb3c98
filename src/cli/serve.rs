//! `halfcast serve`: the SSH server's flags, turned into its configuration.

use std::path::PathBuf;

use clap::Args;

use super::options::MapArgs;
use super::{load_world, Failure};

#[derive(Args, Debug)]
pub(crate) struct ServeArgs {
    #[command(flatten)]
    pub(crate) map: MapArgs,
    /// Address to listen on (port 0 picks a free one; the log says which).
    #[arg(long, default_value = "127.0.0.1:2222")]
    pub(crate) listen: std::net::SocketAddr,
    /// Ed25519 host key: read if it exists, else generated there with mode 0600.
    #[arg(long, default_value = "halfcast_host_ed25519")]
    pub(crate) host_key: PathBuf,
    /// Require this password (default: no authentication).
    #[arg(long, conflicts_with = "authorized_keys")]
    pub(crate) password: Option<String>,
    /// Accept only the public keys in this OpenSSH authorized_keys file.
    #[arg(long)]
    pub(crate) authorized_keys: Option<PathBuf>,
    /// Most concurrent connections.
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub(crate) max_sessions: u32,
    /// Most concurrent connections from one IP address.
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub(crate) max_per_ip: u32,
    /// Close a connection after this many seconds without a keystroke.
    #[arg(long, default_value_t = 600, value_parser = clap::value_parser!(u64).range(1..=86_400))]
    pub(crate) idle_timeout: u64,
    /// Frames per second per session (slow links get fewer).
    #[arg(long, default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..=240))]
    pub(crate) fps: u32,
    /// No connect/disconnect log on stderr.
    #[arg(long)]
    pub(crate) quiet: bool,
}

pub(crate) fn serve(args: ServeArgs) -> Result<(), Failure> {
    use halfcast::serve::{auth::AuthMode, run_until_signal, ServeConfig};
    let world = load_world(&args.map)?;
    let auth = match (args.password, &args.authorized_keys) {
        (Some(p), _) if p.is_empty() => return Err(Failure::input("--password must not be empty")),
        (Some(p), _) => AuthMode::Password(p),
        (None, Some(path)) => AuthMode::from_authorized_keys(path).map_err(Failure::input)?,
        (None, None) => AuthMode::None,
    };
    let mut config = ServeConfig::local(args.listen, args.host_key);
    config.auth = auth;
    config.max_sessions = args.max_sessions as usize;
    config.max_per_ip = args.max_per_ip as usize;
    config.idle_timeout = std::time::Duration::from_secs(args.idle_timeout);
    config.fps = args.fps;
    config.quiet = args.quiet;
    run_until_signal(config, world).map_err(Failure::input)
}
