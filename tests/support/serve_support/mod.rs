//! Helpers for the `serve` integration tests and the `serve_bench` load test (which includes
//! this file with `#[path]`): an in-process server on a free loopback port, and a real russh
//! client whose output goes through a vt100 terminal model.

pub mod browser;
pub mod http;
pub mod openssh;
pub mod pg_cluster;
pub mod postgres;
pub mod web;

use std::sync::Arc;
use std::time::Duration;

use halfcast::serve::{start, RunningServer, ServeConfig};
use halfcast::ui::layout::{Panes, Toggles};
use halfcast::World;
use ratatui::layout::Rect;
use russh::client;
use russh::keys::PublicKeyOrCertificate;
use russh::{ChannelMsg, Preferred};
use tempfile::TempDir;

/// Upper bound on any wait in these tests, so a broken server fails a test instead of hanging it.
pub const PATIENCE: Duration = Duration::from_secs(20);

/// Starts a server on 127.0.0.1:0 with the default world without its game (no items,
/// creatures or exit: the session tests check the plain header and screens); `tweak` may
/// change the config.
pub async fn server(tweak: impl FnOnce(&mut ServeConfig)) -> (RunningServer, TempDir) {
    server_with(tweak, plain_default_world()).await
}

/// [`server`] serving `world`.
pub async fn server_with(
    tweak: impl FnOnce(&mut ServeConfig),
    world: World,
) -> (RunningServer, TempDir) {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut cfg = ServeConfig::local("127.0.0.1:0".parse().expect("addr"), dir.path().join("hk"));
    cfg.quiet = true;
    tweak(&mut cfg);
    let s = start(cfg, world).await.expect("server starts");
    (s, dir)
}

/// The embedded default map without its game lines (`ITEM`, `DOORLOCK`, `EXIT`, `CREATURE`).
pub fn plain_default_world() -> World {
    default_world_keeping(|_| true)
}

/// The embedded default map without its game lines, and without the other lines `keep` refuses.
pub fn default_world_keeping(keep: impl Fn(&str) -> bool) -> World {
    let text: String = halfcast::world::DEFAULT_MAP
        .lines()
        .filter(|l| {
            !["ITEM ", "DOORLOCK ", "EXIT ", "CREATURE "]
                .iter()
                .any(|w| l.starts_with(w))
                && keep(l)
        })
        .map(|l| format!("{l}\n"))
        .collect();
    let map = halfcast::map::parse_map(halfcast::world::DEFAULT_MAP_NAME, text.as_bytes())
        .expect("the default map parses without its game");
    World::load(map, &halfcast::world::TextureSource::Embedded, true)
        .expect("embedded textures")
        .0
}

pub struct Trusting;

impl client::Handler for Trusting {
    type Error = russh::Error;

    async fn check_server_key(&mut self, _: &PublicKeyOrCertificate) -> Result<bool, Self::Error> {
        Ok(true)
    }
}

/// A connected client with a pty-backed shell channel and a terminal model of its screen.
///
/// What the server sends is read off the channel at once by a task of its own and queued
/// (unbounded) for [`Client::wait`]. russh hands a channel's messages to it through a queue of
/// 100; a test that sends (keys, window changes) without reading for a while would otherwise
/// fill it, block the client's connection task, and hang its own next send for ever.
pub struct Client {
    pub handle: client::Handle<Trusting>,
    /// The writing half: keys, window changes.
    pub channel: russh::ChannelWriteHalf<client::Msg>,
    inbox: tokio::sync::mpsc::UnboundedReceiver<ChannelMsg>,
    pub screen: vt100::Parser,
    pub bytes: usize,
    pub closed: bool,
}

/// Connects without shell: authenticated handle only (for refusals and auth tests).
pub async fn connect_raw(
    addr: std::net::SocketAddr,
    compression: Option<russh::compression::Name>,
) -> Result<client::Handle<Trusting>, russh::Error> {
    let mut cfg = client::Config::default();
    if let Some(c) = compression {
        cfg.preferred = Preferred {
            compression: std::borrow::Cow::Owned(vec![c]),
            ..Preferred::default()
        };
    }
    client::connect(Arc::new(cfg), addr, Trusting).await
}

impl Client {
    /// Connects as `user` (no auth), asks for a `cols`×`rows` pty with `term`, starts the shell.
    pub async fn connect(
        addr: std::net::SocketAddr,
        user: &str,
        cols: u16,
        rows: u16,
        term: &str,
    ) -> Self {
        Self::connect_with(addr, user, cols, rows, term, None).await
    }

    /// As [`Client::connect`], offering only the given compression.
    pub async fn connect_with(
        addr: std::net::SocketAddr,
        user: &str,
        cols: u16,
        rows: u16,
        term: &str,
        compression: Option<russh::compression::Name>,
    ) -> Self {
        let handle = connect_raw(addr, compression).await.expect("connect");
        Self::start(handle, user, term, cols, rows)
            .await
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// Logs in as `user` over a connected `handle` (no auth), asks for a `cols`×`rows` pty with
    /// `term` and starts the shell; the error says which step failed.
    pub async fn start(
        handle: client::Handle<Trusting>,
        user: &str,
        term: &str,
        cols: u16,
        rows: u16,
    ) -> Result<Self, String> {
        let (handle, channel) = open_shell(handle, user, term, (cols, rows), &[]).await?;
        Ok(Self::new(handle, channel, cols, rows))
    }

    /// Wraps an open shell `channel` whose terminal is `cols`×`rows`, and starts reading it.
    pub fn new(
        handle: client::Handle<Trusting>,
        channel: russh::Channel<client::Msg>,
        cols: u16,
        rows: u16,
    ) -> Self {
        let (mut read, write) = channel.split();
        let (tx, inbox) = tokio::sync::mpsc::unbounded_channel();
        tokio::spawn(async move {
            while let Some(msg) = read.wait().await {
                if tx.send(msg).is_err() {
                    break;
                }
            }
        });
        Self {
            handle,
            channel: write,
            inbox,
            screen: vt100::Parser::new(rows, cols, 0),
            bytes: 0,
            closed: false,
        }
    }

    /// The next message from the server; `None` once the channel is closed.
    pub async fn wait(&mut self) -> Option<ChannelMsg> {
        self.inbox.recv().await
    }

    /// Reads output into the screen model until `done(screen)` holds; false on close or timeout.
    pub async fn until(&mut self, mut done: impl FnMut(&vt100::Screen) -> bool) -> bool {
        let deadline = tokio::time::Instant::now() + PATIENCE;
        loop {
            if done(self.screen.screen()) {
                return true;
            }
            if self.closed {
                return false;
            }
            match tokio::time::timeout_at(deadline, self.wait()).await {
                Err(_) => return false,
                Ok(None) => self.closed = true,
                Ok(Some(ChannelMsg::Data { data })) => {
                    self.bytes += data.len();
                    self.screen.process(&data);
                }
                Ok(Some(ChannelMsg::Close | ChannelMsg::Eof)) => self.closed = true,
                Ok(Some(_)) => {}
            }
        }
    }

    /// Reads whatever arrives for `d` (to measure or to let the server act).
    pub async fn drain_for(&mut self, d: Duration) {
        let end = tokio::time::Instant::now() + d;
        while let Ok(Some(msg)) = tokio::time::timeout_at(end, self.wait()).await {
            if let ChannelMsg::Data { data } = msg {
                self.bytes += data.len();
                self.screen.process(&data);
            }
        }
    }

    /// Sends key bytes.
    pub async fn keys(&self, bytes: &[u8]) {
        tokio::time::timeout(PATIENCE, self.channel.data(bytes))
            .await
            .expect("sending keys timed out")
            .expect("send keys");
    }

    /// Tells the server the terminal changed size, and resizes the model.
    pub async fn resize(&mut self, cols: u16, rows: u16) {
        let change = self
            .channel
            .window_change(u32::from(cols), u32::from(rows), 0, 0);
        tokio::time::timeout(PATIENCE, change)
            .await
            .expect("a window change timed out")
            .expect("window change");
        self.screen.set_size(rows, cols);
    }
}

/// Logs in as `user` over `handle` (no auth), asks for a `cols`×`rows` pty with `term` and
/// starts the shell; the error says which step failed.
async fn open_shell(
    mut handle: client::Handle<Trusting>,
    user: &str,
    term: &str,
    (cols, rows): (u16, u16),
    env: &[(&str, &str)],
) -> Result<(client::Handle<Trusting>, russh::Channel<client::Msg>), String> {
    let auth = handle
        .authenticate_none(user)
        .await
        .map_err(|e| format!("auth: {e}"))?;
    if !auth.success() {
        return Err("auth refused".into());
    }
    let channel = handle
        .channel_open_session()
        .await
        .map_err(|e| format!("session: {e}"))?;
    channel
        .request_pty(true, term, u32::from(cols), u32::from(rows), 0, 0, &[])
        .await
        .map_err(|e| format!("pty: {e}"))?;
    for (name, value) in env {
        channel
            .set_env(true, *name, *value)
            .await
            .map_err(|e| format!("env {name}: {e}"))?;
    }
    channel
        .request_shell(true)
        .await
        .map_err(|e| format!("shell: {e}"))?;
    Ok((handle, channel))
}

/// The text of screen row `r`.
pub fn row_text(s: &vt100::Screen, r: u16) -> String {
    let (_, cols) = s.size();
    s.contents_between(r, 0, r, cols)
}

/// Whether the bottom row (the TUI's status line) contains `needle`.
pub fn status_has(s: &vt100::Screen, needle: &str) -> bool {
    let (rows, _) = s.size();
    row_text(s, rows - 1).contains(needle)
}

/// Whether the top row (the server's header: who, who else, colour level) contains `needle`.
pub fn header_has(s: &vt100::Screen, needle: &str) -> bool {
    row_text(s, 0).contains(needle)
}

/// Where the 3D view is on a `cols` × `rows` client with the default panes.
pub fn view_rect(cols: u16, rows: u16) -> Rect {
    // The server's screen is a one-row header over the game panes.
    match Panes::compute(
        Rect::new(0, 1, cols, rows.saturating_sub(1)),
        Toggles::default(),
    ) {
        Panes::Game { view, .. } => view,
        Panes::TooSmall(_) => Rect::default(),
    }
}

/// Counts the cells of `view` drawn as half-blocks (or one-colour cells) in 24-bit colour.
pub fn half_block_cells(s: &vt100::Screen, view: Rect) -> usize {
    let mut n = 0;
    for r in view.top()..view.bottom() {
        for c in view.left()..view.right() {
            if let Some(cell) = s.cell(r, c) {
                // The encoder draws a cell as ▀ or ▄ (two colours), or as a space / █ (one).
                let rgb = |c: vt100::Color| matches!(c, vt100::Color::Rgb(..));
                let drawn = match cell.contents().as_str() {
                    "▀" | "▄" => rgb(cell.fgcolor()) && rgb(cell.bgcolor()),
                    "█" => rgb(cell.fgcolor()),
                    "" | " " => rgb(cell.bgcolor()),
                    _ => false,
                };
                if drawn {
                    n += 1;
                }
            }
        }
    }
    n
}

/// Whether the whole view of a `cols` × `rows` client is drawn in 24-bit half-blocks.
pub fn full_view(s: &vt100::Screen, cols: u16, rows: u16) -> bool {
    let v = view_rect(cols, rows);
    v.area() > 0 && half_block_cells(s, v) == usize::from(v.width) * usize::from(v.height)
}

/// All 24-bit colours on the screen (fg and bg).
pub fn colours(s: &vt100::Screen) -> Vec<(u8, u8, u8)> {
    let (rows, cols) = s.size();
    let mut v = Vec::new();
    for r in 0..rows {
        for c in 0..cols {
            if let Some(cell) = s.cell(r, c) {
                for col in [cell.fgcolor(), cell.bgcolor()] {
                    if let vt100::Color::Rgb(r, g, b) = col {
                        v.push((r, g, b));
                    }
                }
            }
        }
    }
    v
}

/// Opens a pty shell as `user` over a stream that counts wire bytes received (after SSH
/// compression and encryption), offering only `compression`, and sends `env` first (as
/// `ssh -o SetEnv` does); the load test reads the channel itself.
#[allow(dead_code)] // examples/serve_bench's load test; the serve tests read through `Client`
pub async fn open_counting(
    addr: std::net::SocketAddr,
    user: &str,
    (cols, rows): (u16, u16),
    term: &str,
    env: &[(&str, &str)],
    compression: russh::compression::Name,
) -> (
    client::Handle<Trusting>,
    russh::Channel<client::Msg>,
    Arc<std::sync::atomic::AtomicU64>,
) {
    let (handle, read) = connect_counting_raw(addr, compression).await;
    let (handle, channel) = open_shell(handle, user, term, (cols, rows), env)
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    (handle, channel, read)
}

/// Like [`Client::connect_with`], over a stream that counts wire bytes received.
pub async fn connect_counting(
    addr: std::net::SocketAddr,
    user: &str,
    cols: u16,
    rows: u16,
    term: &str,
    compression: russh::compression::Name,
) -> (Client, Arc<std::sync::atomic::AtomicU64>) {
    let (handle, read) = connect_counting_raw(addr, compression).await;
    let c = Client::start(handle, user, term, cols, rows)
        .await
        .unwrap_or_else(|e| panic!("{e}"));
    (c, read)
}

/// An SSH connection (not logged in) over a stream that counts wire bytes received.
async fn connect_counting_raw(
    addr: std::net::SocketAddr,
    compression: russh::compression::Name,
) -> (client::Handle<Trusting>, Arc<std::sync::atomic::AtomicU64>) {
    let stream = Tap::new(tokio::net::TcpStream::connect(addr).await.expect("tcp"));
    let read = Arc::clone(&stream.read);
    let cfg = client::Config {
        preferred: Preferred {
            compression: std::borrow::Cow::Owned(vec![compression]),
            ..Preferred::default()
        },
        ..client::Config::default()
    };
    let handle = client::connect_stream(Arc::new(cfg), stream, Trusting)
        .await
        .expect("connect");
    (handle, read)
}

/// Tries once to get a playing session as `user` (no auth, `cols`×`rows` xterm pty, shell);
/// the error says which step failed (refused connections are normal under the abuse tests).
pub async fn try_connect(
    addr: std::net::SocketAddr,
    user: &str,
    cols: u16,
    rows: u16,
) -> Result<Client, String> {
    let handle = connect_raw(addr, None)
        .await
        .map_err(|e| format!("connect: {e}"))?;
    Client::start(handle, user, "xterm", cols, rows).await
}

/// Opens a TCP connection to `addr` from the loopback address `from` (any of 127.0.0.0/8), so
/// one test can play several source addresses.
pub async fn tcp_from(
    from: std::net::Ipv4Addr,
    addr: std::net::SocketAddr,
) -> std::io::Result<tokio::net::TcpStream> {
    let sock = tokio::net::TcpSocket::new_v4()?;
    sock.bind(std::net::SocketAddr::new(from.into(), 0))?;
    sock.connect(addr).await
}

/// Whether the server has closed `s` (a read sees end of file or an error) within `d`; any
/// bytes it sent first (its version line, a refusal) are appended to `got`.
pub async fn closed_within(s: &mut tokio::net::TcpStream, d: Duration, got: &mut Vec<u8>) -> bool {
    use tokio::io::AsyncReadExt;
    let end = tokio::time::Instant::now() + d;
    let mut buf = [0u8; 4096];
    loop {
        match tokio::time::timeout_at(end, s.read(&mut buf)).await {
            Err(_) => return false,
            Ok(Ok(0) | Err(_)) => return true,
            Ok(Ok(n)) => got.extend_from_slice(&buf[..n]),
        }
    }
}

/// What a [`Tap`] stream does now.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TapMode {
    /// Passes everything through.
    Open,
    /// Stops reading (the client's TCP window fills up), still writes.
    Stalled,
    /// Fails every read and write: the client vanished mid-frame (its socket is dropped).
    Cut,
}

/// A client-side TCP stream a test can stall or cut, to play a client that stops reading or
/// dies mid-frame; it counts the bytes read from the wire (after SSH compression/encryption).
pub struct Tap {
    inner: tokio::net::TcpStream,
    ctl: Arc<std::sync::Mutex<(TapMode, Option<std::task::Waker>)>>,
    pub read: Arc<std::sync::atomic::AtomicU64>,
}

/// The test's end of a [`Tap`].
#[derive(Clone)]
pub struct TapControl(Arc<std::sync::Mutex<(TapMode, Option<std::task::Waker>)>>);

impl TapControl {
    /// Switches the stream's mode (waking a stalled read).
    pub fn set(&self, mode: TapMode) {
        let mut g = self.0.lock().expect("tap");
        g.0 = mode;
        if let Some(w) = g.1.take() {
            w.wake();
        }
    }
}

impl Tap {
    /// An open tap over `inner`.
    fn new(inner: tokio::net::TcpStream) -> Self {
        Self {
            inner,
            ctl: Arc::new(std::sync::Mutex::new((TapMode::Open, None))),
            read: Arc::default(),
        }
    }

    fn mode(&self) -> TapMode {
        self.ctl.lock().expect("tap").0
    }

    fn cut_error() -> std::io::Error {
        std::io::Error::new(std::io::ErrorKind::ConnectionReset, "cut by the test")
    }
}

impl tokio::io::AsyncRead for Tap {
    fn poll_read(
        mut self: std::pin::Pin<&mut Self>,
        cx: &mut std::task::Context<'_>,
        buf: &mut tokio::io::ReadBuf<'_>,
    ) -> std::task::Poll<std::io::Result<()>> {
        {
            let mut g = self.ctl.lock().expect("tap");
            match g.0 {
                TapMode::Cut => return std::task::Poll::Ready(Err(Self::cut_error())),
                TapMode::Stalled => {
                    g.1 = Some(cx.waker().clone());
                    return std::task::Poll::Pending;
                }
                TapMode::Open => {}
            }
        }
        let before = buf.filled().len();
        let r = std::pin::Pin::new(&mut self.inner).poll_read(cx, buf);
        let n = (buf.filled().len() - before) as u64;
        self.read.fetch_add(n, std::sync::atomic::Ordering::Relaxed);
        r
    }
}

impl tokio::io::AsyncWrite for Tap {
    fn poll_write(
        mut self: std::pin::Pin<&mut Self>,
        cx: &mut std::task::Context<'_>,
        buf: &[u8],
    ) -> std::task::Poll<std::io::Result<usize>> {
        if self.mode() == TapMode::Cut {
            return std::task::Poll::Ready(Err(Self::cut_error()));
        }
        std::pin::Pin::new(&mut self.inner).poll_write(cx, buf)
    }

    fn poll_flush(
        mut self: std::pin::Pin<&mut Self>,
        cx: &mut std::task::Context<'_>,
    ) -> std::task::Poll<std::io::Result<()>> {
        std::pin::Pin::new(&mut self.inner).poll_flush(cx)
    }

    fn poll_shutdown(
        mut self: std::pin::Pin<&mut Self>,
        cx: &mut std::task::Context<'_>,
    ) -> std::task::Poll<std::io::Result<()>> {
        std::pin::Pin::new(&mut self.inner).poll_shutdown(cx)
    }
}

/// Like [`Client::connect`] (no auth, `cols`×`rows` pty with `term`, shell), over a [`Tap`]
/// stream: the way to play a client that stops reading (its messages are otherwise read off
/// the channel as they come).
pub async fn connect_tapped(
    addr: std::net::SocketAddr,
    user: &str,
    term: &str,
    cols: u16,
    rows: u16,
) -> Result<(Client, TapControl), String> {
    let stream = Tap::new(
        tokio::net::TcpStream::connect(addr)
            .await
            .map_err(|e| format!("tcp: {e}"))?,
    );
    let ctl = Arc::clone(&stream.ctl);
    let handle = client::connect_stream(Arc::new(client::Config::default()), stream, Trusting)
        .await
        .map_err(|e| format!("connect: {e}"))?;
    let c = Client::start(handle, user, term, cols, rows).await?;
    Ok((c, TapControl(ctl)))
}

/// This process's open file descriptors, threads and resident memory (KiB), where /proc tells.
pub fn process_usage() -> Option<(usize, usize, u64)> {
    let fds = std::fs::read_dir("/proc/self/fd").ok()?.count();
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let field = |name: &str| -> Option<u64> {
        status
            .lines()
            .find(|l| l.starts_with(name))?
            .split_whitespace()
            .nth(1)?
            .parse()
            .ok()
    };
    Some((
        fds,
        usize::try_from(field("Threads:")?).ok()?,
        field("VmRSS:")?,
    ))
}

/// Whether this machine routes all of 127.0.0.0/8 to loopback (Linux does; macOS only has
/// 127.0.0.1 unless aliases are added). Tests playing several source addresses skip otherwise.
pub fn many_loopback_addresses() -> bool {
    let ok = std::net::TcpListener::bind("127.0.0.2:0").is_ok();
    if !ok {
        eprintln!(
            "skip: 127.0.0.2 is not a loopback address here (several source addresses needed)"
        );
    }
    ok
}

/// Waits until the server counts `want` (logging in, playing) connections.
pub async fn live_becomes(srv: &RunningServer, want: (usize, usize)) -> bool {
    let deadline = tokio::time::Instant::now() + PATIENCE;
    while tokio::time::Instant::now() < deadline {
        if srv.live() == want {
            return true;
        }
        tokio::time::sleep(std::time::Duration::from_millis(10)).await;
    }
    false
}
