//! Plays a [`Replay`] headlessly at a fixed timestep: the same file gives the same frames.

use std::cell::RefCell;
use std::sync::Arc;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

use crate::camera::Camera;
use crate::game::{step, GameState};
use crate::render::cast::Cast;
use crate::render::framebuffer::Framebuffer;
use crate::render::kept_background::KeptBackground;
use crate::replay::format::{FrameInput, Header, Replay};
use crate::ui::keys::{InputMode, UiCommand};
use crate::ui::layout::{Panes, Toggles};
use crate::ui::render::render_view_kept;
use crate::ui::results::{Results, Then};
use crate::ui::screen::{draw, Screen};
use crate::ui::stats::FrameStats;
use crate::widget::KeptLines;
use crate::world::World;

/// One replayed frame: the whole screen as cells, the 3D view's pixels and its rays.
#[derive(Debug, Clone)]
pub struct Frame {
    pub index: usize,
    pub screen: Buffer,
    pub view: Framebuffer,
    /// Where the view sits on the screen (empty when the terminal is too small for it).
    pub view_area: Rect,
    /// The camera this frame was seen through.
    pub camera: Camera,
    pub cast: Cast,
}

/// The replay's game and screen state, advanced one frame at a time.
#[derive(Debug)]
pub struct Player {
    state: GameState,
    toggles: Toggles,
    size: (u16, u16),
    dt: f64,
    stats: FrameStats,
    next: usize,
    view: Framebuffer,
    /// The results screen, once the level's exit was reached.
    results: Option<Results>,
    /// The ray pane's lines, kept from frame to frame.
    ray_text: RefCell<KeptLines>,
    /// The view's walls, floors and ceilings, kept from frame to frame (one world throughout).
    background: KeptBackground,
}

impl Player {
    /// Starts a replay in `world` (the caller resolved the header's map).
    #[must_use]
    pub fn new(world: Arc<World>, header: &Header) -> Self {
        let camera = Camera::from_angle(header.pos, header.angle_deg, header.fov_deg);
        let mut stats = FrameStats::default();
        stats.fps = f64::from(header.fps);
        stats.glyphs = header.glyphs;
        let mut state = GameState::with_seed(world, camera, 0, header.seed);
        state.speeds = header.speeds;
        Self {
            state,
            toggles: Toggles::default(),
            size: header.size,
            dt: 1.0 / f64::from(header.fps),
            stats,
            next: 0,
            view: Framebuffer::new(0, 0),
            results: None,
            ray_text: RefCell::default(),
            background: KeptBackground::default(),
        }
    }

    /// The game state after the frames played so far.
    #[must_use]
    pub fn state(&self) -> &GameState {
        &self.state
    }

    /// The terminal size in cells the next frame is drawn at.
    #[must_use]
    pub fn size(&self) -> (u16, u16) {
        self.size
    }

    /// Applies one frame's input (UI toggles, resize, then one step of 1/fps s) and draws it,
    /// as the live loop does; `None` when the input asks to quit.
    pub fn play(&mut self, input: &FrameInput) -> Option<Frame> {
        if let Some(size) = input.resize {
            self.size = size;
        }
        for &u in &input.ui {
            match u {
                UiCommand::Quit => return None,
                UiCommand::Back if self.toggles.help => self.toggles.help = false,
                UiCommand::Back => return None,
                UiCommand::ToggleMinimap => self.toggles.minimap = !self.toggles.minimap,
                UiCommand::ToggleDebug => self.toggles.debug = !self.toggles.debug,
                UiCommand::ToggleHelp => self.toggles.help = !self.toggles.help,
                // Recordings keep the setting the key led to; older ones kept the key itself,
                // pressed where the cycle had all four settings.
                UiCommand::SetGlyphs(g) => self.stats.glyphs = g,
                UiCommand::CycleGlyphs => self.stats.glyphs = self.stats.glyphs.cycled(),
                // Frames are written at the level the replay command asks for.
                UiCommand::CycleColours | UiCommand::SaveFigure => {}
            }
        }
        let area = Rect::new(0, 0, self.size.0, self.size.1);
        let panes = Panes::compute(area, self.toggles);
        let view = match panes {
            Panes::Game { view, .. } => view,
            Panes::TooSmall(_) => Rect::default(),
        };
        self.state.view_width = usize::from(view.width);
        // As the live loop: the world stops at the exit and the results screen shows.
        if self.results.is_none() {
            step(&mut self.state, &input.input, self.dt);
            if self.state.level.finished().is_some() {
                self.results = Some(Results::of(
                    &self.state.world.map.name,
                    &self.state,
                    Then::Again,
                ));
            }
        }
        self.view
            .resize_cells(view.width, view.height, self.stats.glyphs);
        let cast = render_view_kept(&self.state, &mut self.view, &mut self.background);
        let mut screen = Buffer::empty(area);
        let s = Screen {
            state: &self.state,
            view: &self.view,
            cast: &cast,
            stats: &self.stats,
            toggles: self.toggles,
            input_mode: InputMode::Emulated,
            results: self.results.as_ref(),
            ray_text: Some(&self.ray_text),
        };
        draw(&s, &panes, area, &mut screen);
        let frame = Frame {
            index: self.next,
            screen,
            view: self.view.clone(),
            view_area: view,
            camera: self.state.camera,
            cast,
        };
        self.next += 1;
        Some(frame)
    }
}

/// Plays a whole replay, handing each frame to `each` (stops early on a quit).
pub fn play_all(world: Arc<World>, replay: &Replay, mut each: impl FnMut(&Frame)) {
    let mut player = Player::new(world, &replay.header);
    for input in &replay.frames {
        match player.play(input) {
            Some(frame) => each(&frame),
            None => break,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::Speeds;
    use crate::render::glyphs::Glyphs;
    use crate::replay::format::MapSource;
    use crate::ui::glyph_cycle::GlyphCycle;
    use crate::ui::octant_support::{octant_dropper, TermEnv};
    use crate::vec2::Vec2;

    fn header() -> Header {
        Header {
            map: MapSource::Embedded,
            pos: Vec2::new(15.5, 5.5),
            angle_deg: 90.0,
            fov_deg: 66.0,
            size: (40, 12),
            fps: 30,
            seed: 0,
            speeds: Speeds::default(),
            glyphs: Glyphs::Half,
        }
    }

    /// Six frames with the glyph key pressed on frames 1 to 4, as the keys arrive.
    fn four_presses() -> Vec<FrameInput> {
        let mut frames = vec![FrameInput::default(); 6];
        for f in &mut frames[1..5] {
            f.ui.push(UiCommand::CycleGlyphs);
        }
        frames
    }

    /// The block characters each frame of `text` (a `.hcr` file) is drawn with.
    fn replayed(text: &str) -> Vec<Glyphs> {
        let replay = Replay::parse("r.hcr", text).expect("valid");
        let mut seen = Vec::new();
        play_all(Arc::new(World::default_world()), &replay, |f| {
            seen.push(f.view.glyphs());
        });
        seen
    }

    #[test]
    fn a_recording_made_behind_tmux_replays_its_settings_wherever_it_plays() {
        // What the local loop does: the key becomes the setting it leads to, then is recorded.
        let env = TermEnv {
            term: Some("xterm-256color"),
            tmux: Some("/tmp/tmux-1000/default,99,0"),
        };
        let mut cycle = GlyphCycle::new(octant_dropper(env), Glyphs::Half, "forces");
        let mut now = Glyphs::Half;
        let mut frames = four_presses();
        let mut live = Vec::new();
        for f in &mut frames {
            cycle.resolve(&mut f.ui, now);
            for u in &f.ui {
                if let UiCommand::SetGlyphs(g) = u {
                    now = *g;
                }
            }
            live.push(now);
        }
        let text = Replay {
            header: header(),
            frames,
        }
        .to_jsonl();
        assert!(
            !text.contains("cycle_glyphs") && !text.contains("octant"),
            "{text}"
        );
        use Glyphs::{Half, Quadrant, Sextant};
        assert_eq!(live, [Half, Quadrant, Sextant, Half, Quadrant, Quadrant]);
        // The player reads no environment: the file alone decides, so this is every replay.
        assert_eq!(replayed(&text), live);
    }

    #[test]
    fn an_older_recording_of_the_key_still_cycles_through_octant() {
        let text = Replay {
            header: header(),
            frames: four_presses(),
        }
        .to_jsonl();
        assert_eq!(text.matches("\"ui\":\"cycle_glyphs\"").count(), 4);
        use Glyphs::{Half, Octant, Quadrant, Sextant};
        assert_eq!(
            replayed(&text),
            [Half, Quadrant, Sextant, Octant, Half, Half]
        );
    }
}
