//! The SSH edge of a play session: what an SSH client gives before play (its terminal's name,
//! its answers to the colour query), its channel as the session's sink ([`super::sink`]), and
//! the goodbye a terminal needs (the alternate screen left, a last line, the channel closed).
//! The session's run and its end are the one way in's ([`crate::serve::edge::run`]).

use std::sync::Arc;
use std::time::Duration;

use russh::server::Handle;
use russh::ChannelId;
use tokio::sync::{mpsc, watch};

use super::ask_colour::{ask_colour, SSH_QUERY_PATIENCE};
use super::lifeline::Lifeline;
use super::sink::SshSink;
use crate::encode::ColourChoice;
use crate::game::multi::players::PlayerId;
use crate::play::session::End;
use crate::render::glyphs::Glyphs;
use crate::serve::edge::arrival::Arrival;
use crate::serve::edge::run::{Facts, Goodbye, Outcome, Transport};
use crate::serve::ops::drain;
use crate::ui::keys::InputMode;
use crate::ui::octant_support::{octant_dropper, TermEnv};

/// Alternate screen, hidden cursor, cleared; kitty keyboard flags pushed (disambiguate, event
/// types, all keys as escapes) and queried, so release events arrive where supported.
const ENTER: &[u8] = b"\x1b[?1049h\x1b[?25l\x1b[0m\x1b[2J\x1b[>11u\x1b[?u";
/// Everything [`ENTER`] changed, undone.
pub const LEAVE: &[u8] = b"\x1b[<u\x1b[0m\x1b[?25h\x1b[?1049l";
/// How an SSH player asks for octants where the glyph key skips them.
pub const FORCE_OCTANTS: &str = "ssh -o SetEnv=HALFCAST_GLYPHS=octant forces";
/// How long a goodbye may take to go out.
const BYE_WAIT: Duration = Duration::from_secs(2);

/// What the SSH edge knows of its client when the shell starts: its terminal, and the channel
/// and socket it plays over.
pub struct SshClient {
    pub term: String,
    pub colorterm: Option<String>,
    /// `TMUX`, when the client sent it (an env request): tmux drops octants.
    pub tmux: Option<String>,
    /// `HALFCAST_GLYPHS`, when the client sent it: the block characters to start with (octant
    /// there forces octants into the glyph key's cycle).
    pub glyphs: Option<Glyphs>,
    pub handle: Handle,
    pub channel: ChannelId,
    /// The connection's socket: bytes written so far, its TCP addresses, and where the link
    /// figures go when the session ends.
    pub life: Arc<Lifeline>,
    /// Whether frames are acknowledged end to end ([`crate::play::acks`]): behind a load
    /// balancer (`--proxy-protocol`), where the kernel sees only the hop to the balancer.
    pub echo: bool,
}

/// Runs a let-in SSH client's session: its terminal's colours asked, then play over the channel,
/// then the terminal put back.
pub async fn run(
    arrival: Arrival,
    c: SshClient,
    mut data: mpsc::Receiver<Vec<u8>>,
    size: watch::Receiver<(u32, u32)>,
) -> Outcome {
    let mut colour = level_for_term(&c.term, c.colorterm.as_deref());
    let mut early = Vec::new();
    // Before the first frame: a TERM guess is checked with the client's terminal itself, on the
    // alternate screen, so a terminal that shows a query as text shows it there only.
    if colour.worth_asking() {
        let asked = ask_colour(
            &c.handle,
            c.channel,
            ENTER,
            &mut data,
            SSH_QUERY_PATIENCE,
            colour,
        )
        .await;
        (colour, early) = asked;
    } else {
        let _ = c.handle.data(c.channel, ENTER.to_vec()).await;
    }
    let facts = Facts {
        colour,
        glyphs: c.glyphs.unwrap_or_default(),
        octant_dropper: octant_dropper(TermEnv {
            term: Some(&c.term),
            tmux: c.tmux.as_deref(),
        }),
        force_octants: FORCE_OCTANTS,
        input_mode: InputMode::Emulated,
        early,
    };
    let transport = Transport {
        facts,
        input: data,
        size,
        sink: SshSink::new(c.handle.clone(), c.channel, Arc::clone(&c.life), c.echo),
    };
    let bye = SshGoodbye {
        handle: c.handle,
        channel: c.channel,
        life: c.life,
        id: arrival.who().id,
        farewell: arrival.shared().farewell.clone(),
    };
    arrival.play(transport, bye).await
}

/// How an SSH client is left: the terminal put back as it was, a last line, the channel closed.
struct SshGoodbye {
    handle: Handle,
    channel: ChannelId,
    life: Arc<Lifeline>,
    id: PlayerId,
    farewell: watch::Receiver<&'static str>,
}

impl Goodbye for SshGoodbye {
    async fn goodbye(self, outcome: &Outcome) {
        let last: Vec<u8> = match *outcome {
            Outcome::Ended(end, tally) => {
                self.life.set_link(tally.link);
                match end {
                    // A dead link or a closed client is not waited on.
                    End::ClientGone | End::Stalled => return,
                    End::Idle => b"halfcast: closed after being idle too long.\r\n".to_vec(),
                    End::Shutdown => drain::farewell_line_for(*self.farewell.borrow(), self.id),
                    End::Quit => Vec::new(),
                }
            }
            Outcome::Failed => Vec::new(),
        };
        let mut bye = LEAVE.to_vec();
        bye.extend_from_slice(&last);
        let (h, channel) = (&self.handle, self.channel);
        let _ = tokio::time::timeout(BYE_WAIT, async {
            let _ = h.data(channel, bye).await;
            if matches!(outcome, Outcome::Ended(..)) {
                let _ = h.exit_status_request(channel, 0).await;
                let _ = h.eof(channel).await;
            }
            let _ = h.close(channel).await;
        })
        .await;
    }
}

/// The colour level for a client's `TERM` (and `COLORTERM`, when its client sends it as an env
/// request): the same rule as the local game's ([`crate::ui::colour_query::rules::guess`]).
fn level_for_term(term: &str, colorterm: Option<&str>) -> ColourChoice {
    crate::ui::colour_query::rules::guess(colorterm, Some(term), None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::encode::ColorLevel;

    #[test]
    fn term_names_map_to_levels() {
        assert_eq!(
            level_for_term("xterm-kitty", None).level,
            ColorLevel::TrueColor
        );
        assert_eq!(
            level_for_term("xterm-direct", None).level,
            ColorLevel::TrueColor
        );
        assert_eq!(
            level_for_term("xterm-256color", None).level,
            ColorLevel::Ansi256
        );
        assert_eq!(
            level_for_term("xterm-256color", Some("truecolor")).level,
            ColorLevel::TrueColor
        );
        assert_eq!(level_for_term("xterm", None).level, ColorLevel::Ansi256);
        assert_eq!(level_for_term("", None).level, ColorLevel::Mono);
        assert_eq!(level_for_term("dumb", None).level, ColorLevel::Mono);
    }
}
