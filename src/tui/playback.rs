//! Showing a recorded run on screen: the replay player's frames, paced by the recorded fps.
//!
//! Frames keep the size they were recorded at. In a larger terminal they are centred; in a
//! smaller one the replay waits, showing what size it needs, until the terminal is enlarged
//! (or q quits) — never a frame cut into pieces.

use std::io;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEventKind, KeyModifiers};

use super::app::Ending;
use super::events::Events;
use super::terminal::Session;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::{Paragraph, Widget, Wrap};

use crate::encode::EncodeOptions;
use crate::present::Presenter;
use crate::render::framebuffer::Framebuffer;
use crate::replay::Replay;
use crate::ui::replay_player::Player;
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
    let mut inputs = replay.frames.iter();
    let mut pending = None;
    loop {
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
        if pending.is_none() {
            pending = match inputs.next() {
                Some(input) => player.play(input),
                None => None,
            };
        }
        let Some(frame) = &pending else {
            break;
        };
        let size = session.size()?;
        let terminal = Rect::new(0, 0, size.width, size.height);
        let placed = fit(&frame.screen, frame.view_area, terminal);
        let bytes = match &placed {
            Some((screen, view_area)) => presenter.frame(screen, &frame.view, *view_area),
            // The frame stays pending: the replay waits for a terminal it fits in.
            None => {
                let note = too_small(frame.screen.area, terminal);
                presenter.frame(&note, &Framebuffer::new(0, 0), Rect::default())
            }
        };
        if placed.is_some() {
            pending = None;
        }
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

/// A recorded `screen` centred in a `terminal`-sized buffer, and where its view lands; `None`
/// when the terminal is smaller than the recording.
#[must_use]
pub fn fit(screen: &Buffer, view_area: Rect, terminal: Rect) -> Option<(Buffer, Rect)> {
    let rec = screen.area;
    if terminal.width < rec.width || terminal.height < rec.height {
        return None;
    }
    if terminal == rec {
        return Some((screen.clone(), view_area));
    }
    let (dx, dy) = (
        (terminal.width - rec.width) / 2,
        (terminal.height - rec.height) / 2,
    );
    let mut out = Buffer::empty(terminal);
    for y in 0..rec.height {
        for x in 0..rec.width {
            out[(x + dx, y + dy)] = screen[(rec.x + x, rec.y + y)].clone();
        }
    }
    let view = Rect::new(
        view_area.x + dx,
        view_area.y + dy,
        view_area.width,
        view_area.height,
    );
    Some((out, view))
}

/// What a terminal too small for the recording shows instead of it.
fn too_small(recorded: Rect, terminal: Rect) -> Buffer {
    let mut b = Buffer::empty(terminal);
    let text = format!(
        "this recording is {}x{}; the terminal is {}x{}. Enlarge it to watch (q quits).",
        recorded.width, recorded.height, terminal.width, terminal.height
    );
    let y = terminal.height / 2;
    Paragraph::new(text)
        .wrap(Wrap { trim: true })
        .centered()
        .render(Rect::new(0, y, terminal.width, terminal.height - y), &mut b);
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_larger_terminal_centres_the_frame_and_a_smaller_one_refuses() {
        let mut rec = Buffer::empty(Rect::new(0, 0, 10, 4));
        rec.set_string(0, 0, "corner", ratatui::style::Style::new());
        let view = Rect::new(0, 1, 10, 3);
        let (big, at) = fit(&rec, view, Rect::new(0, 0, 20, 10)).unwrap();
        assert_eq!(big.area, Rect::new(0, 0, 20, 10));
        assert_eq!(at, Rect::new(5, 4, 10, 3));
        assert_eq!(big[(5, 3)].symbol(), "c");
        assert_eq!(big[(0, 0)].symbol(), " ");
        assert!(fit(&rec, view, Rect::new(0, 0, 9, 10)).is_none());
        assert!(fit(&rec, view, Rect::new(0, 0, 20, 3)).is_none());
        assert_eq!(fit(&rec, view, rec.area).unwrap(), (rec.clone(), view));
        let note = too_small(rec.area, Rect::new(0, 0, 40, 6));
        let text: String = note.content.iter().map(|c| c.symbol()).collect();
        assert!(text.contains("this recording is 10x4"), "{text}");
    }
}
