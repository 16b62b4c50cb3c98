//! The game loop: input → step → render → draw, paced to a target frame rate.

use std::io;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use crossterm::event;
use ratatui::layout::Rect;

use super::keys::{Controls, UiCommand};
use super::layout::{Panes, Toggles};
use super::render::render_view;
use super::screen::{draw, Screen};
use super::stats::FrameStats;
use super::terminal::Session;
use crate::framebuffer::Framebuffer;
use crate::game::{step, GameState};

/// How a play session ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// The player quit.
    Quit,
    /// A signal (SIGTERM, SIGHUP, …) asked us to stop; its number.
    Signal(i32),
}

/// The loop's mutable parts that are not game state.
struct App {
    state: GameState,
    controls: Controls,
    toggles: Toggles,
    stats: FrameStats,
    fb: Framebuffer,
}

/// Runs frames until quit or a signal; `signal` holds the number of a caught signal (0 = none).
///
/// # Errors
/// Terminal I/O failures (reading events, writing frames).
pub fn run_loop(
    session: &mut Session,
    state: GameState,
    fps: u32,
    signal: &Arc<AtomicUsize>,
) -> io::Result<(Ending, FrameStats)> {
    let mut app = App {
        state,
        controls: Controls::new(session.input_mode()),
        toggles: Toggles::default(),
        stats: FrameStats::default(),
        fb: Framebuffer::new(0, 0),
    };
    let period = Duration::from_secs_f64(1.0 / f64::from(fps.max(1)));
    let mut last = Instant::now();
    let mut next = last;
    loop {
        // 1. Input: take events until this frame is due (blocking in poll, never spinning).
        loop {
            let now = Instant::now();
            if now >= next {
                break;
            }
            if event::poll(next - now)? {
                let ev = event::read()?;
                app.controls.handle(&ev, Instant::now());
            }
            if signal.load(Ordering::SeqCst) != 0 {
                break;
            }
        }
        let sig = signal.load(Ordering::SeqCst);
        if sig != 0 {
            return Ok((Ending::Signal(sig as i32), app.stats));
        }
        if app.ui_commands() {
            return Ok((Ending::Quit, app.stats));
        }
        let now = Instant::now();
        let dt = now.duration_since(last).as_secs_f64();
        last = now;
        next += period;
        if next < now {
            next = now + period;
        }

        // 2. Step: the layout decides the view width the debugger works in.
        let size = session.size()?;
        let area = Rect::new(0, 0, size.width, size.height);
        let panes = Panes::compute(area, app.toggles);
        let view = match panes {
            Panes::Game { view, .. } => view,
            Panes::TooSmall(_) => Rect::default(),
        };
        app.state.view_width = usize::from(view.width);
        if view.width > 0 {
            let fov = app.state.camera.fov_deg().to_radians();
            app.controls
                .set_turn_per_column(fov / f64::from(view.width));
        }
        let input = app.controls.take_input(now);
        step(&mut app.state, &input, dt);

        // 3. Render the 3D view at exactly the pane's size.
        let t = Instant::now();
        app.fb
            .resize(usize::from(view.width), usize::from(view.height) * 2);
        let cast = render_view(&app.state, &mut app.fb);
        let render_time = t.elapsed();

        // 4. Draw the terminal frame.
        let t = Instant::now();
        let screen = Screen {
            state: &app.state,
            view: &app.fb,
            cast: &cast,
            stats: &app.stats,
            toggles: app.toggles,
            input_mode: app.controls.mode(),
        };
        session.draw(|frame| {
            let area = frame.area();
            draw(&screen, &panes, area, frame.buffer_mut());
        })?;
        let draw_time = t.elapsed();
        app.stats.record(Instant::now(), render_time, draw_time);
        // Lets the end-to-end tests prove the panic hook restores the terminal (debug builds only).
        #[cfg(debug_assertions)]
        if std::env::var_os("HALFCAST_TEST_PANIC").is_some() {
            panic!("HALFCAST_TEST_PANIC is set");
        }
    }
}

impl App {
    /// Applies UI commands; true when the player asked to quit.
    fn ui_commands(&mut self) -> bool {
        for c in self.controls.take_ui() {
            match c {
                UiCommand::Quit => return true,
                UiCommand::Back if self.toggles.help => self.toggles.help = false,
                UiCommand::Back => return true,
                UiCommand::ToggleMinimap => self.toggles.minimap = !self.toggles.minimap,
                UiCommand::ToggleDebug => self.toggles.debug = !self.toggles.debug,
                UiCommand::ToggleHelp => self.toggles.help = !self.toggles.help,
            }
        }
        false
    }
}
