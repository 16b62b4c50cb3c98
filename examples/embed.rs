//! halfcast inside an ordinary ratatui app: the 3D view in one pane, the minimap in another,
//! drawn by the stock `Terminal` with the crossterm backend. Arrow keys move, q quits.
//!
//! ```sh
//! cargo run --example embed --no-default-features --features crossterm
//! ```

use halfcast::world::door::DoorState;
use halfcast::{Camera, Framebuffer, HalfBlockView, Minimap, Scene, Vec2, World};
use ratatui::crossterm::event::{self, Event, KeyCode, KeyEventKind};
use ratatui::layout::{Constraint, Layout};
use ratatui::widgets::Block;

fn main() -> std::io::Result<()> {
    let world = World::default_world();
    let start = world.map.start;
    let mut camera = Camera::from_angle(start.pos(), start.angle_deg(), 66.0);
    // `ratatui::init` enters the alternate screen and raw mode, and restores them on panic.
    let mut terminal = ratatui::init();
    let result = (|| loop {
        terminal.draw(|frame| {
            let [view, map] =
                Layout::horizontal([Constraint::Fill(3), Constraint::Fill(1)]).areas(frame.area());
            let inner = Block::bordered().title("3D view (arrows, q)").inner(view);
            frame.render_widget(Block::bordered().title("3D view (arrows, q)"), view);
            // The view renders at the pane's size: one cell shows two stacked pixels.
            let mut fb = Framebuffer::for_cells(inner.width, inner.height);
            let cast = Scene::new(&world, camera).render_into(&mut fb, None);
            frame.render_widget(HalfBlockView::new(&fb), inner);
            let map_inner = Block::bordered().title("map").inner(map);
            frame.render_widget(Block::bordered().title("map"), map);
            frame.render_widget(Minimap::new(&world, &camera, &cast.columns), map_inner);
        })?;
        if let Event::Key(key) = event::read()? {
            if key.kind != KeyEventKind::Press {
                continue;
            }
            let step =
                |c: &Camera, by: f64| Vec2::new(c.pos.x + c.dir.x * by, c.pos.y + c.dir.y * by);
            match key.code {
                KeyCode::Char('q') | KeyCode::Esc => return Ok(()),
                KeyCode::Left => camera.rotate(0.1),
                KeyCode::Right => camera.rotate(-0.1),
                KeyCode::Up | KeyCode::Down => {
                    let by = if key.code == KeyCode::Up { 0.25 } else { -0.25 };
                    let next = step(&camera, by);
                    if !world.is_blocked(next, 0.2, &DoorState::none()) {
                        camera.pos = next;
                    }
                }
                _ => {}
            }
        }
    })();
    ratatui::restore();
    result
}
