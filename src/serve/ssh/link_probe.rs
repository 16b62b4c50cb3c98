//! What the kernel knows about one client's TCP connection: bytes written but not yet
//! acknowledged, the smoothed round trip and the delivery rate. A session reads it before each
//! frame, so it sends a new frame only once the last has (nearly) arrived, and steps its colour
//! level to what the link carries ([`crate::play::pacing`]).
//!
//! Read through the sock_diag netlink interface (what `ss -ti` uses), one exact-socket query per
//! sample; no `unsafe`, no extra privileges. On other systems, or where the query fails (a
//! sandbox without netlink), [`LinkProbe::open`] gives `None` and the session paces on the
//! socket's own writes alone.

use std::net::SocketAddr;
use std::time::Duration;

pub use crate::play::link::LinkSample;

#[cfg(target_os = "linux")]
pub use linux::LinkProbe;

#[cfg(not(target_os = "linux"))]
pub use other::LinkProbe;

#[cfg(target_os = "linux")]
mod linux {
    use super::{Duration, LinkSample, SocketAddr};
    use netlink_packet_core::{NetlinkHeader, NetlinkMessage, NetlinkPayload, NLM_F_REQUEST};
    use netlink_packet_sock_diag::constants::{AF_INET, AF_INET6, IPPROTO_TCP};
    use netlink_packet_sock_diag::inet::{
        nlas::Nla, ExtensionFlags, InetRequest, SocketId, StateFlags,
    };
    use netlink_packet_sock_diag::SockDiagMessage;
    use netlink_sys::{protocols::NETLINK_SOCK_DIAG, Socket, SocketAddr as NlAddr};

    /// A netlink socket that asks about one TCP connection (ours: local and peer address).
    pub struct LinkProbe {
        socket: Socket,
        request: Vec<u8>,
        reply: Vec<u8>,
    }

    impl std::fmt::Debug for LinkProbe {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str("LinkProbe")
        }
    }

    impl LinkProbe {
        /// A probe for the connection from `local` to `peer` (the server's accepted socket),
        /// checked with a first sample; `None` where sock_diag cannot answer.
        #[must_use]
        pub fn open(local: SocketAddr, peer: SocketAddr) -> Option<Self> {
            let mut socket = Socket::new(NETLINK_SOCK_DIAG).ok()?;
            socket.bind_auto().ok()?;
            socket.connect(&NlAddr::new(0, 0)).ok()?;
            let family = if local.is_ipv4() { AF_INET } else { AF_INET6 };
            let mut header = NetlinkHeader::default();
            header.flags = NLM_F_REQUEST;
            let mut packet = NetlinkMessage::new(
                header,
                SockDiagMessage::InetRequest(InetRequest {
                    family,
                    protocol: IPPROTO_TCP,
                    extensions: ExtensionFlags::INFO,
                    states: StateFlags::all(),
                    socket_id: SocketId {
                        source_port: local.port(),
                        destination_port: peer.port(),
                        source_address: local.ip(),
                        destination_address: peer.ip(),
                        interface_id: 0,
                        // All ones: no cookie, match by addresses and ports.
                        cookie: [0xff; 8],
                    },
                })
                .into(),
            );
            packet.finalize();
            let mut request = vec![0; packet.buffer_len()];
            packet.serialize(&mut request);
            let mut probe = Self {
                socket,
                request,
                reply: Vec::with_capacity(2048),
            };
            probe.sample().map(|_| probe)
        }

        /// The connection's send side now; `None` when the kernel no longer knows it (closed).
        pub fn sample(&mut self) -> Option<LinkSample> {
            self.socket.send(&self.request, 0).ok()?;
            self.reply.clear();
            self.socket.recv(&mut self.reply, 0).ok()?;
            let msg = NetlinkMessage::<SockDiagMessage>::deserialize(&self.reply).ok()?;
            let NetlinkPayload::InnerMessage(SockDiagMessage::InetResponse(resp)) = msg.payload
            else {
                return None;
            };
            let mut sample = LinkSample {
                outstanding: u64::from(resp.header.send_queue),
                ..LinkSample::default()
            };
            for nla in &resp.nlas {
                if let Nla::TcpInfo(info) = nla {
                    sample.unsent = u64::from(info.notsent_bytes);
                    sample.rtt = Duration::from_micros(u64::from(info.rtt));
                    sample.delivery_rate = info.delivery_rate;
                    sample.app_limited = info.delivery_rate_app_limited & 1 != 0;
                    sample.acked = info.bytes_acked;
                    sample.min_rtt = Duration::from_micros(u64::from(info.min_rtt));
                }
            }
            Some(sample)
        }
    }
}

#[cfg(not(target_os = "linux"))]
mod other {
    use super::{LinkSample, SocketAddr};

    /// No probe where sock_diag does not exist: sessions pace on the socket's writes.
    #[derive(Debug)]
    pub struct LinkProbe;

    impl LinkProbe {
        /// Always `None` here.
        #[must_use]
        pub fn open(_local: SocketAddr, _peer: SocketAddr) -> Option<Self> {
            None
        }

        /// Never called: no probe opens.
        pub fn sample(&mut self) -> Option<LinkSample> {
            None
        }
    }
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;
    use std::io::{Read, Write};
    use std::net::{TcpListener, TcpStream};

    #[test]
    fn bytes_the_client_has_not_taken_are_outstanding_until_it_reads() {
        let listener = TcpListener::bind("127.0.0.1:0").expect("bind");
        let mut client = TcpStream::connect(listener.local_addr().expect("addr")).expect("dial");
        let (mut server, peer) = listener.accept().expect("accept");
        let Some(mut probe) = LinkProbe::open(server.local_addr().expect("local"), peer) else {
            println!("SKIPPED: sock_diag netlink is not available here");
            return;
        };
        let idle = probe.sample().expect("sample");
        assert_eq!(idle.outstanding, 0);
        // The client reads nothing: once its receive window is full, what the server writes
        // waits in the server's socket, unsent.
        server.set_nonblocking(true).expect("nonblocking");
        let chunk = [7u8; 65_536];
        let mut written = 0u64;
        while let Ok(n) = server.write(&chunk) {
            written += n as u64;
        }
        let full = probe.sample().expect("sample");
        assert!(full.outstanding > 0 && full.unsent > 0, "{full:?}");
        assert!(full.outstanding <= written, "{full:?} of {written}");
        // Once the client has read everything, nothing is outstanding and all was acknowledged.
        let mut buf = vec![0u8; 65_536];
        let mut read = 0u64;
        while read < written {
            read += client.read(&mut buf).expect("read") as u64;
            let _ = server.write(&[]);
        }
        let mut after = probe.sample().expect("sample");
        for _ in 0..200 {
            if after.outstanding == 0 {
                break;
            }
            std::thread::sleep(Duration::from_millis(5));
            after = probe.sample().expect("sample");
        }
        assert_eq!(after.outstanding, 0, "{after:?}");
        assert!(
            after.acked >= idle.acked + written,
            "{idle:?} then {after:?}"
        );
        assert!(after.rtt > Duration::ZERO, "{after:?}");
    }
}
