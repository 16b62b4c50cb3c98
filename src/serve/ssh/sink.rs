//! A play session's frames over an SSH channel: written with russh, their arrival read from the
//! kernel's figures for the socket ([`super::link_probe`]) and, behind a load balancer, from the
//! client's answers to a request sent after each frame ([`crate::play::acks`]).

use std::sync::Arc;
use std::time::{Duration, Instant};

use russh::server::Handle;
use russh::ChannelId;

use super::lifeline::Lifeline;
use super::link_probe::LinkProbe;
use crate::play::acks::EchoGate;
use crate::play::link::LinkSample;
use crate::play::sink::{FrameSink, Gone};

/// How long a task waits for the client's answer to a frame's echo.
const ECHO_WAIT: Duration = Duration::from_secs(60);

/// One SSH channel as a session's frame sink.
pub struct SshSink {
    handle: Handle,
    channel: ChannelId,
    /// The connection's socket: bytes written so far, and its TCP addresses.
    life: Arc<Lifeline>,
    /// The kernel's figures for the socket, while it can give them.
    probe: Option<LinkProbe>,
    echo: EchoGate,
}

impl SshSink {
    /// A sink over `channel`; `echo` asks the client to answer each frame (behind a load
    /// balancer, where the kernel sees only the hop to the balancer).
    #[must_use]
    pub fn new(handle: Handle, channel: ChannelId, life: Arc<Lifeline>, echo: bool) -> Self {
        let probe = life
            .tcp()
            .and_then(|(local, peer)| LinkProbe::open(local, peer));
        Self {
            handle,
            channel,
            life,
            probe,
            echo: if echo {
                EchoGate::new()
            } else {
                EchoGate::off()
            },
        }
    }

    /// After a frame: asks the client for an answer that comes only once it has read the frame;
    /// a task waits for it.
    fn send_echo(&mut self) {
        let (n, answers) = self.echo.sent(crate::play::session::now());
        let handle = self.handle.clone();
        tokio::spawn(async move {
            let asked = Instant::now();
            // Success or failure alike: the client has read everything before it. No answer in
            // time (the connection is gone) leaves the frame unanswered.
            let answer =
                tokio::time::timeout(ECHO_WAIT, handle.cancel_forward_tcpip(String::new(), 0))
                    .await;
            if answer.is_ok() {
                answers.answered(n, asked.elapsed());
            }
        });
    }
}

impl FrameSink for SshSink {
    async fn send(&mut self, frame: Vec<u8>) -> Result<(), Gone> {
        self.handle
            .data(self.channel, frame)
            .await
            .map_err(|_| Gone)?;
        if self.echo.on() {
            self.send_echo();
        }
        Ok(())
    }

    fn written(&self) -> u64 {
        self.life.written()
    }

    fn sample(&mut self) -> Option<LinkSample> {
        let sample = self.probe.as_mut()?.sample();
        if sample.is_none() {
            // The kernel no longer knows the socket: pace on writes alone from now.
            self.probe = None;
        }
        sample
    }

    fn answered(&mut self, period: Duration, now: Instant) -> bool {
        self.echo.clear(period, now)
    }

    fn acked_rtt(&self) -> Option<Duration> {
        self.echo.least_rtt()
    }

    fn measures(&self) -> bool {
        self.probe.is_some()
    }
}
