//! One session's screen: a header row (who you are, who is here), then exactly the local TUI's
//! panes — the 3D view, minimap, ray debugger pane and status line — drawn by `ui::screen`
//! and put on the wire by the same `Presenter` (ratatui's diff for the panes, the byte-lean
//! encoder for the view).

use std::cell::RefCell;
use std::sync::Arc;
use std::time::Instant;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;
use ratatui::widgets::{Block, Paragraph, Widget, Wrap};

use super::avatars;
use crate::encode::{ColorLevel, ColourChoice, ColourReason, EncodeOptions, SYNC_BEGIN, SYNC_END};
use crate::game::multi::players::{PlayerId, Snapshot};
use crate::game::multi::round::RoundEnd;
use crate::present::Presenter;
use crate::render::framebuffer::Framebuffer;
use crate::render::glyphs::Glyphs;
use crate::render::kept_background::KeptBackground;
use crate::ui::keymap::KeyMap;
use crate::ui::keys::InputMode;
use crate::ui::layout::{Panes, Toggles};
use crate::ui::notice::Notice;
use crate::ui::render::render_view_kept;
use crate::ui::results::{Board, Results, Then};
use crate::ui::screen::{draw_for_presenter, draw_notice, Screen};
use crate::ui::stats::FrameStats;
use crate::ui::status::BAR;
use crate::widget::KeptLines;
use crate::world::World;

/// Rows above the TUI's panes: the header.
pub const HEADER_ROWS: u16 = 1;

/// Everything one session keeps between frames to draw its screen.
#[derive(Debug)]
pub struct SessionScreen {
    /// This session's copy of the served world; its sprites after `base_sprites` are the
    /// other players, replaced every frame.
    world: Arc<World>,
    /// The world it is a copy of (a new one comes with the next map of a rotation).
    source: Option<Arc<World>>,
    /// The leaderboard for the results, and whether it shows over the game too (`L`).
    leaders: Option<Board>,
    show_leaders: bool,
    /// The last frame's (render, draw and encode) times.
    times: (std::time::Duration, std::time::Duration),
    base_sprites: usize,
    avatar_sheet: usize,
    presenter: Presenter,
    /// The ray pane's lines, kept from frame to frame.
    ray_text: RefCell<KeptLines>,
    /// The view's walls, floors and ceilings, kept from frame to frame.
    background: KeptBackground,
    fb: Framebuffer,
    stats: FrameStats,
    /// The frame's bytes: the presenter's, plus other players' name tags over the view.
    out: Vec<u8>,
    /// The screen buffer the panes are drawn into, cleared and reused every frame.
    buf: Buffer,
    /// Which panes this client shows (M, I and ? toggle them, as in the local TUI).
    pub toggles: Toggles,
    /// This client's block characters (U cycles them; each session its own).
    glyphs: Glyphs,
    /// A note over the status line.
    pub notice: Notice,
}

/// Where a terminal of `size` puts the 3D view, below the header.
#[must_use]
pub fn panes_for(size: (u16, u16), toggles: Toggles) -> Panes {
    let (cols, rows) = size;
    let body = Rect::new(
        0,
        HEADER_ROWS.min(rows),
        cols,
        rows.saturating_sub(HEADER_ROWS),
    );
    Panes::compute(body, toggles)
}

/// The 3D view's rectangle for `panes` (empty when the terminal is too small).
#[must_use]
pub fn view_rect(panes: &Panes) -> Rect {
    match *panes {
        Panes::Game { view, .. } => view,
        Panes::TooSmall(_) => Rect::default(),
    }
}

/// Whether a presenter's frame changes nothing on the terminal (only the synchronized update's
/// markers around nothing): such a frame is not sent at all.
fn is_unchanged(bytes: &[u8]) -> bool {
    bytes.is_empty()
        || bytes.len() == SYNC_BEGIN.len() + SYNC_END.len()
            && bytes.starts_with(SYNC_BEGIN)
            && bytes.ends_with(SYNC_END)
}

/// A finished round as the results screen shows it.
fn round_results(
    state: &crate::game::GameState,
    end: &RoundEnd,
    leaders: Option<&Board>,
) -> Results {
    Results {
        level: state.world.map.name.clone(),
        seconds: end.seconds,
        points: end.points,
        treasures: end.treasures,
        then: Then::NewRound {
            seconds: end.left.max(0.0).ceil() as u64,
            map: end.next_map.clone(),
        },
        leaders: leaders.cloned(),
        by: end.by.clone(),
        board: end
            .board
            .iter()
            .map(|r| (r.name.clone(), r.figure.clone()))
            .collect(),
    }
}

impl SessionScreen {
    /// A screen over `world` (the served world, with the avatar sheet at `avatar_sheet`).
    #[must_use]
    pub fn new(world: &World, avatar_sheet: usize, level: ColorLevel) -> Self {
        let mut stats = FrameStats::default();
        stats.level = Some(ColourChoice {
            level,
            reason: ColourReason::Term,
        });
        Self {
            base_sprites: world.sprites.len(),
            world: Arc::new(world.clone()),
            source: None,
            leaders: None,
            show_leaders: false,
            times: Default::default(),
            avatar_sheet,
            presenter: Presenter::new(EncodeOptions::new(level)),
            ray_text: RefCell::default(),
            background: KeptBackground::default(),
            fb: Framebuffer::new(0, 0),
            stats,
            out: Vec::new(),
            buf: Buffer::empty(Rect::default()),
            toggles: Toggles::default(),
            glyphs: Glyphs::Half,
            notice: Notice::default(),
        }
    }

    /// The block characters this client's view is drawn with.
    #[must_use]
    pub fn glyphs(&self) -> Glyphs {
        self.glyphs
    }

    /// Switches block characters; the next frame redraws the view.
    pub fn set_glyphs(&mut self, glyphs: Glyphs) {
        self.glyphs = glyphs;
        self.stats.glyphs = glyphs;
    }

    /// The map served.
    #[must_use]
    pub fn map(&self) -> &crate::map::Map {
        &self.world.map
    }

    /// The leaderboard to show on the results, and over the game when `over_game`.
    pub fn set_leaders(&mut self, board: Option<Board>, over_game: bool) {
        self.leaders = board;
        self.show_leaders = over_game;
    }

    /// How long the last frame took to render, and to draw and encode.
    #[must_use]
    pub fn last_times(&self) -> (std::time::Duration, std::time::Duration) {
        self.times
    }

    /// Switches to `world` when the round plays another map than the one drawn so far.
    fn follow(&mut self, world: &Arc<World>) {
        if self.source.as_ref().is_some_and(|w| Arc::ptr_eq(w, world)) {
            return;
        }
        if self.source.is_some() || world.map.file != self.world.map.file {
            let (copy, sheet) = avatars::with_avatar_sheet(World::clone(world));
            self.base_sprites = copy.sprites.len();
            self.avatar_sheet = sheet;
            self.world = Arc::new(copy);
            // Another world: its walls are not the kept ones.
            self.background.forget();
        }
        self.source = Some(Arc::clone(world));
    }

    /// Switches colour level, keeping why it was chosen (for the status line and header).
    pub fn set_colour(&mut self, choice: ColourChoice) {
        self.presenter.set_level(choice.level);
        self.stats.level = Some(choice);
    }

    /// The colour level frames are sent at, and why.
    #[must_use]
    pub fn colour(&self) -> ColourChoice {
        self.stats.level.unwrap_or(ColourChoice {
            level: self.presenter.level(),
            reason: ColourReason::Term,
        })
    }

    /// The bytes that bring the client's screen (`size` columns × rows) to this frame: the
    /// world through `eye`'s eyes (or a waiting message when nobody is there to follow); none
    /// when the screen would not change.
    pub fn frame(
        &mut self,
        snap: &Snapshot,
        eye: Option<PlayerId>,
        header: &str,
        size: (u16, u16),
        mode: InputMode,
        now: Instant,
    ) -> &[u8] {
        let area = Rect::new(0, 0, size.0, size.1);
        let mut buf = std::mem::take(&mut self.buf);
        // Last frame's cells are cleared below: the game's screen clears its whole body itself.
        let reused = buf.area == area;
        if !reused {
            buf = Buffer::empty(area);
        }
        let panes = panes_for(size, self.toggles);
        let body = Rect::new(
            0,
            HEADER_ROWS.min(size.1),
            size.0,
            size.1.saturating_sub(HEADER_ROWS),
        );
        let mut view = view_rect(&panes);
        let started = Instant::now();
        let mut render_time = std::time::Duration::ZERO;
        if let Some(w) = &snap.world {
            self.follow(w);
        }
        match eye.and_then(|id| snap.player(id).map(|p| (id, p))) {
            Some((id, p)) => {
                if reused {
                    // `draw` clears the body; the header's rows are left.
                    for cell in &mut buf.content
                        [..usize::from(size.0) * usize::from(HEADER_ROWS.min(size.1))]
                    {
                        cell.reset();
                    }
                }
                if let Some(world) = Arc::get_mut(&mut self.world) {
                    avatars::place(world, self.base_sprites, self.avatar_sheet, snap, id);
                }
                let mut state = p.state.clone();
                state.world = Arc::clone(&self.world);
                state.doors = snap.doors.clone();
                state.level = snap.level.clone();
                state.view_width = usize::from(view.width);
                // Mono is ASCII shades: it draws half-blocks' worth whatever the setting.
                let glyphs = if self.presenter.level() == ColorLevel::Mono {
                    Glyphs::Half
                } else {
                    self.glyphs
                };
                self.fb.resize_cells(view.width, view.height, glyphs);
                self.fb.set_phases_wanted(self.presenter.level().mixes());
                let cast = render_view_kept(&state, &mut self.fb, &mut self.background);
                let tags = avatars::mark_players(&mut self.fb, &state, &cast, snap, id);
                render_time = started.elapsed();
                let results = snap
                    .ended
                    .as_ref()
                    .map(|end| round_results(&state, end, self.leaders.as_ref()));
                let screen = Screen {
                    state: &state,
                    view: &self.fb,
                    cast: &cast,
                    stats: &self.stats,
                    toggles: self.toggles,
                    input_mode: mode,
                    results: results.as_ref(),
                    ray_text: Some(&self.ray_text),
                };
                draw_for_presenter(&screen, &panes, body, &mut buf, KeyMap::shared_default());
                if let (Some(text), Panes::Game { status, .. }) = (self.notice.at(now), panes) {
                    draw_notice(text, status, &mut buf);
                }
                if let Panes::Game {
                    minimap: Some(r), ..
                } = panes
                {
                    let inner = Block::bordered().inner(r);
                    avatars::label_minimap(&mut buf, inner, &state, &cast, snap, id);
                }
                avatars::draw_tags(&mut buf, view, &tags);
                if let (Some(board), true, None) = (&self.leaders, self.show_leaders, &results) {
                    board.render(body, &mut buf);
                }
            }
            None => {
                if reused {
                    buf.reset();
                }
                view = Rect::default();
                let y = body.y + body.height / 2;
                let msg = Rect::new(body.x, y, body.width, body.bottom().saturating_sub(y));
                Paragraph::new("nobody is playing yet: waiting for players (Tab: next)")
                    .wrap(Wrap { trim: true })
                    .centered()
                    .render(msg, &mut buf);
            }
        }
        if size.1 > HEADER_ROWS {
            let row = Rect::new(0, 0, size.0, HEADER_ROWS);
            buf.set_style(row, BAR);
            crate::widget::text::line_row(Line::raw(header), row, &mut buf);
        }
        // The presenter keeps this screen for its next diff and hands back last frame's buffer.
        let bytes = self.presenter.frame_taking(&mut buf, &self.fb, view);
        self.out.clear();
        if !is_unchanged(bytes) {
            self.out.extend_from_slice(bytes);
        }
        self.buf = buf;
        self.stats.record_bytes(self.out.len());
        self.times = (render_time, started.elapsed() - render_time);
        self.stats
            .record(Instant::now(), render_time, started.elapsed() - render_time);
        &self.out
    }
}

#[cfg(test)]
#[path = "screen_tests.rs"]
mod tests;
