//! Snapshots of the widgets on small frames, in the colour-aware text form every text snapshot
//! of the project uses (`snapshot::cells_text`: glyph + fg + bg per cell).

use halfcast::camera::Camera;
use halfcast::render::cast::{cast, trace_column};
use halfcast::snapshot::cells_text;
use halfcast::widget::{DebugPane, HalfBlockView, Minimap, RevealedTrace};
use halfcast::{Framebuffer, Scene, Vec2, World};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::widgets::Widget;

fn pose() -> Camera {
    Camera::from_angle(Vec2::new(8.5, 5.5), 30.0, 66.0)
}

#[test]
fn view_40x12_of_the_default_map() {
    let world = World::default_world();
    let scene = Scene::new(&world, pose());
    let text = cells_text(scene.to_buffer(40, 12));
    // The view widget's cells and the framebuffer's half blocks are the same frame.
    assert_eq!(text, scene.to_cells_text(40, 12));
    insta::assert_snapshot!(text);
}

#[test]
fn minimap_30x12_with_a_half_stepped_ray() {
    let world = World::default_world();
    let cam = pose();
    let rays = cast(&world.map, &cam, 40, None).columns;
    let trace = trace_column(&world.map, &cam, 20, 40);
    let area = Rect::new(0, 0, 30, 12);
    let mut buf = Buffer::empty(area);
    Minimap::new(&world, &cam, &rays)
        .debug_ray(RevealedTrace::partial(&trace, 3))
        .render(area, &mut buf);
    insta::assert_snapshot!(cells_text(&buf));
}

#[test]
fn debug_pane_44x16_highlights_the_current_step() {
    let world = World::default_world();
    let cam = pose();
    let trace = trace_column(&world.map, &cam, 20, 40);
    let area = Rect::new(0, 0, 44, 16);
    let mut buf = Buffer::empty(area);
    DebugPane::new(RevealedTrace::partial(&trace, 2), &world, &cam, (40, 12))
        .render(area, &mut buf);
    insta::assert_snapshot!(cells_text(&buf));
    // Row of step 2 (the current one) has the highlight background; step 1 does not.
    let row_of = |needle: &str| {
        (0..area.height)
            .find(|&y| {
                let row: String = (0..area.width)
                    .map(|x| buf[(x, y)].symbol().to_owned())
                    .collect();
                row.starts_with(needle)
            })
            .unwrap()
    };
    assert_ne!(buf[(1, row_of("  2 "))].bg, Color::Reset);
    assert_eq!(buf[(1, row_of("  1 "))].bg, Color::Reset);
}

#[test]
fn the_view_widget_shows_exactly_the_framebuffer() {
    let world = World::default_world();
    let fb: Framebuffer = Scene::new(&world, pose()).render(37, 11);
    let area = Rect::new(2, 1, 37, 11);
    let mut buf = Buffer::empty(Rect::new(0, 0, 41, 13));
    HalfBlockView::new(&fb).render(area, &mut buf);
    for cy in 0..11u16 {
        for cx in 0..37u16 {
            let c = &buf[(area.x + cx, area.y + cy)];
            let (up, low) = fb.cell(cx.into(), cy.into());
            assert_eq!(c.fg, Color::Rgb(up.r, up.g, up.b));
            assert_eq!(c.bg, Color::Rgb(low.r, low.g, low.b));
        }
    }
}
