//! What an operator sets for the browser edge (`--web`, `--web-origin`, `--web-trusted-proxy`).

use std::net::{IpAddr, SocketAddr};

/// The browser listener's settings.
#[derive(Debug, Clone)]
pub struct WebOptions {
    /// Where the page and its WebSocket are served; port 0 picks a free port (tests).
    pub listen: SocketAddr,
    /// Origins (`https://example.org`) whose pages may open the WebSocket besides the page this
    /// server serves itself.
    pub origins: Vec<String>,
    /// Reverse proxies whose `X-Forwarded-For`/`Forwarded` headers name the player's address.
    pub trusted_proxies: Vec<IpAddr>,
    /// When a page's frames are compressed.
    pub compress: Compress,
}

/// When a page's frames go compressed (`--web-compress`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Compress {
    /// While the page's link holds frames back ([`super::deflate`]).
    #[default]
    Auto,
    /// Every frame (a link known to be slow; measurements).
    Always,
    /// None (the CPU matters more than the link; measurements).
    Never,
}

impl WebOptions {
    /// Serves on `listen`, trusting no other origin and no proxy.
    #[must_use]
    pub fn new(listen: SocketAddr) -> Self {
        Self {
            listen,
            origins: Vec::new(),
            trusted_proxies: Vec::new(),
            compress: Compress::Auto,
        }
    }
}
