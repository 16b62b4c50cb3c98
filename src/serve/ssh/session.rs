//! The SSH edge of a play session: what an SSH client gives before play (its terminal's name,
//! its answers to the colour query), the session run over the channel ([`super::sink`]), and
//! the goodbye a terminal needs (the alternate screen left, a last line, the channel closed).

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;

use russh::server::Handle;
use russh::ChannelId;
use tokio::sync::{mpsc, watch};

use super::ask_colour::{ask_colour, SSH_QUERY_PATIENCE};
use super::sink::SshSink;
use crate::encode::ColourChoice;
use crate::game::multi::players::PlayerId;
use crate::play::session::{self, End, Feeds, Setup};
use crate::play::world_port::WorldHandle;
use crate::render::glyphs::Glyphs;
use crate::serve::ops::drain::{self};
use crate::serve::ops::lifecycle::Lifeline;
use crate::serve::ops::log::Log;
use crate::serve::ops::stats::ServeStats;
use crate::serve::session_hooks::{
    draining_notes, session_ended, session_started, BoardLine, ServerHooks,
};
use crate::ui::keys::InputMode;
use crate::ui::octant_support::{octant_dropper, TermEnv};
use crate::world::World;

/// Alternate screen, hidden cursor, cleared; kitty keyboard flags pushed (disambiguate, event
/// types, all keys as escapes) and queried, so release events arrive where supported.
const ENTER: &[u8] = b"\x1b[?1049h\x1b[?25l\x1b[0m\x1b[2J\x1b[>11u\x1b[?u";
/// Everything [`ENTER`] changed, undone.
pub const LEAVE: &[u8] = b"\x1b[<u\x1b[0m\x1b[?25h\x1b[?1049l";
/// How an SSH player asks for octants where the glyph key skips them.
pub const FORCE_OCTANTS: &str = "ssh -o SetEnv=HALFCAST_GLYPHS=octant forces";

/// What the SSH edge knows of a connection when its shell starts.
pub struct SessionParams {
    pub id: PlayerId,
    pub peer: SocketAddr,
    pub name: String,
    /// Watches a player's view instead of playing.
    pub spectator: bool,
    pub term: String,
    pub colorterm: Option<String>,
    /// `TMUX`, when the client sent it (an env request): tmux drops octants.
    pub tmux: Option<String>,
    /// `HALFCAST_GLYPHS`, when the client sent it: the block characters to start with (octant
    /// there forces octants into the glyph key's cycle).
    pub glyphs: Option<Glyphs>,
    pub handle: Handle,
    pub channel: ChannelId,
    pub world: WorldHandle,
    /// The lasting leaderboard, when the server keeps one.
    pub boards: Option<BoardLine>,
    /// The served world (with the avatar sheet at `avatar_sheet`).
    pub world_data: Arc<World>,
    pub avatar_sheet: usize,
    pub fps: u32,
    /// Players with no keystroke for this long are closed; spectators never are.
    pub idle_timeout: Duration,
    /// A client that takes no frame for this long is dropped.
    pub stall_timeout: Duration,
    pub stats: Arc<ServeStats>,
    pub log: Log,
    pub shutdown: watch::Receiver<bool>,
    /// The connection's socket: bytes written so far, its TCP addresses, and where the link
    /// figures go when the session ends.
    pub life: Arc<Lifeline>,
    /// Whether frames are acknowledged end to end ([`crate::play::acks`]): behind a load
    /// balancer (`--proxy-protocol`), where the kernel sees only the hop to the balancer.
    pub echo: bool,
    /// The last line a player sees when the server stops (see [`drain`]).
    pub farewell: watch::Receiver<&'static str>,
}

/// What the connection handler feeds the session: raw key bytes, and the latest pty size.
pub struct SessionInputs {
    pub data: mpsc::Receiver<Vec<u8>>,
    pub size: watch::Receiver<(u32, u32)>,
}

/// Runs one SSH client's session until it ends, then says goodbye and logs it.
pub async fn run(p: SessionParams, mut inputs: SessionInputs) -> End {
    session_started(p.spectator, "ssh");
    let joined = session::join(&p.world, p.id, &p.name, p.spectator).await;
    let mut colour = level_for_term(&p.term, p.colorterm.as_deref());
    let mut early = Vec::new();
    // Before the first frame: a TERM guess is checked with the client's terminal itself, on the
    // alternate screen, so a terminal that shows a query as text shows it there only.
    if colour.worth_asking() {
        let asked = ask_colour(
            &p.handle,
            p.channel,
            ENTER,
            &mut inputs.data,
            SSH_QUERY_PATIENCE,
            colour,
        )
        .await;
        (colour, early) = asked;
    } else {
        let _ = p.handle.data(p.channel, ENTER.to_vec()).await;
    }
    let setup = Setup {
        id: p.id,
        name: p.name.clone(),
        spectator: p.spectator,
        colour,
        glyphs: p.glyphs.unwrap_or_default(),
        octant_dropper: octant_dropper(TermEnv {
            term: Some(&p.term),
            tmux: p.tmux.as_deref(),
        }),
        force_octants: FORCE_OCTANTS,
        input_mode: InputMode::Emulated,
        early,
        world: p.world.clone(),
        world_data: Arc::clone(&p.world_data),
        avatar_sheet: p.avatar_sheet,
        fps: p.fps,
        idle_timeout: p.idle_timeout,
        stall_timeout: p.stall_timeout,
    };
    let feeds = Feeds {
        input: inputs.data,
        size: inputs.size,
        shutdown: p.shutdown.clone(),
        announce: draining_notes(p.farewell.clone()),
    };
    let sink = SshSink::new(p.handle.clone(), p.channel, Arc::clone(&p.life), p.echo);
    let hooks = ServerHooks::new(p.id, p.peer, p.log, p.boards.clone());
    let (end, tally) = session::run(joined, setup, feeds, sink, hooks).await;
    p.life.set_link(tally.link);
    if !matches!(end, End::ClientGone | End::Stalled) {
        goodbye(&p, end).await;
    }
    session_ended(
        (&p.stats, p.log),
        (p.id, p.peer),
        (p.spectator, "ssh"),
        end,
        &tally,
    );
    end
}

/// The terminal put back as it was, a last line, and the channel closed; best effort, as the
/// client may already be gone (a dead link is not waited on).
async fn goodbye(p: &SessionParams, end: End) {
    let mut bye = LEAVE.to_vec();
    let farewell = drain::farewell_line_for(*p.farewell.borrow(), p.id);
    bye.extend_from_slice(match end {
        End::Idle => b"halfcast: closed after being idle too long.\r\n".as_slice(),
        End::Shutdown => &farewell,
        _ => b"",
    });
    let h = &p.handle;
    let _ = tokio::time::timeout(Duration::from_secs(2), async {
        let _ = h.data(p.channel, bye).await;
        let _ = h.exit_status_request(p.channel, 0).await;
        let _ = h.eof(p.channel).await;
        let _ = h.close(p.channel).await;
    })
    .await;
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
