//! The TUI's per-frame cost without a real terminal: render (cast + raster), then draw (build
//! the ratatui buffer, diff, encode with crossterm into memory). Also prints bytes per frame.

use std::cell::Cell;
use std::hint::black_box;
use std::io::Write;
use std::rc::Rc;
use std::sync::Arc;

use criterion::{criterion_group, criterion_main, Criterion};
use halfcast::camera::Camera;
use halfcast::game::GameState;
use halfcast::tui::FrameStats;
use halfcast::ui::keys::InputMode;
use halfcast::ui::layout::{Panes, Toggles};
use halfcast::ui::render::render_view;
use halfcast::ui::screen::{draw, Screen};
use halfcast::{Framebuffer, World};
use ratatui::backend::CrosstermBackend;
use ratatui::layout::Rect;
use ratatui::{Terminal, TerminalOptions, Viewport};

/// A terminal stand-in that only counts the bytes written to it.
#[derive(Clone, Default)]
struct Counter(Rc<Cell<usize>>);

impl Write for Counter {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.set(self.0.get() + buf.len());
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

struct Rig {
    state: GameState,
    fb: Framebuffer,
    panes: Panes,
    bytes: Counter,
    terminal: Terminal<CrosstermBackend<Counter>>,
}

impl Rig {
    fn new(cols: u16, rows: u16) -> Self {
        let world = Arc::new(World::default_world());
        let cam = Camera::from_angle(world.map.start.pos(), 90.0, 66.0);
        let area = Rect::new(0, 0, cols, rows);
        let panes = Panes::compute(area, Toggles::default());
        let Panes::Game { view, .. } = panes else {
            panic!("too small")
        };
        let state = GameState::new(world, cam, usize::from(view.width));
        let bytes = Counter::default();
        let terminal = Terminal::with_options(
            CrosstermBackend::new(bytes.clone()),
            TerminalOptions {
                viewport: Viewport::Fixed(area),
            },
        )
        .expect("in-memory terminal");
        Self {
            state,
            fb: Framebuffer::for_cells(view.width, view.height),
            panes,
            bytes,
            terminal,
        }
    }

    /// Turns a little (so every view cell changes), renders and draws; returns bytes written.
    fn frame(&mut self) -> usize {
        self.state.camera.rotate(0.01);
        let cast = render_view(&self.state, &mut self.fb);
        let stats = FrameStats::default();
        let screen = Screen {
            state: &self.state,
            view: &self.fb,
            cast: &cast,
            stats: &stats,
            toggles: Toggles::default(),
            input_mode: InputMode::Emulated,
            results: None,
            ray_text: None,
        };
        let before = self.bytes.0.get();
        let panes = self.panes;
        self.terminal
            .draw(|f| draw(&screen, &panes, f.area(), f.buffer_mut()))
            .expect("draw");
        self.bytes.0.get() - before
    }
}

fn bench(c: &mut Criterion) {
    for (cols, rows) in [(120u16, 40u16), (240, 68)] {
        let mut rig = Rig::new(cols, rows);
        rig.frame();
        let bytes: usize = (0..20).map(|_| rig.frame()).sum::<usize>() / 20;
        eprintln!("{cols}x{rows}: {bytes} bytes per frame while turning (ratatui + crossterm)");
        c.bench_function(&format!("render {cols}x{rows}"), |b| {
            b.iter(|| {
                rig.state.camera.rotate(0.01);
                black_box(render_view(&rig.state, &mut rig.fb));
            });
        });
        c.bench_function(&format!("render+draw {cols}x{rows}"), |b| {
            b.iter(|| black_box(rig.frame()));
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
