//! The whole game screen at many terminal sizes: no panic, nothing drawn outside the area.

use std::sync::Arc;

use halfcast::camera::Camera;
use halfcast::game::GameState;
use halfcast::tui::FrameStats;
use halfcast::ui::keys::InputMode;
use halfcast::ui::layout::{Panes, Toggles};
use halfcast::ui::render::render_view;
use halfcast::ui::screen::{draw, Screen};
use halfcast::{Framebuffer, World};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

const SENTINEL: &str = "#";

/// Draws a frame of `w`×`h` at an offset inside a bigger buffer of sentinels; returns it.
fn frame(w: u16, h: u16, toggles: Toggles, paused: bool) -> (Buffer, Rect) {
    let world = Arc::new(World::default_world());
    let start = world.map.start;
    let cam = Camera::from_angle(start.pos(), start.angle_deg(), 66.0);
    let mut state = GameState::new(world, cam, 0);
    if paused {
        state.debugger.toggle_pause();
    }
    let area = Rect::new(3, 2, w, h);
    let panes = Panes::compute(area, toggles);
    let view = match panes {
        Panes::Game { view, .. } => view,
        Panes::TooSmall(_) => Rect::default(),
    };
    state.view_width = usize::from(view.width);
    let mut fb = Framebuffer::for_cells(view.width, view.height);
    let cast = render_view(&state, &mut fb);
    let stats = FrameStats::default();
    let screen = Screen {
        state: &state,
        view: &fb,
        cast: &cast,
        stats: &stats,
        toggles,
        input_mode: InputMode::Emulated,
        results: None,
        ray_text: None,
    };
    let mut buf = Buffer::filled(
        Rect::new(0, 0, w + 6, h + 4),
        ratatui::buffer::Cell::new(SENTINEL),
    );
    draw(&screen, &panes, area, &mut buf);
    (buf, area)
}

fn text(buf: &Buffer, area: Rect) -> String {
    (area.top()..area.bottom())
        .map(|y| {
            let row: String = (area.left()..area.right())
                .map(|x| buf[(x, y)].symbol().to_owned())
                .collect();
            row.trim_end().to_owned() + "\n"
        })
        .collect()
}

#[test]
fn every_size_draws_inside_its_area_only() {
    let sizes = [
        (1, 1),
        (19, 7),
        (20, 7),
        (19, 8),
        (20, 8),
        (40, 12),
        (59, 29),
        (60, 30),
        (80, 24),
        (80, 40),
        (99, 30),
        (100, 30),
        (120, 40),
        (160, 48),
        (240, 68),
        (500, 200),
    ];
    let toggles = [
        Toggles::default(),
        Toggles {
            help: true,
            ..Toggles::default()
        },
        Toggles {
            minimap: false,
            debug: true,
            help: false,
        },
        Toggles {
            minimap: true,
            debug: false,
            help: false,
        },
    ];
    for (w, h) in sizes {
        for t in toggles {
            for paused in [false, true] {
                let (buf, area) = frame(w, h, t, paused);
                for y in 0..buf.area.height {
                    for x in 0..buf.area.width {
                        let inside =
                            x >= area.x && x < area.right() && y >= area.y && y < area.bottom();
                        if !inside {
                            assert_eq!(buf[(x, y)].symbol(), SENTINEL, "{w}x{h}: ({x},{y}) drawn");
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn below_the_minimum_a_short_message_is_shown() {
    let (buf, area) = frame(19, 7, Toggles::default(), false);
    let t = text(&buf, area);
    assert!(t.contains("terminal too"), "{t}");
    assert!(!t.contains('▀'));
    let (buf, area) = frame(20, 8, Toggles::default(), false);
    assert!(text(&buf, area).contains('▀'));
}

#[test]
fn layout_at_120x36_with_the_debugger_paused() {
    let (buf, area) = frame(120, 36, Toggles::default(), true);
    // The view's ▀ cells are shown as '.' so the panes stand out in the snapshot.
    insta::assert_snapshot!(text(&buf, area).replace('▀', "."));
}

#[test]
fn help_overlay_lists_the_keys() {
    let (buf, area) = frame(
        100,
        40,
        Toggles {
            help: true,
            ..Toggles::default()
        },
        false,
    );
    let t = text(&buf, area);
    for needle in [
        "walk forward",
        "single-step the DDA",
        "quit",
        "look straight ahead",
        "jump",
        "night mode",
        "hold to keep moving",
    ] {
        assert!(t.contains(needle), "{needle}: {t}");
    }
}
