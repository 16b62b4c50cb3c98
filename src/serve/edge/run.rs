//! A let-in player's session run to its end, the same for every transport: the session in a task
//! of its own (a panic there ends that session only, and is logged, counted, and its player
//! taken out of the world), then the transport's goodbye, then the end's figures and log line,
//! and last the player's place given back.

use std::future::Future;

use tokio::sync::watch;

use super::arrival::{Arrival, Who};
use super::hooks::{draining_notes, ServerHooks};
use crate::play::input::InputSource;
use crate::play::link_text::link_summary;
use crate::play::session::{self, Client, End, Feeds, Setup, Tally};
pub use crate::play::setup::Facts;
use crate::play::sink::FrameSink;
use crate::play::world_port::WorldMsg;
use crate::serve::ops::metrics::{self, Reason};
use crate::serve::ops::stats::ServeStats;
use crate::serve::shared::Shared;

/// How a session ended, for its transport's goodbye.
#[derive(Debug, Clone, Copy)]
pub enum Outcome {
    /// The session ran to an end, with its figures.
    Ended(End, Tally),
    /// The session panicked (a bug): it was logged and counted, its player left the world.
    Failed,
}

/// How a transport says goodbye to its client once the session is over (a terminal put back, a
/// close frame with the reason): best effort, never long.
pub trait Goodbye: Send {
    /// Says goodbye after `outcome`.
    fn goodbye(self, outcome: &Outcome) -> impl Future<Output = ()> + Send;
}

/// What the transport hands over for play: its client's facts, its input and size, its sink.
pub struct Transport<I, S> {
    pub facts: Facts,
    pub input: I,
    /// The client's latest size in columns and rows.
    pub size: watch::Receiver<(u32, u32)>,
    pub sink: S,
}

impl Arrival {
    /// Plays the session to its end over `transport`, says goodbye with `bye`, then does the end's
    /// bookkeeping and gives the place back.
    pub async fn play<I, S, G>(self, transport: Transport<I, S>, bye: G) -> Outcome
    where
        I: InputSource + Send + 'static,
        S: FrameSink + Send + 'static,
        G: Goodbye,
    {
        let Arrival {
            shared,
            who,
            joined,
            live,
        } = self;
        let client = Client {
            id: who.id,
            name: who.name.clone(),
            spectator: who.spectator,
            facts: transport.facts,
        };
        let setup = Setup {
            client,
            rules: shared.rules(),
        };
        let feeds = Feeds {
            input: transport.input,
            size: transport.size,
            shutdown: shared.shutdown.clone(),
            announce: draining_notes(shared.farewell.clone()),
        };
        let hooks = ServerHooks::new(who.id, who.peer, shared.log, shared.boards.clone());
        let running = session::run(joined, setup, feeds, transport.sink, hooks);
        let outcome = match tokio::spawn(running).await {
            Ok((end, tally)) => Outcome::Ended(end, tally),
            Err(e) => {
                failed(&shared, &who, &e).await;
                Outcome::Failed
            }
        };
        bye.goodbye(&outcome).await;
        if let Outcome::Ended(end, tally) = &outcome {
            session_ended(&shared, &who, *end, tally);
        }
        drop(live);
        outcome
    }
}

/// A session ended with `end`: the totals add its figures, and its last log line says how it
/// went.
fn session_ended(shared: &Shared, who: &Who, end: End, tally: &Tally) {
    let (stats, log) = (&shared.stats, shared.log);
    let (id, peer, transport) = (who.id, who.peer, who.via.label());
    if end == End::Stalled {
        metrics::refused(Reason::Stall);
    }
    ServeStats::add(&stats.frames_sent, tally.frames);
    ServeStats::add(&stats.bytes_sent, tally.bytes);
    ServeStats::add(&stats.frames_dropped, tally.dropped);
    // SSH's is the line operators know; another transport says which it is.
    let over = if transport == "ssh" {
        String::new()
    } else {
        format!(" over {transport}")
    };
    log.session(
        id,
        peer,
        format_args!(
            "session ended ({end:?}){over}: {} frames, {} bytes, {} frame ticks skipped{}",
            tally.frames,
            tally.bytes,
            tally.dropped,
            link_summary(&tally.link),
        ),
    );
}

/// A session that panicked: logged and counted, and its player taken out of the world (the
/// session never got to say it left).
async fn failed(shared: &Shared, who: &Who, e: &tokio::task::JoinError) {
    shared
        .log
        .session(who.id, who.peer, format_args!("session failed: {e}"));
    metrics::session_failed(who.via.label());
    ServeStats::add(&shared.stats.sessions_failed, 1);
    if !who.spectator {
        shared.world.send(WorldMsg::Leave { id: who.id }).await;
    }
}
