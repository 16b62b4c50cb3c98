//! A session driven without a network: a scripted link (bytes a second, a round trip) as its
//! frame sink, on tokio's paused clock, so every run is the same and none sleeps.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use tokio::sync::{mpsc, watch};

use super::hooks::Hooks;
use super::input::Input;
use super::link::LinkSample;
use super::pacing::MIN_FPS;
use super::session::{self, now, Client, End, Facts, Feeds, Rules, Setup, Tally};
use super::sink::{FrameSink, Gone};
use crate::encode::{ColorLevel, ColourChoice, ColourReason};
use crate::game::multi::players::Rules as GameRules;
use crate::game::multi::players::Snapshot;
use crate::game::multi::round::Mode;
use crate::game::TAP_TURN_DEG;
use crate::play::avatars::with_avatar_sheet;
use crate::render::glyphs::Glyphs;
use crate::ui::key_bytes::{Key, KeyEvent, KeyKind};
use crate::ui::keys::InputMode;
use crate::world::World;

/// A frame handed to the link: when, how big, and when its last byte leaves the bottleneck.
#[derive(Debug, Clone, Copy)]
struct Sent {
    at: Instant,
    bytes: u64,
    /// When the bottleneck starts and ends sending it.
    start: Instant,
    end: Instant,
}

/// A bottleneck of `rate` bytes a second behind a path of round trip `rtt`: frames queue in it
/// one after another; a byte is acknowledged a round trip after it left.
#[derive(Debug)]
struct Link {
    rate: f64,
    rtt: Duration,
    frames: Vec<Sent>,
    /// The share of its bytes a frame would keep if the transport shrank it (as a browser's
    /// compression does), when it can.
    could_shrink: Option<f64>,
    /// The share it keeps now.
    ratio: f64,
}

impl Link {
    fn new(rate: f64, rtt: Duration) -> Self {
        Self {
            rate,
            rtt,
            frames: Vec::new(),
            could_shrink: None,
            ratio: 1.0,
        }
    }

    fn written(&self) -> u64 {
        self.frames.iter().map(|f| f.bytes).sum()
    }

    /// Bytes that left the bottleneck by `t`.
    fn left_by(&self, t: Instant) -> u64 {
        self.frames
            .iter()
            .map(|f| {
                if t >= f.end {
                    f.bytes
                } else if t <= f.start {
                    0
                } else {
                    let part = (t - f.start).as_secs_f64() / (f.end - f.start).as_secs_f64();
                    (f.bytes as f64 * part) as u64
                }
            })
            .sum()
    }

    fn acked_by(&self, t: Instant) -> u64 {
        t.checked_sub(self.rtt).map_or(0, |t| self.left_by(t))
    }

    fn send(&mut self, bytes: u64, at: Instant) {
        let start = self.frames.last().map_or(at, |f| f.end.max(at));
        let end = start + Duration::from_secs_f64(bytes as f64 / self.rate);
        self.frames.push(Sent {
            at,
            bytes,
            start,
            end,
        });
    }

    /// When the frame handed over at `i` has reached the client (its last byte left the
    /// bottleneck and crossed half the round trip).
    fn arrived(&self, i: usize) -> Instant {
        self.frames[i].end + self.rtt / 2
    }
}

/// The scripted link as a session's sink.
#[derive(Clone)]
struct FakeSink(Arc<Mutex<Link>>);

impl FrameSink for FakeSink {
    async fn send(&mut self, frame: Vec<u8>) -> Result<(), Gone> {
        let mut link = self.0.lock().unwrap();
        let bytes = (frame.len() as f64 * link.ratio).ceil() as u64;
        link.send(bytes, now());
        Ok(())
    }

    fn could_shrink(&self) -> Option<f64> {
        let link = self.0.lock().unwrap();
        link.could_shrink.filter(|r| *r < link.ratio)
    }

    fn shrink(&mut self) {
        let mut link = self.0.lock().unwrap();
        if let Some(r) = link.could_shrink {
            link.ratio = r;
        }
    }

    fn written(&self) -> u64 {
        self.0.lock().unwrap().written()
    }

    fn sample(&mut self) -> Option<LinkSample> {
        let link = self.0.lock().unwrap();
        let t = now();
        let acked = link.acked_by(t);
        Some(LinkSample {
            outstanding: link.written() - acked,
            unsent: link.written() - link.left_by(t),
            rtt: link.rtt,
            delivery_rate: link.rate as u64,
            app_limited: false,
            acked,
            min_rtt: link.rtt,
        })
    }

    fn answered(&mut self, _period: Duration, _now: Instant) -> bool {
        true
    }

    fn acked_rtt(&self) -> Option<Duration> {
        None
    }

    fn measures(&self) -> bool {
        true
    }
}

/// Level steps the session reported, with when.
#[derive(Clone, Default)]
struct Steps(Arc<Mutex<Vec<(Instant, bool)>>>);

impl Hooks for Steps {
    fn level_stepped(&self, down: bool) {
        self.0.lock().unwrap().push((now(), down));
    }
}

/// A running session: its input, its link, its level steps.
struct Run {
    input: mpsc::Sender<Input>,
    /// The world's snapshots, to read where the player looks.
    snaps: watch::Receiver<Arc<Snapshot>>,
    link: Arc<Mutex<Link>>,
    steps: Steps,
    done: tokio::task::JoinHandle<(End, Tally)>,
    _shutdown: watch::Sender<bool>,
    _hold: watch::Sender<bool>,
    _size: watch::Sender<(u32, u32)>,
    _announce: watch::Sender<Option<String>>,
}

/// A player at 80×24 and `level` on a link of `rate` bytes a second and round trip `rtt`, alone
/// in the default map's world.
fn start(rate: f64, rtt: Duration, level: ColorLevel) -> Run {
    let (world, sheet) = with_avatar_sheet(World::default_world());
    let world = Arc::new(world);
    // Never drained (`hold` stays false): the world's rounds go on for the test's whole run.
    let (hold, held) = watch::channel(false);
    let (port, _phase) = crate::serve::world_task::spawn_rounds(
        vec![Arc::clone(&world)],
        30,
        GameRules::new(Mode::Coop, 1),
        |_| {},
        held,
    );
    let client = Client {
        id: 1,
        name: "ann".into(),
        spectator: false,
        facts: Facts {
            colour: ColourChoice {
                level,
                reason: ColourReason::Term,
            },
            glyphs: Glyphs::Half,
            octant_dropper: None,
            force_octants: "",
            input_mode: InputMode::Emulated,
            early: Vec::new(),
        },
    };
    let snaps = port.snapshots();
    let rules = Rules {
        world: port,
        world_data: world,
        avatar_sheet: sheet,
        fps: 30,
        idle_timeout: Duration::from_secs(600),
        stall_timeout: Duration::from_secs(30),
    };
    let setup = Setup { client, rules };
    let (input, input_rx) = mpsc::channel(64);
    let (shutdown, shutdown_rx) = watch::channel(false);
    let (size, size_rx) = watch::channel((80, 24));
    let (announce, announce_rx) = watch::channel(None);
    let feeds = Feeds {
        input: input_rx,
        size: size_rx,
        shutdown: shutdown_rx,
        announce: announce_rx,
    };
    let link = Arc::new(Mutex::new(Link::new(rate, rtt)));
    let steps = Steps::default();
    let (sink_link, steps_hooks) = (Arc::clone(&link), steps.clone());
    let done = tokio::spawn(async move {
        let c = &setup.client;
        let joined = session::join(&setup.rules.world, c.id, &c.name, c.spectator).await;
        session::run(
            joined,
            setup,
            feeds,
            FakeSink(Arc::clone(&sink_link)),
            steps_hooks,
        )
        .await
    });
    Run {
        input,
        snaps,
        link,
        steps,
        done,
        _shutdown: shutdown,
        _hold: hold,
        _size: size,
        _announce: announce,
    }
}

impl Run {
    async fn key(&self, c: char, kind: KeyKind) {
        let ev = KeyEvent {
            key: Key::Char(c),
            kind,
        };
        self.input.send(Input::Keys(vec![ev])).await.unwrap();
    }

    /// Key events that arrive together (a quick tap, or a link that bunched them).
    async fn keys(&self, events: &[(char, KeyKind)]) {
        let events = events
            .iter()
            .map(|&(c, kind)| KeyEvent {
                key: Key::Char(c),
                kind,
            })
            .collect();
        self.input.send(Input::Keys(events)).await.unwrap();
    }

    /// Where the player looks now, in degrees (0 east, 90 north).
    fn angle(&self) -> f64 {
        let snap = self.snaps.borrow();
        let dir = snap.player(1).expect("in the world").state.camera.dir;
        (-dir.y).atan2(dir.x).to_degrees()
    }

    /// Frames handed over from `from` on: (when, bytes, when it reached the client).
    fn frames_since(&self, from: Instant) -> Vec<(Instant, u64, Instant)> {
        self.frames_of(from, 0)
    }

    /// Frames of the view (at least [`VIEW_BYTES`]) handed over from `from` on.
    fn view_frames_since(&self, from: Instant) -> Vec<(Instant, u64, Instant)> {
        self.frames_of(from, VIEW_BYTES)
    }

    fn frames_of(&self, from: Instant, least: u64) -> Vec<(Instant, u64, Instant)> {
        let link = self.link.lock().unwrap();
        (0..link.frames.len())
            .filter(|&i| link.frames[i].at >= from && link.frames[i].bytes >= least)
            .map(|i| (link.frames[i].at, link.frames[i].bytes, link.arrived(i)))
            .collect()
    }

    async fn quit(self) -> (End, Tally) {
        self.key('q', KeyKind::Press).await;
        self.done.await.unwrap()
    }
}

/// Bytes below which a frame changed no more than the status line (a turning 80×24 view at 256
/// colours changes over a thousand).
const VIEW_BYTES: u64 = 500;

async fn wait(d: Duration) {
    tokio::time::sleep(d).await;
}

#[tokio::test(start_paused = true)]
async fn frames_are_paced_to_the_link_and_nothing_queues_behind_a_release() {
    // 512 kbit/s, 40 ms: a turning truecolor view at 80×24 is far more than this carries.
    let rate = 64_000.0;
    let run = start(rate, Duration::from_millis(40), ColorLevel::Ansi256);
    wait(Duration::from_secs(1)).await;
    let held = now();
    run.key('d', KeyKind::Press).await;
    wait(Duration::from_secs(4)).await;
    let released = now();
    run.key('d', KeyKind::Release).await;
    wait(Duration::from_secs(2)).await;

    let turning = run.frames_since(held);
    let during: Vec<_> = turning.iter().filter(|f| f.0 < released).collect();
    assert!(during.len() > 10, "frames while turning: {}", during.len());
    // Paced: what was handed over while turning is what the link carried, plus about one
    // frame in flight, never a growing queue.
    let bytes: u64 = during.iter().map(|f| f.1).sum();
    let carried = rate * (released - held).as_secs_f64();
    let biggest = during.iter().map(|f| f.1).max().unwrap();
    assert!(
        (bytes as f64) <= carried + 2.0 * biggest as f64,
        "{bytes} B handed over against {carried:.0} B the link carried"
    );
    for w in during.windows(2) {
        // Each frame was handed over only once the one before had (nearly) arrived.
        assert!(
            w[1].0 + Duration::from_millis(45) >= w[0].2,
            "frame at {:?} went before the one at {:?} arrived ({:?})",
            w[1].0 - held,
            w[0].0 - held,
            w[0].2 - held
        );
    }
    // Nothing queued behind the release: the view stops moving within one frame's trip. (A
    // frame of a few dozen bytes later redraws only the status line's figures, which follow the
    // machine's own clock.)
    let view_frames = run.view_frames_since(held);
    let after: Vec<_> = view_frames.iter().filter(|f| f.0 >= released).collect();
    println!(
        "turning 4 s: {} frames, {bytes} B (the link carried {carried:.0} B); {} view frames after the release",
        during.len(),
        after.len()
    );
    assert!(
        after.len() <= 2,
        "{} view frames after the release",
        after.len()
    );
    let last_arrival = view_frames.iter().map(|f| f.2).max().unwrap();
    assert!(
        last_arrival <= released + Duration::from_millis(300),
        "the view moved until {:?} after the release",
        last_arrival - released
    );
    let (end, tally) = run.quit().await;
    assert_eq!(end, End::Quit);
    assert!(tally.link.max_queued > 0);
}

#[tokio::test(start_paused = true)]
async fn the_level_steps_down_on_a_slow_link_and_back_up_when_it_is_fast_again() {
    let run = start(40_000.0, Duration::from_millis(20), ColorLevel::TrueColor);
    wait(Duration::from_millis(500)).await;
    run.key('d', KeyKind::Press).await;
    wait(Duration::from_secs(6)).await;
    let downs: Vec<_> = run.steps.0.lock().unwrap().clone();
    assert!(
        !downs.is_empty() && downs.iter().all(|(_, down)| *down),
        "steps on a slow link: {downs:?}"
    );
    // The link becomes fast (a quiet network): still turning, the level comes back up.
    run.link.lock().unwrap().rate = 50_000_000.0;
    let fast = now();
    wait(Duration::from_secs(90)).await;
    let steps = run.steps.0.lock().unwrap().clone();
    let ups = steps.iter().filter(|(t, down)| !down && *t >= fast).count();
    println!(
        "level steps (seconds after the link became fast, down?): {:?}",
        steps
            .iter()
            .map(|(t, d)| (t.checked_duration_since(fast).map(|d| d.as_secs_f64()), *d))
            .collect::<Vec<_>>()
    );
    assert_eq!(
        ups,
        downs.len(),
        "every step down is taken back once the link is fast: {steps:?}"
    );
    run.key('d', KeyKind::Release).await;
    let (end, tally) = run.quit().await;
    assert_eq!(end, End::Quit);
    assert_eq!(tally.link.steps_down as usize, downs.len());
    assert_eq!(tally.link.steps_up as usize, downs.len());
}

#[tokio::test(start_paused = true)]
async fn a_transport_that_can_shrink_its_frames_does_so_before_the_level_drops() {
    // 3 Mbit/s: turning truecolor frames at 80×24 (about 33 kB) make 11 a second as they are,
    // 45 at a quarter of their size.
    let rate = 375_000.0;
    let run = start(rate, Duration::from_millis(20), ColorLevel::TrueColor);
    run.link.lock().unwrap().could_shrink = Some(0.25);
    wait(Duration::from_millis(500)).await;
    run.key('d', KeyKind::Press).await;
    wait(Duration::from_secs(3)).await;
    assert!(
        (run.link.lock().unwrap().ratio - 0.25).abs() < 1e-9,
        "shrunk"
    );
    let from = now();
    wait(Duration::from_secs(5)).await;
    let frames = run.view_frames_since(from);
    let fps = frames.len() as f64 / 5.0;
    assert!(fps >= MIN_FPS, "{fps} frames a second while turning");
    run.key('d', KeyKind::Release).await;
    let steps = run.steps.0.lock().unwrap().clone();
    assert!(steps.is_empty(), "the level stayed: {steps:?}");
    let (_, tally) = run.quit().await;
    assert_eq!((tally.link.steps_down, tally.link.steps_up), (0, 0));
}

#[tokio::test(start_paused = true)]
async fn a_level_measured_raw_comes_back_once_its_frames_go_shrunk() {
    // The same link, the frames shrunk only once the level has dropped (a browser's
    // compression starts when the link holds frames back): truecolor's size was measured
    // raw, but its shrunk frames fit, so the level goes back up and stays.
    let run = start(375_000.0, Duration::from_millis(20), ColorLevel::TrueColor);
    wait(Duration::from_millis(500)).await;
    run.key('d', KeyKind::Press).await;
    wait(Duration::from_secs(3)).await;
    let down: Vec<_> = run.steps.0.lock().unwrap().clone();
    assert_eq!(down.iter().map(|(_, d)| *d).collect::<Vec<_>>(), [true]);
    run.link.lock().unwrap().ratio = 0.25;
    // Up once the hold after the step (5 s) is over, not after a further hold of quiet.
    wait(Duration::from_secs(4)).await;
    let up: Vec<_> = run.steps.0.lock().unwrap().clone();
    assert_eq!(
        up.iter().map(|(_, d)| *d).collect::<Vec<_>>(),
        [true, false]
    );
    wait(Duration::from_secs(20)).await;
    let steps: Vec<_> = run.steps.0.lock().unwrap().clone();
    assert_eq!(steps, up, "never down again");
    run.key('d', KeyKind::Release).await;
    run.quit().await;
}

#[tokio::test(start_paused = true)]
async fn a_tap_from_idle_is_drawn_at_once() {
    let run = start(64_000.0, Duration::from_millis(40), ColorLevel::Ansi256);
    // Idle: the first frames are drawn, then the view stays as it is (the status line's
    // figures, which follow the machine's clock, may still change).
    wait(Duration::from_secs(3)).await;
    let idle = now();
    wait(Duration::from_secs(1)).await;
    assert!(
        run.view_frames_since(idle).is_empty(),
        "frames while nothing moved: {:?}",
        run.view_frames_since(idle)
    );
    let tapped = now();
    run.key('d', KeyKind::Press).await;
    // A quick finger: down for 80 ms.
    wait(Duration::from_millis(80)).await;
    run.key('d', KeyKind::Release).await;
    wait(Duration::from_secs(1)).await;
    let frames = run.view_frames_since(tapped);
    assert!(
        !frames.is_empty(),
        "the tap drew nothing: {:?}",
        run.frames_since(tapped)
    );
    // The world applies the tap on its next tick (a 30th of a second); the frame follows it.
    let first = frames[0].0 - tapped;
    println!(
        "a tap from idle: first frame after {first:?}, {} frames",
        frames.len()
    );
    assert!(
        first <= Duration::from_millis(70),
        "first frame {first:?} after the tap"
    );
    assert!(frames.len() <= 3, "a tap drew {} frames", frames.len());
    run.quit().await;
}

/// The turn from `before` to `after`, in degrees, positive to the right.
fn turned(before: f64, after: f64) -> f64 {
    (before - after + 540.0).rem_euclid(360.0) - 180.0
}

/// Starts a browser player (true releases) in a still world, settled.
async fn browser_player() -> Run {
    let run = start(1e9, Duration::from_millis(1), ColorLevel::TrueColor);
    wait(Duration::from_secs(1)).await;
    run
}

#[tokio::test(start_paused = true)]
async fn taps_shorter_than_a_tick_each_turn_exactly_one_tap() {
    let run = browser_player().await;
    let tick = Duration::from_secs(1) / 30;
    // Every length under a tick, at every phase against the world's ticks.
    for down_ms in [0, 5, 10, 20, 30] {
        for phase_ms in [0, 7, 14, 21, 28] {
            wait(Duration::from_millis(phase_ms)).await;
            let before = run.angle();
            run.key('d', KeyKind::Press).await;
            wait(Duration::from_millis(down_ms)).await;
            run.key('d', KeyKind::Release).await;
            wait(tick * 4).await;
            let t = turned(before, run.angle());
            assert!(
                (t - TAP_TURN_DEG).abs() < 1e-6,
                "a {down_ms} ms tap at phase {phase_ms} ms turned {t}°"
            );
        }
    }
    run.quit().await;
}

#[tokio::test(start_paused = true)]
async fn press_and_release_bunched_by_the_link_are_each_a_tap() {
    let run = browser_player().await;
    let before = run.angle();
    use KeyKind::{Press, Release};
    run.keys(&[('d', Press), ('d', Release), ('d', Press), ('d', Release)])
        .await;
    run.keys(&[('a', Press), ('a', Release), ('d', Press), ('d', Release)])
        .await;
    wait(Duration::from_millis(200)).await;
    let t = turned(before, run.angle());
    assert!(
        (t - 2.0 * TAP_TURN_DEG).abs() < 1e-6,
        "turned {t}°, not two taps"
    );
    run.quit().await;
}

#[tokio::test(start_paused = true)]
async fn a_hold_turns_by_the_time_held_and_no_more() {
    let run = browser_player().await;
    let per_second = crate::game::TURN_SPEED.to_degrees();
    for held_ms in [40u64, 100, 500, 1000] {
        let before = run.angle();
        run.key('d', KeyKind::Press).await;
        wait(Duration::from_millis(held_ms)).await;
        run.key('d', KeyKind::Release).await;
        wait(Duration::from_millis(200)).await;
        let t = turned(before, run.angle());
        // The world turns on whole ticks: the time held within one tick's turn, and never less
        // than a tap.
        let expected = (per_second * held_ms as f64 / 1000.0).max(TAP_TURN_DEG);
        let tick = per_second / 30.0;
        assert!(
            (t - expected).abs() <= tick + 1e-6,
            "held {held_ms} ms: turned {t:.2}°, expected {expected:.2}° ± {tick:.2}°"
        );
    }
    run.quit().await;
}
