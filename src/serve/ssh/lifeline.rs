//! One connection's life from TCP accept to close: the kill switch that ends it whatever state
//! the SSH layer is in, and the flag saying it reached a playing session (which stops the login
//! grace clock).
//!
//! russh runs each connection in a task of its own that only ends when its stream does, so the
//! server wraps the socket in [`Killable`]: once [`Lifeline::kill`] is called every read and
//! write on it fails, the SSH task ends, and the socket and its slot are freed — even for a
//! client that stopped reading, to whom no goodbye can be delivered.

use std::future::Future;
use std::io;
use std::net::SocketAddr;
use std::pin::Pin;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};
use std::task::{Context, Poll};

use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::sync::watch;

use crate::play::pacing::LinkFigures;

/// Shared by the accept task, the SSH handler and the session of one connection.
#[derive(Debug)]
pub struct Lifeline {
    kill: watch::Sender<bool>,
    playing: watch::Sender<bool>,
    wire: Arc<Wire>,
    /// The TCP socket's (local, peer) addresses: the session asks the kernel about it by them.
    tcp: OnceLock<(SocketAddr, SocketAddr)>,
    /// The session's link figures as it ended, for the disconnect log line.
    link: Mutex<Option<LinkFigures>>,
}

/// Bytes read from and written to one connection's socket.
#[derive(Debug, Default)]
struct Wire {
    read: AtomicU64,
    written: AtomicU64,
}

impl Default for Lifeline {
    fn default() -> Self {
        Self {
            kill: watch::channel(false).0,
            playing: watch::channel(false).0,
            wire: Arc::default(),
            tcp: OnceLock::new(),
            link: Mutex::new(None),
        }
    }
}

impl Lifeline {
    /// Ends the connection: every later read or write on its [`Killable`] stream fails.
    pub fn kill(&self) {
        self.kill.send_replace(true);
    }

    /// Whether [`Lifeline::kill`] was called.
    #[must_use]
    pub fn killed(&self) -> bool {
        *self.kill.borrow()
    }

    /// Marks the connection as playing (or watching): its login is over.
    pub fn set_playing(&self) {
        self.playing.send_replace(true);
    }

    /// Watches the playing flag.
    #[must_use]
    pub fn playing(&self) -> watch::Receiver<bool> {
        self.playing.subscribe()
    }

    /// Bytes (read, written) on the socket so far.
    #[must_use]
    pub fn wire_bytes(&self) -> (u64, u64) {
        (
            self.wire.read.load(Ordering::Relaxed),
            self.wire.written.load(Ordering::Relaxed),
        )
    }

    /// Bytes written to the socket so far (a cheap read, once per frame).
    #[must_use]
    pub fn written(&self) -> u64 {
        self.wire.written.load(Ordering::Relaxed)
    }

    /// Records the TCP socket's (local, peer) addresses; the first call wins.
    pub fn set_tcp(&self, local: SocketAddr, peer: SocketAddr) {
        let _ = self.tcp.set((local, peer));
    }

    /// The TCP socket's (local, peer) addresses, when known.
    #[must_use]
    pub fn tcp(&self) -> Option<(SocketAddr, SocketAddr)> {
        self.tcp.get().copied()
    }

    /// Keeps the session's link figures for the disconnect line.
    pub fn set_link(&self, figures: LinkFigures) {
        if let Ok(mut l) = self.link.lock() {
            *l = Some(figures);
        }
    }

    /// The session's link figures, once it has ended (none for a connection that never played).
    #[must_use]
    pub fn link(&self) -> Option<LinkFigures> {
        self.link.lock().ok().and_then(|l| *l)
    }

    /// Wraps `inner` so that [`Lifeline::kill`] cuts it (and its bytes are counted).
    #[must_use]
    pub fn wrap<S>(&self, inner: S) -> Killable<S> {
        let mut rx = self.kill.subscribe();
        Killable {
            wire: Arc::clone(&self.wire),
            wire_metric: crate::serve::ops::metrics::wire_bytes(),
            inner,
            kill: Box::pin(async move {
                // Err: the lifeline is gone, and nobody is left to keep the connection.
                let _ = rx.wait_for(|k| *k).await;
            }),
            dead: false,
        }
    }
}

/// A stream that fails every read and write once its [`Lifeline`] is killed.
pub struct Killable<S> {
    inner: S,
    wire: Arc<Wire>,
    wire_metric: metrics::Counter,
    kill: Pin<Box<dyn Future<Output = ()> + Send>>,
    dead: bool,
}

impl<S> Killable<S> {
    fn cut(&mut self, cx: &mut Context<'_>) -> Option<io::Error> {
        if !self.dead && self.kill.as_mut().poll(cx).is_ready() {
            self.dead = true;
        }
        self.dead
            .then(|| io::Error::new(io::ErrorKind::ConnectionAborted, "closed by the server"))
    }
}

impl<S: AsyncRead + Unpin> AsyncRead for Killable<S> {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        if let Some(e) = self.cut(cx) {
            return Poll::Ready(Err(e));
        }
        let before = buf.filled().len();
        let r = Pin::new(&mut self.inner).poll_read(cx, buf);
        let n = buf.filled().len().saturating_sub(before) as u64;
        self.wire.read.fetch_add(n, Ordering::Relaxed);
        r
    }
}

impl<S: AsyncWrite + Unpin> AsyncWrite for Killable<S> {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        if let Some(e) = self.cut(cx) {
            return Poll::Ready(Err(e));
        }
        let r = Pin::new(&mut self.inner).poll_write(cx, buf);
        if let Poll::Ready(Ok(n)) = r {
            self.wire.written.fetch_add(n as u64, Ordering::Relaxed);
            self.wire_metric.increment(n as u64);
        }
        r
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        if let Some(e) = self.cut(cx) {
            return Poll::Ready(Err(e));
        }
        Pin::new(&mut self.inner).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        if let Some(e) = self.cut(cx) {
            return Poll::Ready(Err(e));
        }
        Pin::new(&mut self.inner).poll_shutdown(cx)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tokio::io::{AsyncReadExt, AsyncWriteExt};

    #[tokio::test]
    async fn a_killed_stream_fails_pending_and_later_reads_and_writes() {
        let life = Lifeline::default();
        let (a, mut b) = tokio::io::duplex(64);
        let mut s = life.wrap(a);
        b.write_all(b"hi").await.expect("write");
        let mut buf = [0u8; 2];
        s.read_exact(&mut buf).await.expect("read before the kill");
        assert_eq!(&buf, b"hi");
        let reader = tokio::spawn(async move {
            let mut one = [0u8; 1];
            let r = s.read(&mut one).await;
            (r.is_err(), s)
        });
        tokio::time::sleep(std::time::Duration::from_millis(20)).await;
        assert!(!life.killed());
        life.kill();
        let (failed, mut s) = reader.await.expect("join");
        assert!(failed, "a read waiting when the kill came fails");
        assert!(s.write_all(b"x").await.is_err(), "so do later writes");
    }

    #[test]
    fn playing_flag_is_watched() {
        let life = Lifeline::default();
        let rx = life.playing();
        assert!(!*rx.borrow());
        life.set_playing();
        assert!(*rx.borrow());
    }
}
