//! The encoder drawing the 3D view inside a terminal that ratatui also draws (borders, side
//! panes): both byte streams into one terminal model; the view and the panes must both be right.

use crate::capture;

use capture::Capture;

use halfcast::encode::palette::{Code, DEFAULT};
use halfcast::encode::quantize;
use halfcast::encode::{ColorLevel, EncodeOptions, Encoder};
use halfcast::{Camera, Scene, World};
use ratatui::backend::CrosstermBackend;
use ratatui::layout::Rect;
use ratatui::widgets::{Block, Paragraph};
use ratatui::{Terminal, TerminalOptions, Viewport};

fn code_of(c: vt100::Color) -> Code {
    match c {
        vt100::Color::Default => DEFAULT,
        vt100::Color::Idx(i) => u32::from(i),
        vt100::Color::Rgb(r, g, b) => (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b),
    }
}

#[test]
fn view_and_ratatui_panes_coexist_frame_after_frame() {
    let world = World::default_world();
    let start = world.map.start;
    let out = Capture::default();
    let mut terminal = Terminal::with_options(
        CrosstermBackend::new(out.clone()),
        TerminalOptions {
            viewport: Viewport::Fixed(Rect::new(0, 0, 64, 16)),
        },
    )
    .unwrap();
    let mut parser = vt100::Parser::new(16, 64, 0);
    for level in [
        ColorLevel::TrueColor,
        ColorLevel::Ansi256,
        ColorLevel::Ansi16,
    ] {
        let mut enc = Encoder::new(EncodeOptions::new(level));
        for i in 0..12 {
            let cam = Camera::from_angle(start.pos(), start.angle_deg() + 4.0 * f64::from(i), 66.0);
            let fb = Scene::new(&world, cam).render(40, 12);
            terminal
                .draw(|f| {
                    f.render_widget(Block::bordered().title("view"), Rect::new(0, 0, 42, 14));
                    f.render_widget(
                        Paragraph::new(format!("frame {i:02}")),
                        Rect::new(44, 0, 20, 1),
                    );
                })
                .unwrap();
            parser.process(&std::mem::take(&mut *out.0.borrow_mut()));
            parser.process(enc.encode(&fb, 1, 1));
            let screen = parser.screen();
            let mut want = Vec::new();
            quantize(enc.palette(), &fb, &mut want);
            for (k, w) in want.iter().enumerate() {
                let cell = screen
                    .cell(1 + (k / 40) as u16, 1 + (k % 40) as u16)
                    .unwrap();
                let (fg, bg) = (code_of(cell.fgcolor()), code_of(cell.bgcolor()));
                let got = match cell.contents().as_str() {
                    "▀" => [fg, bg],
                    "▄" => [bg, fg],
                    "" | " " => [bg, bg],
                    "█" => [fg, fg],
                    g => panic!("glyph {g:?} in the view"),
                };
                assert_eq!(got, *w, "{level} frame {i} cell {k}");
            }
            assert_eq!(screen.cell(0, 0).unwrap().contents(), "┌");
            assert_eq!(screen.cell(13, 41).unwrap().contents(), "┘");
            assert_eq!(screen.cell(0, 1).unwrap().fgcolor(), vt100::Color::Default);
            assert!(screen.contents().contains(&format!("frame {i:02}")));
        }
    }
}
