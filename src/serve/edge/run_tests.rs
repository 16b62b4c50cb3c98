//! The one way in driven without a network: a session whose sink panics (a bug in a transport or
//! in the session) is caught, counted, logged, its player taken out of the world and its place
//! given back; one that ends normally is counted once and frees its place too.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use tokio::sync::{mpsc, watch};

use super::admission;
use super::arrival::{arrive, Who};
use super::run::{Facts, Goodbye, Outcome, Transport};
use super::Via;
use crate::game::multi::players::Rules as GameRules;
use crate::game::multi::round::Mode;
use crate::play::avatars::with_avatar_sheet;
use crate::play::input::Input;
use crate::play::link::LinkSample;
use crate::play::session::End;
use crate::play::sink::{FrameSink, Gone};
use crate::serve::config::ServeConfig;
use crate::serve::limits::{Caps, Limiter};
use crate::serve::ops::log::Log;
use crate::serve::ops::stats::ServeStats;
use crate::serve::shared::Shared;
use crate::world::World;

/// A sink that takes frames (each at once on the wire) until armed, then panics on the next.
struct Fragile(Arc<AtomicBool>, u64);

impl FrameSink for Fragile {
    async fn send(&mut self, frame: Vec<u8>) -> Result<(), Gone> {
        assert!(!self.0.load(Ordering::SeqCst), "a bug in the transport");
        self.1 += frame.len() as u64;
        Ok(())
    }
    fn written(&self) -> u64 {
        self.1
    }
    fn sample(&mut self) -> Option<LinkSample> {
        None
    }
    fn answered(&mut self, _period: Duration, _now: Instant) -> bool {
        true
    }
    fn acked_rtt(&self) -> Option<Duration> {
        None
    }
    fn measures(&self) -> bool {
        false
    }
}

/// Remembers the outcome the transport was told to say goodbye to.
#[derive(Clone, Default)]
struct Told(Arc<Mutex<Vec<String>>>);

impl Goodbye for Told {
    async fn goodbye(self, outcome: &Outcome) {
        self.0.lock().unwrap().push(format!("{outcome:?}"));
    }
}

/// What keeps a test server's world and signals alive.
type Alive = (
    watch::Sender<bool>,
    watch::Sender<bool>,
    watch::Sender<&'static str>,
);

/// A server's shared state with room for exactly one player, its world running.
fn one_place() -> (Arc<Shared>, Alive) {
    let (world, sheet) = with_avatar_sheet(World::default_world());
    let world = Arc::new(world);
    let (hold, held) = watch::channel(false);
    let rules = GameRules::new(Mode::Coop, 1);
    let (port, _) =
        crate::serve::world_task::spawn_rounds(vec![Arc::clone(&world)], 30, rules, |_| {}, held);
    let caps = Caps {
        max_sessions: 1,
        max_per_ip: 4,
        startups: "10:30:100".parse().unwrap(),
        startups_per_ip: 4,
    };
    let (shutdown_tx, shutdown) = watch::channel(false);
    let (farewell_tx, farewell) = watch::channel("");
    let addr: SocketAddr = "127.0.0.1:0".parse().unwrap();
    let shared = Arc::new(Shared {
        config: ServeConfig::local(addr, PathBuf::from("unused")),
        world: port,
        maps: vec![Arc::clone(&world)],
        world_data: world,
        avatar_sheet: sheet,
        stats: Arc::new(ServeStats::default()),
        log: Log::new(true),
        shutdown,
        farewell,
        limiter: Limiter::new(caps, 1),
        boards: None,
        next_id: 1.into(),
    });
    (shared, (hold, shutdown_tx, farewell_tx))
}

/// Waits (up to 5 s of the real clock) until the world's snapshots say whether `id` plays.
async fn until_in_world(shared: &Shared, id: u64, present: bool) -> bool {
    let mut snaps = shared.world.snapshots();
    let wait = async {
        loop {
            if snaps.borrow_and_update().player(id).is_some() == present {
                return;
            }
            if snaps.changed().await.is_err() {
                return;
            }
        }
    };
    tokio::time::timeout(Duration::from_secs(5), wait)
        .await
        .is_ok()
}

#[tokio::test]
async fn a_panicking_browser_session_is_caught_counted_and_frees_its_place() {
    let (shared, _alive) = one_place();
    let peer: SocketAddr = "127.0.0.1:40000".parse().unwrap();
    let pending = admission::admit(&shared, peer).unwrap();
    let place = admission::take_place(&shared, (None, peer), &pending).unwrap();
    drop(pending);
    let id = admission::connected(&shared, peer);
    assert!(shared.limiter.has_room().is_err(), "one place, taken");
    let who = Who {
        id,
        peer,
        name: "ann".into(),
        spectator: false,
        via: Via::Web,
    };
    let arrival = arrive(&shared, who, place).await;
    assert_eq!(shared.stats.snapshot().sessions_live, 1);
    assert!(until_in_world(&shared, id, true).await, "joined the world");
    let armed = Arc::new(AtomicBool::new(false));
    let (_input, input) = mpsc::channel::<Input>(4);
    let (size_tx, size) = watch::channel((80, 24));
    let transport = Transport {
        facts: Facts::browser(),
        input,
        size,
        sink: Fragile(Arc::clone(&armed), 0),
    };
    let told = Told::default();
    let play = tokio::spawn(arrival.play(transport, told.clone()));
    // Let the first frame go out, then break the sink and ask for a frame of another size.
    tokio::time::sleep(Duration::from_millis(200)).await;
    armed.store(true, Ordering::SeqCst);
    size_tx.send_replace((100, 30));
    let outcome = tokio::time::timeout(Duration::from_secs(5), play)
        .await
        .expect("the panic ends the session")
        .expect("the edge itself does not panic");
    assert!(matches!(outcome, Outcome::Failed), "{outcome:?}");
    assert_eq!(*told.0.lock().unwrap(), ["Failed"], "the goodbye heard it");
    let stats = shared.stats.snapshot();
    assert_eq!(stats.sessions_failed, 1, "counted");
    assert_eq!(stats.sessions_live, 0, "not counted live");
    assert!(shared.limiter.has_room().is_ok(), "the place is free again");
    assert!(until_in_world(&shared, id, false).await, "left the world");
    // The server is not full: the next page gets the place.
    let next = admission::admit(&shared, peer).unwrap();
    assert!(admission::take_place(&shared, (None, peer), &next).is_ok());
}

#[tokio::test]
async fn a_session_that_ends_gives_back_its_place_once() {
    let (shared, _alive) = one_place();
    let peer: SocketAddr = "127.0.0.1:40001".parse().unwrap();
    let pending = admission::admit(&shared, peer).unwrap();
    let place = admission::take_place(&shared, (None, peer), &pending).unwrap();
    drop(pending);
    let id = admission::connected(&shared, peer);
    let who = Who {
        id,
        peer,
        name: "bob".into(),
        spectator: false,
        via: Via::Ssh {
            term: "xterm".into(),
        },
    };
    let arrival = arrive(&shared, who, place).await;
    let (input_tx, input) = mpsc::channel::<Vec<u8>>(4);
    let (_size_tx, size) = watch::channel((80, 24));
    let transport = Transport {
        facts: Facts::browser(),
        input,
        size,
        sink: Fragile(Arc::new(AtomicBool::new(false)), 0),
    };
    let told = Told::default();
    let play = tokio::spawn(arrival.play(transport, told.clone()));
    input_tx.send(b"q".to_vec()).await.unwrap();
    let outcome = tokio::time::timeout(Duration::from_secs(5), play)
        .await
        .unwrap()
        .unwrap();
    assert!(
        matches!(outcome, Outcome::Ended(End::Quit, _)),
        "{outcome:?}"
    );
    let stats = shared.stats.snapshot();
    assert_eq!((stats.sessions_live, stats.sessions_failed), (0, 0));
    assert!(shared.limiter.has_room().is_ok());
    assert!(until_in_world(&shared, id, false).await);
}
