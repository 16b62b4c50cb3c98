//! The game loop: input → step → render → draw, paced to a target frame rate.

use std::cell::RefCell;
use std::io;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

use super::events::Events;
use super::terminal::Session;
use crate::encode::{ColourChoice, ColourReason, EncodeOptions, Pacer};
use crate::game::{step, Command, GameState, Input};
use crate::present::Presenter;
use crate::render::framebuffer::Framebuffer;
use crate::render::kept_background::KeptBackground;
use crate::replay::FrameInput;
use crate::ui::frame_grid::FrameGrid;
use crate::ui::glyph_cycle::GlyphCycle;
use crate::ui::keys::{Controls, UiCommand};
use crate::ui::layout::{Panes, Toggles, COMPACT_MIN_WIDTH};
use crate::ui::notice::Notice;
use crate::ui::render::render_view_kept;
use crate::ui::results::{Results, Then};
use crate::ui::screen::{draw_for_presenter, draw_notice, KeptLines, Screen};
use crate::ui::stats::FrameStats;

/// How a play session ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// The player quit.
    Quit,
    /// A signal (SIGTERM, SIGHUP, …) asked us to stop; its number.
    Signal(i32),
}

/// How the loop paces and encodes frames, and whether it records its input.
#[derive(Debug, Clone, Copy)]
pub struct LoopOptions {
    /// Target frames per second.
    pub fps: u32,
    /// Colour level and the lossy delta for the terminal encoder.
    pub encode: EncodeOptions,
    /// Bandwidth cap in bits per second: the frame rate drops to fit.
    pub max_bandwidth: Option<u64>,
    /// With `min_fps`, drop a colour level when the cap cannot sustain this frame rate.
    pub adapt_colours: bool,
    /// Record each frame's input (then every step is exactly 1/fps seconds long).
    pub record: bool,
    /// Why `encode.level` is what it is (shown in the status line).
    pub colour_reason: ColourReason,
}

/// Frame-by-frame input captured while playing, for a `.hcr` replay; it stops after
/// [`crate::replay::LONGEST_RECORDING_SECS`] of game time (the game goes on unrecorded).
#[derive(Debug, Clone, Default)]
pub struct Recording {
    /// Terminal size at the first frame.
    pub size: (u16, u16),
    pub frames: Vec<FrameInput>,
}

/// The levels a game plays in order, and the seed their creatures start from.
#[derive(Debug, Clone)]
pub struct Campaign {
    /// At least one level.
    pub stages: Vec<super::Stage>,
    /// Level `i` plays with seed `seed + i`.
    pub seed: u64,
}

impl Campaign {
    /// A fresh game state at the start of level `i`.
    fn start(&self, i: usize, speeds: crate::game::Speeds) -> GameState {
        let stage = &self.stages[i];
        let mut state = GameState::with_seed(
            Arc::clone(&stage.world),
            stage.camera,
            0,
            self.seed.wrapping_add(i as u64),
        );
        state.speeds = speeds;
        state
    }

    /// The results of level `i` as `state` finished it.
    fn results(&self, i: usize, state: &GameState) -> Results {
        let then = match self.stages.get(i + 1) {
            Some(next) => Then::Level(next.name.clone()),
            None => Then::Again,
        };
        Results::of(&self.stages[i].name, state, then)
    }
}

/// Frame rate below which an adapting bandwidth cap lowers the colour level.
const MIN_ADAPT_FPS: f64 = 12.0;

/// The loop's mutable parts that are not game state.
struct App {
    state: GameState,
    campaign: Campaign,
    /// The level being played (index into the campaign).
    stage: usize,
    /// The results screen, once this level's exit is reached.
    results: Option<Results>,
    controls: Controls,
    toggles: Toggles,
    stats: FrameStats,
    fb: Framebuffer,
    presenter: Presenter,
    /// The ray pane's lines, kept from frame to frame.
    ray_text: RefCell<KeptLines>,
    /// The view's walls, floors and ceilings, kept from frame to frame.
    background: KeptBackground,
    pacer: Option<Pacer>,
    recording: Option<Recording>,
    /// Whether frames are still being recorded (a recording ends at the level's exit).
    recording_open: bool,
    last_size: Option<(u16, u16)>,
    keys: crate::ui::keymap::KeyMap,
    /// A note for the status line (a pane hidden for lack of room, a figure written).
    notice: Notice,
    /// The wanted panes that did not fit last frame, to notice a change.
    hidden: Vec<&'static str>,
    /// The glyph key's cycle here (without octant inside tmux, unless asked for).
    glyph_cycle: GlyphCycle,
    /// When the next frame is due.
    grid: FrameGrid,
}

/// Most keys taken between two frames once the frame is already due (the input queue's size).
const LATE_KEYS: usize = 256;

/// Runs frames until quit or a signal; `signal` holds the number of a caught signal (0 = none).
///
/// # Errors
/// Terminal I/O failures (reading events, writing frames).
pub fn run_loop(
    session: &mut Session,
    campaign: Campaign,
    options: LoopOptions,
    setup: &super::Setup,
    early_keys: Vec<crossterm::event::Event>,
    signal: &Arc<AtomicUsize>,
) -> io::Result<(Ending, FrameStats, Option<Recording>)> {
    let fps = f64::from(options.fps.max(1));
    let mut app = App::new(campaign, &options, setup, session);
    // Keys typed while the start-up colour query ran come first.
    let now = Instant::now();
    for ev in &early_keys {
        app.controls.handle(ev, now);
    }
    let period = Duration::from_secs_f64(1.0 / fps);
    let events = Events::spawn()?;
    let mut last = Instant::now();
    loop {
        // 1. Input: take events until this frame is due.
        app.take_events(&events, signal)?;
        if let Some(sig) = caught(signal) {
            return Ok((Ending::Signal(sig), app.stats, app.recording));
        }
        let ui = app.take_ui();
        if app.ui_commands(&ui) {
            return Ok((Ending::Quit, app.stats, app.recording));
        }
        let now = Instant::now();
        // Recording steps exactly 1/fps per frame, so the replay is the same run.
        let dt = if app.recording.is_some() {
            1.0 / fps
        } else {
            now.duration_since(last).as_secs_f64()
        };
        last = now;
        let interval = app
            .pacer
            .as_ref()
            .map_or(period, |p| p.frame_interval().max(period));
        app.grid.set_period(interval);
        app.grid.drawn(now);

        // 2. Step: the layout decides the view width the debugger works in.
        let size = session.size()?;
        let (panes, view) = app.lay_out(size, &ui, now);
        app.save_figure(&ui, view, now);
        let input = app.controls.take_input(now);
        app.record(&input, ui, (size.width, size.height), options.fps);
        app.advance(&input, view, dt);

        // 3. Render the view and draw the panes; 4. encode and write the frame once.
        let sent = match app.draw(session, size, panes, view, now) {
            Ok(sent) => sent,
            // A full terminal gave way to a signal: end like any signalled frame.
            Err(_) if caught(signal).is_some() => {
                let sig = caught(signal).unwrap_or_default();
                return Ok((Ending::Signal(sig), app.stats, app.recording));
            }
            Err(e) => return Err(e),
        };
        app.adapt(&options, fps, sent);
        // Lets the end-to-end tests prove the panic hook restores the terminal (debug builds only).
        #[cfg(debug_assertions)]
        if std::env::var_os("HALFCAST_TEST_PANIC").is_some() {
            panic!("HALFCAST_TEST_PANIC is set");
        }
    }
}

/// The signal caught, if any.
fn caught(signal: &Arc<AtomicUsize>) -> Option<i32> {
    match signal.load(Ordering::SeqCst) {
        0 => None,
        sig => Some(sig as i32),
    }
}

impl App {
    fn new(
        campaign: Campaign,
        options: &LoopOptions,
        setup: &super::Setup,
        session: &Session,
    ) -> Self {
        let fps = f64::from(options.fps.max(1));
        let state = campaign.start(0, setup.speeds);
        let mut controls = Controls::new(session.input_mode());
        controls.set_keymap(setup.keys.clone());
        controls.set_speeds(state.speeds);
        let mut stats = FrameStats::default();
        stats.level = Some(ColourChoice {
            level: options.encode.level,
            reason: options.colour_reason,
        });
        stats.glyphs = setup.glyphs;
        App {
            state,
            campaign,
            stage: 0,
            results: None,
            controls,
            toggles: setup.toggles,
            stats,
            fb: Framebuffer::new(0, 0),
            presenter: Presenter::new(options.encode),
            ray_text: RefCell::default(),
            background: KeptBackground::default(),
            pacer: options.max_bandwidth.map(|bits| Pacer::new(bits, fps)),
            recording: options.record.then(Recording::default),
            recording_open: true,
            last_size: None,
            keys: setup.keys.clone(),
            notice: Notice::default(),
            hidden: Vec::new(),
            glyph_cycle: GlyphCycle::new(
                super::octant_dropper_here(),
                setup.glyphs,
                "--glyphs octant forces",
            ),
            grid: FrameGrid::new(options.fps),
        }
    }

    /// Takes events until the next frame is due (blocking in poll, never spinning). A frame
    /// that took longer than the period leaves no time to wait: the keys already typed are
    /// still taken (up to the queue's size), so a slow machine lags but never drops keys.
    fn take_events(&mut self, events: &Events, signal: &Arc<AtomicUsize>) -> io::Result<()> {
        let mut late = 0;
        loop {
            let now = Instant::now();
            let wait = self
                .grid
                .wait_until(now)
                .map_or(Duration::ZERO, |t| t - now);
            match events.next_within(wait)? {
                Some(ev) => self.controls.handle(&ev, Instant::now()),
                None => return Ok(()),
            }
            if wait.is_zero() {
                late += 1;
                if late >= LATE_KEYS {
                    return Ok(());
                }
            }
            if caught(signal).is_some() {
                return Ok(());
            }
        }
    }

    /// The UI commands since the last frame; the glyph key becomes the setting it leads to
    /// here, which is what gets recorded.
    fn take_ui(&mut self) -> Vec<UiCommand> {
        let mut ui = self.controls.take_ui();
        if let Some(note) = self.glyph_cycle.resolve(&mut ui, self.stats.glyphs) {
            self.notice.show(note, Instant::now());
        }
        ui
    }

    /// Lays the panes out for `size`: says when a wanted pane has no room, and sets the view
    /// width the game and the turn keys work in.
    fn lay_out(
        &mut self,
        size: ratatui::layout::Size,
        ui: &[UiCommand],
        now: Instant,
    ) -> (Panes, Rect) {
        let area = Rect::new(0, 0, size.width, size.height);
        let panes = Panes::compute(area, self.toggles);
        let hidden = panes.hidden(self.toggles);
        let asked = ui
            .iter()
            .any(|u| matches!(u, UiCommand::ToggleMinimap | UiCommand::ToggleDebug));
        if (asked || hidden != self.hidden) && !hidden.is_empty() {
            let need = if size.width < COMPACT_MIN_WIDTH {
                format!("needs {COMPACT_MIN_WIDTH} columns")
            } else {
                "needs more rows".to_string()
            };
            let text = format!(
                "{} hidden: no room at {}x{} ({need})",
                hidden.join(" and "),
                size.width,
                size.height
            );
            self.notice.show(text, now);
        }
        self.hidden = hidden;
        let view = match panes {
            Panes::Game { view, .. } => view,
            Panes::TooSmall(_) => Rect::default(),
        };
        self.state.view_width = usize::from(view.width);
        if view.width > 0 {
            let fov = self.state.camera.fov_deg().to_radians();
            self.controls
                .set_turn_per_column(fov / f64::from(view.width));
        }
        (panes, view)
    }

    /// Writes the debugged column's ray as a figure when the figure key was pressed.
    fn save_figure(&mut self, ui: &[UiCommand], view: Rect, now: Instant) {
        if !ui.contains(&UiCommand::SaveFigure) || view.width == 0 {
            return;
        }
        let text = match super::figure_key::write_figure(
            &self.state,
            (view.width, view.height),
            std::path::Path::new("."),
        ) {
            Ok(path) => format!(
                "figure of column {} written to {}",
                self.state.debug_column(),
                path.display()
            ),
            Err(e) => format!("figure not written: {e}"),
        };
        self.notice.show(text, now);
    }

    /// Adds this frame's input to the recording while it is open.
    fn record(&mut self, input: &Input, ui: Vec<UiCommand>, size: (u16, u16), fps: u32) {
        if self.results.is_some() {
            // A recording is one level: it ends at the exit.
            self.recording_open = false;
        }
        if let Some(rec) = self.recording.as_mut().filter(|_| self.recording_open) {
            let resize = match self.last_size {
                None => {
                    rec.size = size;
                    None
                }
                Some(prev) if prev != size => Some(size),
                Some(_) => None,
            };
            rec.frames.push(FrameInput {
                input: input.clone(),
                ui,
                resize,
            });
            // An hour at most, so every recording replays within the default `--max-frames`
            // and a game left running does not grow the recording without bound.
            if rec.frames.len() >= crate::replay::default_max_frames(fps) {
                self.recording_open = false;
            }
        }
        self.last_size = Some(size);
    }

    /// Moves on from the results screen when asked, and steps the game by `dt` seconds.
    fn advance(&mut self, input: &Input, view: Rect, dt: f64) {
        // Enter (the run-to-hit key) on the results screen: the next level, or the last one
        // again (as the results screen says).
        if self.results.is_some() && input.commands.contains(&Command::RunToHit) {
            if self.stage + 1 < self.campaign.stages.len() {
                self.stage += 1;
            }
            self.state = self.campaign.start(self.stage, self.state.speeds);
            self.background.forget();
            self.state.view_width = usize::from(view.width);
            self.results = None;
        }
        if self.results.is_none() {
            step(&mut self.state, input, dt);
            if self.state.level.finished().is_some() {
                self.results = Some(self.campaign.results(self.stage, &self.state));
            }
        }
        self.controls.set_paused(self.state.debugger.paused);
    }

    /// Renders the 3D view at exactly the pane's size, draws the panes, and writes the frame;
    /// returns its bytes.
    fn draw(
        &mut self,
        session: &mut Session,
        size: ratatui::layout::Size,
        panes: Panes,
        view: Rect,
        now: Instant,
    ) -> io::Result<usize> {
        let t = Instant::now();
        // Mono is ASCII shades: it draws half-blocks' worth whatever the setting.
        let glyphs = if self.presenter.level() == crate::encode::ColorLevel::Mono {
            crate::render::glyphs::Glyphs::Half
        } else {
            self.stats.glyphs
        };
        self.fb.resize_cells(view.width, view.height, glyphs);
        self.fb.set_phases_wanted(self.presenter.level().mixes());
        let cast = render_view_kept(&self.state, &mut self.fb, &mut self.background);
        let render_time = t.elapsed();
        let t = Instant::now();
        let area = Rect::new(0, 0, size.width, size.height);
        let screen = Screen {
            state: &self.state,
            view: &self.fb,
            cast: &cast,
            stats: &self.stats,
            toggles: self.toggles,
            input_mode: self.controls.mode(),
            results: self.results.as_ref(),
            ray_text: Some(&self.ray_text),
        };
        let mut buf = Buffer::empty(area);
        draw_for_presenter(&screen, &panes, area, &mut buf, &self.keys);
        if let (Some(text), Panes::Game { status, .. }) = (self.notice.at(now), panes) {
            draw_notice(text, status, &mut buf);
        }
        let bytes = self.presenter.frame_taking(&mut buf, &self.fb, view);
        session.write_frame(bytes)?;
        let sent = bytes.len();
        let draw_time = t.elapsed();
        self.stats.record_bytes(sent);
        self.stats.record(Instant::now(), render_time, draw_time);
        Ok(sent)
    }

    /// Under a bandwidth cap: records the frame's size, and lowers the colour level when the
    /// cap cannot carry the least frame rate at this one.
    fn adapt(&mut self, options: &LoopOptions, fps: f64, sent: usize) {
        let Some(p) = self.pacer.as_mut() else {
            return;
        };
        p.record(sent);
        let level = self.presenter.level();
        let lower = p.level_for(level, MIN_ADAPT_FPS);
        if options.adapt_colours && lower != level {
            self.presenter.set_level(lower);
            self.stats.level = Some(ColourChoice {
                level: lower,
                reason: ColourReason::Bandwidth,
            });
            *p = Pacer::new(options.max_bandwidth.unwrap_or(u64::MAX), fps);
        }
    }
}

impl App {
    /// The level frames are sent at now, and why.
    fn presenter_choice(&self) -> ColourChoice {
        self.stats.level.unwrap_or(ColourChoice {
            level: self.presenter.level(),
            reason: ColourReason::Key,
        })
    }

    /// Applies UI commands; true when the player asked to quit.
    fn ui_commands(&mut self, ui: &[UiCommand]) -> bool {
        for &c in ui {
            match c {
                UiCommand::Quit => return true,
                UiCommand::Back if self.toggles.help => self.toggles.help = false,
                UiCommand::Back => return true,
                UiCommand::ToggleMinimap => self.toggles.minimap = !self.toggles.minimap,
                UiCommand::ToggleDebug => self.toggles.debug = !self.toggles.debug,
                UiCommand::ToggleHelp => self.toggles.help = !self.toggles.help,
                UiCommand::CycleColours => {
                    let next = self.presenter_choice().cycled();
                    self.presenter.set_level(next.level);
                    self.stats.level = Some(next);
                }
                UiCommand::SetGlyphs(g) => self.stats.glyphs = g,
                // Resolved into `SetGlyphs` by the glyph cycle before it gets here.
                UiCommand::CycleGlyphs => self.stats.glyphs = self.stats.glyphs.cycled(),
                // Needs the view's size: written once the frame is laid out.
                UiCommand::SaveFigure => {}
            }
        }
        false
    }
}
