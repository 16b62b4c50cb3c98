//! Showing a recorded run on screen: the replay player's frames, paced by the recorded fps.

use std::io;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEventKind, KeyModifiers};

use super::app::Ending;
use super::events::Events;
use super::terminal::Session;
use crate::encode::EncodeOptions;
use crate::present::Presenter;
use crate::replay::player::Player;
use crate::replay::Replay;
use crate::world::World;

/// Whether a key asks to stop watching.
fn stops(ev: &Event) -> bool {
    matches!(ev, Event::Key(k) if k.kind != KeyEventKind::Release
        && (matches!(k.code, KeyCode::Char('q' | 'Q') | KeyCode::Esc)
            || (k.code == KeyCode::Char('c') && k.modifiers.contains(KeyModifiers::CONTROL))))
}

/// Plays every frame of `replay` at 1/fps intervals; the simulation never reads the clock.
///
/// # Errors
/// Terminal I/O failures.
pub fn run(
    session: &mut Session,
    world: Arc<World>,
    replay: &Replay,
    encode: EncodeOptions,
    signal: &Arc<AtomicUsize>,
) -> io::Result<Ending> {
    let mut player = Player::new(world, &replay.header);
    let mut presenter = Presenter::new(encode);
    let period = Duration::from_secs_f64(1.0 / f64::from(replay.header.fps));
    let events = Events::spawn()?;
    let mut next = Instant::now();
    for input in &replay.frames {
        loop {
            let now = Instant::now();
            if now >= next {
                break;
            }
            if events.next_within(next - now)?.is_some_and(|ev| stops(&ev)) {
                return Ok(Ending::Quit);
            }
            let sig = signal.load(Ordering::SeqCst);
            if sig != 0 {
                return Ok(Ending::Signal(sig as i32));
            }
        }
        next += period;
        let Some(frame) = player.play(input) else {
            break;
        };
        let bytes = presenter.frame(&frame.screen, &frame.view, frame.view_area);
        if let Err(e) = session.write_frame(bytes) {
            let sig = signal.load(Ordering::SeqCst);
            if sig != 0 {
                return Ok(Ending::Signal(sig as i32));
            }
            return Err(e);
        }
    }
    Ok(Ending::Quit)
}
