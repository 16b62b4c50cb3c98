//! A ratatui app embedding halfcast as a library user would, with the default features off:
//! the stock `Terminal` over `TestBackend`, the 3D view in one pane and the minimap in another.

use halfcast::{Camera, ColorLevel, Framebuffer, HalfBlockView, Minimap, Scene, World};
use ratatui::backend::TestBackend;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Color;
use ratatui::widgets::Block;
use ratatui::Terminal;

/// Draws one frame of the app and returns the view's inner area.
fn draw(
    terminal: &mut Terminal<TestBackend>,
    world: &World,
    camera: Camera,
    level: ColorLevel,
) -> Rect {
    let mut view_area = Rect::default();
    terminal
        .draw(|frame| {
            let [view, map] =
                Layout::horizontal([Constraint::Fill(2), Constraint::Fill(1)]).areas(frame.area());
            let inner = Block::bordered().inner(view);
            frame.render_widget(Block::bordered().title("view"), view);
            let mut fb = Framebuffer::for_cells(inner.width, inner.height);
            let cast = Scene::new(world, camera).render_into(&mut fb, None);
            frame.render_widget(HalfBlockView::new(&fb).level(level), inner);
            frame.render_widget(Minimap::new(world, &camera, &cast.columns), map);
            view_area = inner;
        })
        .expect("TestBackend cannot fail");
    view_area
}

/// The default world, its start camera and a 60×20 stock terminal over `TestBackend`.
fn setup() -> (World, Camera, Terminal<TestBackend>) {
    let world = World::default_world();
    let start = world.map.start;
    let camera = Camera::from_angle(start.pos(), start.angle_deg(), 66.0);
    (
        world,
        camera,
        Terminal::new(TestBackend::new(60, 20)).unwrap(),
    )
}

#[test]
fn the_stock_terminal_shows_the_view_and_the_minimap() {
    let (world, camera, mut terminal) = setup();
    let inner = draw(&mut terminal, &world, camera, ColorLevel::TrueColor);
    let shown = terminal.backend().buffer().clone();
    assert_eq!(inner, Rect::new(1, 1, 38, 18));
    // The view pane holds exactly the scene's half-block frame at that size.
    let want = Scene::new(&world, camera).to_buffer(inner.width, inner.height);
    for y in 0..inner.height {
        for x in 0..inner.width {
            let (got, want) = (&shown[(inner.x + x, inner.y + y)], &want[(x, y)]);
            assert_eq!(
                (got.symbol(), got.fg, got.bg),
                (want.symbol(), want.fg, want.bg),
                "({x},{y})"
            );
        }
    }
    assert_eq!(shown[(1, 0)].symbol(), "v", "the border title");
    // The minimap pane (columns 40..60) is drawn: half-blocks in more than one colour.
    let colours: std::collections::HashSet<_> = (0..20)
        .flat_map(|y| (40..60).map(move |x| (x, y)))
        .map(|p| shown[p].fg)
        .collect();
    assert!(colours.len() > 2, "{colours:?}");

    // Turning changes the view; the minimap stays.
    let mut turned = camera;
    turned.rotate(0.5);
    draw(&mut terminal, &world, turned, ColorLevel::TrueColor);
    assert_ne!(terminal.backend().buffer(), &shown);
}

#[test]
fn the_view_can_be_drawn_in_256_colours_on_the_stock_backend() {
    let (world, camera, mut terminal) = setup();
    let inner = draw(&mut terminal, &world, camera, ColorLevel::Ansi256);
    let buf = terminal.backend().buffer();
    for y in inner.top()..inner.bottom() {
        for x in inner.left()..inner.right() {
            let c = &buf[(x, y)];
            assert!(
                matches!((c.fg, c.bg), (Color::Indexed(16..), Color::Indexed(16..))),
                "({x},{y}) {c:?}"
            );
        }
    }
}
