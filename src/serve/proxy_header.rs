//! The PROXY protocol (v1 text and v2 binary) that a load balancer such as HAProxy puts before
//! a connection's own bytes to say whom it is carrying. Parsing is the `ppp` crate's; this file
//! reads exactly one header off a new connection (`--proxy-protocol`), hands the bytes after it
//! on to SSH, and, without the flag, refuses a connection that starts with a header anyway
//! (someone is either misconfigured or pretending to be the balancer).

use std::io;
use std::net::SocketAddr;
use std::pin::Pin;
use std::task::{Context, Poll};
use std::time::Duration;

use ppp::v1;
use ppp::v2;
use ppp::{HeaderResult, PartialResult};
use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, ReadBuf};

/// The longest header accepted: v1's 107 bytes, or v2's 16-byte preamble and addresses (and
/// TLVs HAProxy may add) up to this many.
pub const MAX_HEADER: usize = 1024;

/// How long a new connection may take to send its header.
pub const HEADER_WAIT: Duration = Duration::from_secs(5);

/// v1 headers start with this.
const V1_PREFIX: &[u8] = b"PROXY ";
/// v2 headers start with this.
const V2_SIGNATURE: &[u8] = b"\r\n\r\n\0\r\nQUIT\n";

/// What a header said.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// The client's own address, as the balancer saw it.
    Client(SocketAddr),
    /// The balancer speaking for itself (v2 LOCAL, v1 UNKNOWN: a health check): keep the TCP
    /// peer's address.
    Local,
}

/// Parses a complete header at the start of `bytes`: what it says and its length; `Ok(None)`
/// when more bytes are needed.
///
/// # Errors
/// A message saying what is wrong with the header.
pub fn parse(bytes: &[u8]) -> Result<Option<(Source, usize)>, String> {
    if !could_be_header(bytes) {
        return Err("the connection did not start with a PROXY protocol header".into());
    }
    // The first byte tells the versions apart: `P` or `\r`.
    let parsed: HeaderResult = if bytes.first() == Some(&b'P') {
        v1::Header::try_from(bytes).into()
    } else {
        v2::Header::try_from(bytes).into()
    };
    if parsed.is_incomplete() {
        return if bytes.len() >= MAX_HEADER {
            Err(format!("PROXY header longer than {MAX_HEADER} bytes"))
        } else {
            Ok(None)
        };
    }
    match parsed {
        HeaderResult::V1(Ok(h)) => {
            let src = match h.addresses {
                v1::Addresses::Tcp4(a) => {
                    Source::Client(SocketAddr::from((a.source_address, a.source_port)))
                }
                v1::Addresses::Tcp6(a) => {
                    Source::Client(SocketAddr::from((a.source_address, a.source_port)))
                }
                v1::Addresses::Unknown => Source::Local,
            };
            Ok(Some((src, h.header.len())))
        }
        HeaderResult::V2(Ok(h)) => {
            let src = match (h.command, h.addresses) {
                (v2::Command::Local, _) => Source::Local,
                (v2::Command::Proxy, v2::Addresses::IPv4(a)) => {
                    Source::Client(SocketAddr::from((a.source_address, a.source_port)))
                }
                (v2::Command::Proxy, v2::Addresses::IPv6(a)) => {
                    Source::Client(SocketAddr::from((a.source_address, a.source_port)))
                }
                (v2::Command::Proxy, _) => {
                    return Err("PROXY v2 header for a protocol other than TCP/IP".into())
                }
            };
            Ok(Some((src, h.len())))
        }
        HeaderResult::V1(Err(e)) => Err(format!("bad PROXY v1 header: {e}")),
        HeaderResult::V2(Err(e)) => Err(format!("bad PROXY v2 header: {e}")),
    }
}

/// Whether `bytes` begin (as far as they go) like a v1 or v2 header.
fn could_be_header(bytes: &[u8]) -> bool {
    let n = bytes.len();
    V1_PREFIX.starts_with(&bytes[..n.min(V1_PREFIX.len())])
        || V2_SIGNATURE.starts_with(&bytes[..n.min(V2_SIGNATURE.len())])
}

/// Whether `bytes` (at least what has arrived) begin with a whole header's opening.
fn opens_header(bytes: &[u8]) -> bool {
    bytes.starts_with(V1_PREFIX) || bytes.starts_with(V2_SIGNATURE)
}

/// Reads one header off `stream`: what it says, and the bytes read past it (the client's
/// first SSH bytes, to be read again by SSH).
///
/// # Errors
/// A missing, malformed or overlong header, or the connection closing first.
pub async fn read_header<S: AsyncRead + Unpin>(
    stream: &mut S,
) -> Result<(Source, Vec<u8>), String> {
    let mut buf = Vec::with_capacity(256);
    let mut chunk = [0u8; 256];
    loop {
        let n = stream
            .read(&mut chunk)
            .await
            .map_err(|e| format!("reading the PROXY header: {e}"))?;
        if n == 0 {
            return Err("closed before a whole PROXY header arrived".into());
        }
        buf.extend_from_slice(&chunk[..n]);
        if let Some((src, len)) = parse(&buf)? {
            return Ok((src, buf.split_off(len)));
        }
    }
}

/// A connection's stream as SSH reads it: the bytes read past a PROXY header first, then the
/// socket. Without `--proxy-protocol` it also watches the first bytes and fails the read when
/// they open a PROXY header.
pub struct Inbound<S> {
    inner: S,
    head: Vec<u8>,
    at: usize,
    /// The first bytes seen, while they could still open a header (unguarded: `None`).
    guard: Option<Vec<u8>>,
}

impl<S> Inbound<S> {
    /// A stream behind a header already read: `head` is what was read past it.
    #[must_use]
    pub fn after_header(inner: S, head: Vec<u8>) -> Self {
        Self {
            inner,
            head,
            at: 0,
            guard: None,
        }
    }

    /// A stream that must not start with a header.
    #[must_use]
    pub fn refusing_headers(inner: S) -> Self {
        Self {
            inner,
            head: Vec::new(),
            at: 0,
            guard: Some(Vec::new()),
        }
    }
}

impl<S: AsyncRead + Unpin> AsyncRead for Inbound<S> {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        if self.at < self.head.len() {
            let n = (self.head.len() - self.at).min(buf.remaining());
            let from = self.at;
            buf.put_slice(&self.head[from..from + n]);
            self.at += n;
            return Poll::Ready(Ok(()));
        }
        let before = buf.filled().len();
        let r = Pin::new(&mut self.inner).poll_read(cx, buf);
        if let (Poll::Ready(Ok(())), Some(seen)) = (&r, self.guard.as_mut()) {
            let new = &buf.filled()[before..];
            let room = V2_SIGNATURE.len().saturating_sub(seen.len());
            seen.extend_from_slice(&new[..new.len().min(room)]);
            if opens_header(seen) {
                super::ops::metrics::refused(super::ops::metrics::Reason::Proxy);
                return Poll::Ready(Err(io::Error::new(
                    io::ErrorKind::InvalidData,
                    "a PROXY protocol header, but --proxy-protocol is off",
                )));
            }
            if !could_be_header(seen) || seen.len() >= V2_SIGNATURE.len() || new.is_empty() {
                self.guard = None;
            }
        }
        r
    }
}

impl<S: AsyncWrite + Unpin> AsyncWrite for Inbound<S> {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        Pin::new(&mut self.inner).poll_write(cx, buf)
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.inner).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.inner).poll_shutdown(cx)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn v2(command: u8, family: u8, addr: &[u8]) -> Vec<u8> {
        let mut b = V2_SIGNATURE.to_vec();
        b.push(0x20 | command);
        b.push(family);
        b.extend_from_slice(&(addr.len() as u16).to_be_bytes());
        b.extend_from_slice(addr);
        b
    }

    #[test]
    fn v1_and_v2_name_the_client() {
        let h = b"PROXY TCP4 192.0.2.7 127.0.0.1 50123 2222\r\nSSH-2.0-x\r\n";
        let (src, len) = parse(h).unwrap().unwrap();
        assert_eq!(src, Source::Client("192.0.2.7:50123".parse().unwrap()));
        assert_eq!(&h[len..], b"SSH-2.0-x\r\n");
        let h6 = b"PROXY TCP6 2001:db8::1 ::1 4000 22\r\n";
        let (src, _) = parse(h6).unwrap().unwrap();
        assert_eq!(src, Source::Client("[2001:db8::1]:4000".parse().unwrap()));
        assert_eq!(
            parse(b"PROXY UNKNOWN\r\n").unwrap().unwrap().0,
            Source::Local
        );
        // v2, TCP over IPv4: 198.51.100.9:4242 -> 127.0.0.1:2222.
        let mut b = v2(
            1,
            0x11,
            &[198, 51, 100, 9, 127, 0, 0, 1, 0x10, 0x92, 0x08, 0xae],
        );
        b.extend_from_slice(b"SSH-");
        let (src, len) = parse(&b).unwrap().unwrap();
        assert_eq!(src, Source::Client("198.51.100.9:4242".parse().unwrap()));
        assert_eq!(&b[len..], b"SSH-");
        assert_eq!(parse(&v2(0, 0, &[])).unwrap().unwrap().0, Source::Local);
    }

    #[test]
    fn partial_headers_wait_and_bad_ones_are_refused() {
        assert_eq!(parse(b"PROX").unwrap(), None);
        assert_eq!(parse(b"PROXY TCP4 1.2.3.4").unwrap(), None);
        assert_eq!(parse(&V2_SIGNATURE[..5]).unwrap(), None);
        assert!(parse(b"SSH-2.0-OpenSSH\r\n")
            .unwrap_err()
            .contains("did not start"));
        assert!(parse(b"PROXY TCP4 1.2.3 5.6.7.8 1 2\r\n")
            .unwrap_err()
            .contains("bad PROXY v1 header"));
        let bad_version = {
            let mut b = v2(1, 0x11, &[0; 12]);
            b[12] = 0x30 | 1;
            b
        };
        assert!(parse(&bad_version).unwrap_err().contains("bad PROXY v2"));
        assert!(parse(&[b"PROXY TCP4 ".as_slice(), &[b'1'; 2000]].concat()).is_err());
    }

    #[tokio::test]
    async fn the_bytes_after_the_header_are_read_again_and_a_stray_header_fails_the_read() {
        let (mut a, b) = tokio::io::duplex(256);
        tokio::io::AsyncWriteExt::write_all(
            &mut a,
            b"PROXY TCP4 10.0.0.1 10.0.0.2 5 6\r\nSSH-2.0-c\r\n",
        )
        .await
        .unwrap();
        let mut b = b;
        let (src, head) = read_header(&mut b).await.unwrap();
        assert_eq!(src, Source::Client("10.0.0.1:5".parse().unwrap()));
        let mut s = Inbound::after_header(b, head);
        let mut got = [0u8; 11];
        s.read_exact(&mut got).await.unwrap();
        assert_eq!(&got, b"SSH-2.0-c\r\n");

        let (mut a, b) = tokio::io::duplex(256);
        tokio::io::AsyncWriteExt::write_all(&mut a, b"PROXY TCP4 10.0.0.1 10.0.0.2 5 6\r\n")
            .await
            .unwrap();
        let mut s = Inbound::refusing_headers(b);
        let mut buf = [0u8; 64];
        let e = s.read(&mut buf).await.unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::InvalidData);

        let (mut a, b) = tokio::io::duplex(256);
        tokio::io::AsyncWriteExt::write_all(&mut a, b"SSH-2.0-c\r\n")
            .await
            .unwrap();
        let mut s = Inbound::refusing_headers(b);
        let n = s.read(&mut buf).await.unwrap();
        assert_eq!(&buf[..n], b"SSH-2.0-c\r\n");
    }

    proptest! {
        #[test]
        fn any_bytes_parse_without_panicking_and_lengths_stay_inside(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
            if let Ok(Some((_, len))) = parse(&bytes) {
                prop_assert!(len <= bytes.len());
            }
        }

        #[test]
        fn every_v1_tcp4_header_round_trips(a in any::<[u8; 4]>(), p in 1u16.., tail in proptest::collection::vec(any::<u8>(), 0..20)) {
            let text = format!("PROXY TCP4 {}.{}.{}.{} 127.0.0.1 {p} 2222\r\n", a[0], a[1], a[2], a[3]);
            let bytes = [text.as_bytes(), &tail].concat();
            let (src, len) = parse(&bytes).unwrap().unwrap();
            prop_assert_eq!(src, Source::Client(SocketAddr::from((a, p))));
            prop_assert_eq!(len, text.len());
        }
    }
}
