//! The SSH protocol side of one connection: authentication, one session channel with a pty, and
//! refusal of everything that is not the game (exec, subsystems, forwarding, X11, agent).

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::{Duration, Instant};

use russh::keys::PublicKey;
use russh::server::{Auth, ChannelOpenHandle, Msg, Session};
use russh::{Channel, ChannelId, Pty};
use tokio::sync::{mpsc, watch};

use super::auth::Backoff;
use super::lifeline::Lifeline;
use super::session::{self, SshClient};
use crate::play::session::End;
use crate::serve::config::DEFAULT_SIZE;
use crate::serve::edge::admission;
use crate::serve::edge::arrival::{arrive, Who};
use crate::serve::edge::name::display_name;
use crate::serve::edge::run::Outcome;
use crate::serve::edge::Via;
use crate::serve::limits::{Pending, Playing, Refusal};
use crate::serve::ops::metrics::{self, Reason};
use crate::serve::shared::Shared;

/// The user name that watches instead of playing (`ssh -p 2222 watch@host`).
pub const SPECTATOR_USER: &str = "watch";
/// Key reads a session may have waiting; a client that floods beyond this loses its own keys.
const INPUT_QUEUE: usize = 64;

/// How long a connection whose game ended may linger before it is closed (the client normally
/// closes it first, on the channel's close).
const AFTER_GAME: Duration = Duration::from_secs(1);

/// The per-connection russh handler.
pub struct ConnHandler {
    id: u64,
    peer: SocketAddr,
    shared: Arc<Shared>,
    /// Failed password logins per source address, for every connection of the SSH port.
    backoff: Arc<Backoff>,
    user: String,
    channel: Option<ChannelId>,
    term: String,
    colorterm: Option<String>,
    /// `TMUX` and `HALFCAST_GLYPHS`, when the client sends them (for the glyph key's cycle).
    tmux: Option<String>,
    glyphs: Option<crate::render::glyphs::Glyphs>,
    size: watch::Sender<(u32, u32)>,
    data: Option<mpsc::Sender<Vec<u8>>>,
    started: bool,
    /// The logging-in place, until the shell starts.
    pending: Option<Pending>,
    life: Arc<Lifeline>,
}

impl ConnHandler {
    /// A handler for connection `id` from `peer`, admitted as `pending`, ended through `life`.
    #[must_use]
    pub fn new(
        id: u64,
        peer: SocketAddr,
        (shared, backoff): (Arc<Shared>, Arc<Backoff>),
        pending: Pending,
        life: Arc<Lifeline>,
    ) -> Self {
        let (size, _) = watch::channel((u32::from(DEFAULT_SIZE.0), u32::from(DEFAULT_SIZE.1)));
        Self {
            id,
            peer,
            shared,
            backoff,
            user: String::new(),
            channel: None,
            term: String::new(),
            colorterm: None,
            tmux: None,
            glyphs: None,
            size,
            data: None,
            started: false,
            pending: Some(pending),
            life,
        }
    }

    fn ours(&self, channel: ChannelId) -> bool {
        self.channel == Some(channel)
    }

    fn accept_user(&mut self, user: &str) -> Auth {
        self.user = user.to_string();
        Auth::Accept
    }

    fn reject(&self) -> Auth {
        Auth::Reject {
            proceed_with_methods: Some(self.shared.config.auth.methods()),
            partial_success: false,
        }
    }

    /// A wrong password: waits the source address's growing delay, then rejects.
    async fn reject_guess(&self) -> Auth {
        metrics::refused(Reason::Auth);
        let wait = self.backoff.failed(self.peer.ip(), Instant::now());
        self.shared.log.session(
            self.id,
            self.peer,
            format_args!("wrong password; next reply in {} ms", wait.as_millis()),
        );
        tokio::time::sleep(wait).await;
        self.reject()
    }

    /// Refuses a place to play: logged, counted, and told to the client as an SSH disconnect.
    fn turn_away(&self, session: &mut Session, why: &Refusal) -> Result<(), russh::Error> {
        admission::refuse(&self.shared, Some(self.id), self.peer, why.reason(), why);
        self.disconnect(session, why)
    }

    /// Tells the client why it may not play, as an SSH disconnect.
    fn disconnect(&self, session: &mut Session, why: &Refusal) -> Result<(), russh::Error> {
        session.disconnect(russh::Disconnect::TooManyConnections, &why.to_string(), "")
    }

    /// Turns the logging-in place into a playing one, or disconnects saying the server is full.
    fn take_place(&mut self, session: &mut Session) -> Result<Option<Playing>, russh::Error> {
        let Some(pending) = self.pending.as_ref() else {
            return Ok(None);
        };
        match admission::take_place(&self.shared, (Some(self.id), self.peer), pending) {
            Ok(place) => {
                self.pending = None;
                self.life.set_playing();
                Ok(Some(place))
            }
            Err(why) => {
                self.disconnect(session, &why)?;
                Ok(None)
            }
        }
    }
}

impl russh::server::Handler for ConnHandler {
    type Error = russh::Error;

    async fn auth_none(&mut self, user: &str) -> Result<Auth, Self::Error> {
        if self.shared.config.auth.allows_none() {
            Ok(self.accept_user(user))
        } else {
            Ok(self.reject())
        }
    }

    async fn auth_password(&mut self, user: &str, password: &str) -> Result<Auth, Self::Error> {
        if self.shared.config.auth.allows_password(password) {
            self.backoff.succeeded(self.peer.ip());
            Ok(self.accept_user(user))
        } else {
            Ok(self.reject_guess().await)
        }
    }

    async fn auth_publickey_offered(
        &mut self,
        _user: &str,
        offer: russh::server::PublicKeyOffer<'_>,
    ) -> Result<Auth, Self::Error> {
        if self.shared.config.auth.allows_key(offer.public_key) {
            Ok(Auth::Accept)
        } else {
            Ok(self.reject())
        }
    }

    async fn auth_publickey(
        &mut self,
        user: &str,
        key: russh::server::VerifiedPublicKey<'_>,
    ) -> Result<Auth, Self::Error> {
        let key: &PublicKey = key.public_key;
        if self.shared.config.auth.allows_key(key) {
            Ok(self.accept_user(user))
        } else {
            metrics::refused(Reason::Auth);
            Ok(self.reject())
        }
    }

    async fn auth_succeeded(&mut self, session: &mut Session) -> Result<(), Self::Error> {
        // Say "server full" now rather than after the client asked for a pty and a shell.
        if let Err(why) = self.shared.limiter.has_room() {
            self.turn_away(session, &why)?;
        }
        Ok(())
    }

    async fn channel_open_session(
        &mut self,
        channel: Channel<Msg>,
        reply: ChannelOpenHandle,
        _session: &mut Session,
    ) -> Result<(), Self::Error> {
        if self.channel.is_some() {
            // One game per connection; dropping `reply` refuses the channel.
            return Ok(());
        }
        self.channel = Some(channel.id());
        // We read the channel through this handler's callbacks; dropping the channel object
        // keeps russh from queueing a second copy of every key for nobody.
        drop(channel);
        reply.accept().await;
        Ok(())
    }

    async fn pty_request(
        &mut self,
        channel: ChannelId,
        term: &str,
        col_width: u32,
        row_height: u32,
        _pix_width: u32,
        _pix_height: u32,
        _modes: &[(Pty, u32)],
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        if !self.ours(channel) || self.started {
            return session.channel_failure(channel);
        }
        self.term = term.chars().take(64).collect();
        self.size.send_replace((col_width, row_height));
        session.channel_success(channel)
    }

    async fn window_change_request(
        &mut self,
        channel: ChannelId,
        col_width: u32,
        row_height: u32,
        _pix_width: u32,
        _pix_height: u32,
        _session: &mut Session,
    ) -> Result<(), Self::Error> {
        if self.ours(channel) {
            // Latest size wins; a client resizing 1000 times a second costs one store each.
            self.size.send_replace((col_width, row_height));
        }
        Ok(())
    }

    async fn env_request(
        &mut self,
        channel: ChannelId,
        name: &str,
        value: &str,
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        // Only three names are read, each kept short; nothing runs with the client's env.
        // COLORTERM picks the colour level; TMUX (tmux drops octants) and HALFCAST_GLYPHS (the
        // block characters to start with) shape the glyph key's cycle.
        if !self.ours(channel) || self.started {
            return session.channel_failure(channel);
        }
        match name {
            "COLORTERM" => self.colorterm = Some(value.chars().take(32).collect()),
            "TMUX" => self.tmux = Some(value.chars().take(64).collect()),
            "HALFCAST_GLYPHS" => match value.parse() {
                Ok(g) => self.glyphs = Some(g),
                Err(_) => return session.channel_failure(channel),
            },
            _ => return session.channel_failure(channel),
        }
        session.channel_success(channel)
    }

    async fn shell_request(
        &mut self,
        channel: ChannelId,
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        if !self.ours(channel) || self.started {
            return session.channel_failure(channel);
        }
        let Some(place) = self.take_place(session)? else {
            return Ok(());
        };
        self.started = true;
        session.channel_success(channel)?;
        let (tx, rx) = mpsc::channel(INPUT_QUEUE);
        self.data = Some(tx);
        let who = Who {
            id: self.id,
            peer: self.peer,
            name: display_name(&self.user, self.id),
            spectator: self.user == SPECTATOR_USER,
            via: Via::Ssh {
                term: self.term.clone(),
            },
        };
        let client = SshClient {
            term: self.term.clone(),
            colorterm: self.colorterm.clone(),
            tmux: self.tmux.clone(),
            glyphs: self.glyphs,
            handle: session.handle(),
            channel,
            life: Arc::clone(&self.life),
            echo: self.shared.config.proxy_protocol,
        };
        let (shared, size) = (Arc::clone(&self.shared), self.size.subscribe());
        let life = Arc::clone(&self.life);
        tokio::spawn(async move {
            let arrival = arrive(&shared, who, place).await;
            let outcome = session::run(arrival, client, rx, size).await;
            // A client that stopped reading can take no goodbye: cut the connection now.
            if !matches!(outcome, Outcome::Ended(End::Stalled, _)) {
                tokio::time::sleep(AFTER_GAME).await;
            }
            // One game per connection: when it is over, so is the connection.
            life.kill();
        });
        Ok(())
    }

    async fn data(
        &mut self,
        channel: ChannelId,
        data: &[u8],
        _session: &mut Session,
    ) -> Result<(), Self::Error> {
        if let (true, Some(tx)) = (self.ours(channel), &self.data) {
            // Full queue: this client is typing faster than its session reads; drop the excess.
            let _ = tx.try_send(data.to_vec());
        }
        Ok(())
    }

    async fn channel_eof(
        &mut self,
        channel: ChannelId,
        _session: &mut Session,
    ) -> Result<(), Self::Error> {
        if self.ours(channel) {
            self.data = None;
        }
        Ok(())
    }

    async fn channel_close(
        &mut self,
        channel: ChannelId,
        _session: &mut Session,
    ) -> Result<(), Self::Error> {
        if self.ours(channel) {
            self.data = None;
        }
        Ok(())
    }

    async fn exec_request(
        &mut self,
        channel: ChannelId,
        _data: &[u8],
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        self.shared
            .log
            .session(self.id, self.peer, "refused an exec request");
        session.channel_failure(channel)
    }

    async fn subsystem_request(
        &mut self,
        channel: ChannelId,
        name: &str,
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        self.shared.log.session(
            self.id,
            self.peer,
            format_args!(
                "refused subsystem {:?}",
                name.chars().take(32).collect::<String>()
            ),
        );
        session.channel_failure(channel)
    }

    async fn x11_request(
        &mut self,
        channel: ChannelId,
        _single_connection: bool,
        _x11_auth_protocol: &str,
        _x11_auth_cookie: &str,
        _x11_screen_number: u32,
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        session.channel_failure(channel)
    }

    async fn agent_request(
        &mut self,
        _channel: ChannelId,
        _session: &mut Session,
    ) -> Result<bool, Self::Error> {
        Ok(false)
    }

    async fn tcpip_forward(
        &mut self,
        _address: &str,
        _port: &mut u32,
        _session: &mut Session,
    ) -> Result<bool, Self::Error> {
        Ok(false)
    }

    async fn streamlocal_forward(
        &mut self,
        _socket_path: &str,
        _session: &mut Session,
    ) -> Result<bool, Self::Error> {
        Ok(false)
    }
    // Channel opens other than "session" (direct-tcpip, x11, streamlocal, forwarded) keep the
    // default handlers, which drop the open handle and so refuse the channel.
}
