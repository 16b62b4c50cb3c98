//! `LeanBackend` against stock ratatui's `CrosstermBackend` on ratatui demo-style screens (a
//! table, a chart, sparklines and gauges that change every frame) and halfcast's own panes:
//! the same frames through both must leave identical terminal screens (vt100: glyphs, colours,
//! attributes; a half-block cell compared by the two colours it shows), and the lean one must
//! send fewer bytes. Runs without default features.
//!
//! `cargo test --test lean_backend -- --nocapture` prints the bytes-per-frame table.

use crate::capture;

use capture::Capture;

use halfcast::encode::{EncodeOptions, Palette};
use halfcast::present::Presenter;
use halfcast::widget::RevealedTrace;
use halfcast::{
    Camera, ColorLevel, DebugPane, Framebuffer, HalfBlockView, LeanBackend, Minimap, Scene, World,
};
use ratatui::backend::{Backend, CrosstermBackend};
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::widgets::{
    Axis, Block, Chart, Dataset, Gauge, GraphType, LineGauge, Row, Sparkline, Table,
};
use ratatui::{Frame, Terminal, TerminalOptions, Viewport};

const COLS: u16 = 120;
const ROWS: u16 = 40;
const FRAMES: usize = 24;

fn fixed<B: Backend>(backend: B) -> Terminal<B> {
    Terminal::with_options(
        backend,
        TerminalOptions {
            viewport: Viewport::Fixed(Rect::new(0, 0, COLS, ROWS)),
        },
    )
    .unwrap_or_else(|_| panic!("a fixed viewport asks nothing of the backend"))
}

/// A smooth colour that moves with the frame (24-bit, as modern ratatui apps use).
fn hue(i: usize, k: usize) -> Color {
    let t = (i * 7 + k * 23) as f64 * 0.09;
    let c = |p: f64| (127.5 + 127.5 * (t + p).sin()) as u8;
    Color::Rgb(c(0.0), c(2.1), c(4.2))
}

/// A table of numbers that change every frame, with a header, a highlighted row and colours.
fn table(f: &mut Frame, i: usize) {
    let rows = (0..36).map(|r| {
        let v = (r * 37 + i * 11) % 1000;
        let style = if r == i % 36 {
            Style::new().add_modifier(Modifier::REVERSED)
        } else if v > 700 {
            Style::new().fg(Color::Red).add_modifier(Modifier::BOLD)
        } else {
            Style::new().fg(hue(i, r))
        };
        Row::new(vec![
            format!("host-{r:02}"),
            format!("{v}"),
            format!("{:.1} %", v as f64 / 10.0),
            format!("{} ms", (v * 3 + i) % 250),
            if v.is_multiple_of(3) {
                "ok".into()
            } else {
                "busy".into()
            },
        ])
        .style(style)
    });
    let header = Row::new(vec!["host", "load", "cpu", "latency", "state"])
        .style(Style::new().bold().underlined().fg(Color::Yellow));
    let widths = [Constraint::Length(10); 5];
    f.render_widget(
        Table::new(rows, widths)
            .header(header)
            .block(Block::bordered().title("table")),
        f.area(),
    );
}

/// Two moving line charts with labelled axes (braille markers).
fn chart(f: &mut Frame, i: usize) {
    let wave = |phase: f64, amp: f64| -> Vec<(f64, f64)> {
        (0..200)
            .map(|x| {
                let x = f64::from(x) * 0.1;
                (x, amp * (x + phase + i as f64 * 0.3).sin())
            })
            .collect()
    };
    let (a, b) = (wave(0.0, 1.0), wave(1.3, 0.6));
    let datasets = vec![
        Dataset::default()
            .name("sin")
            .marker(Marker::Braille)
            .graph_type(GraphType::Line)
            .style(Style::new().fg(Color::Cyan))
            .data(&a),
        Dataset::default()
            .name("cos")
            .marker(Marker::Braille)
            .style(Style::new().fg(hue(i, 3)))
            .data(&b),
    ];
    let chart = Chart::new(datasets)
        .block(Block::bordered().title(format!("chart, frame {i}")))
        .x_axis(
            Axis::default()
                .title("t")
                .bounds([0.0, 20.0])
                .labels(["0", "10", "20"]),
        )
        .y_axis(
            Axis::default()
                .title("v")
                .bounds([-1.0, 1.0])
                .labels(["-1", "0", "1"]),
        );
    f.render_widget(chart, f.area());
}

/// Sparklines and gauges whose values change every frame.
fn gauges(f: &mut Frame, i: usize) {
    let rows = Layout::vertical([Constraint::Length(3); 12]).split(f.area());
    for (k, r) in rows.iter().enumerate() {
        let data: Vec<u64> = (0..120)
            .map(|x| ((x * 13 + k * 7 + i * 5) % 64) as u64)
            .collect();
        let ratio = ((i * 3 + k * 11) % 100) as f64 / 100.0;
        match k % 3 {
            0 => f.render_widget(
                Sparkline::default()
                    .block(Block::bordered().title(format!("spark {k}")))
                    .data(&data)
                    .style(Style::new().fg(hue(i, k))),
                *r,
            ),
            1 => f.render_widget(
                Gauge::default()
                    .block(Block::bordered())
                    .gauge_style(Style::new().fg(hue(i, k)).bg(Color::Rgb(20, 20, 30)))
                    .ratio(ratio),
                *r,
            ),
            _ => f.render_widget(
                LineGauge::default()
                    .filled_style(Style::new().fg(Color::Green).bold())
                    .ratio(ratio)
                    .label(format!("job {k}")),
                *r,
            ),
        }
    }
}

/// halfcast's own screen: the 3D view turning, the minimap and the DDA pane beside it.
fn panes(f: &mut Frame, i: usize, world: &World, level: ColorLevel) {
    let [view, side] =
        Layout::horizontal([Constraint::Min(60), Constraint::Length(40)]).areas::<2>(f.area());
    let [map, ray] = Layout::vertical([Constraint::Percentage(50); 2]).areas::<2>(side);
    let camera = turning(world, i);
    let mut fb = Framebuffer::for_cells(view.width, view.height);
    let cast = Scene::new(world, camera).render_into(&mut fb, Some(usize::from(view.width) / 2));
    f.render_widget(HalfBlockView::new(&fb).level(level), view);
    f.render_widget(Minimap::new(world, &camera, &cast.columns), map);
    if let Some(t) = &cast.trace {
        let cells = (usize::from(view.width), usize::from(view.height));
        f.render_widget(
            DebugPane::new(RevealedTrace::full(t), world, &camera, cells),
            ray,
        );
    }
}

/// The 3D view alone, full screen.
fn view_only(f: &mut Frame, i: usize, world: &World, level: ColorLevel) {
    let fb = Scene::new(world, turning(world, i)).render(COLS, ROWS);
    f.render_widget(HalfBlockView::new(&fb).level(level), f.area());
}

fn turning(world: &World, i: usize) -> Camera {
    let start = world.map.start;
    Camera::from_angle(start.pos(), start.angle_deg() + 3.0 * i as f64, 66.0)
}

type Screen = fn(&mut Frame, usize, &World, ColorLevel);

fn screens() -> Vec<(&'static str, Screen)> {
    vec![
        ("table", |f, i, _, _| table(f, i)),
        ("chart", |f, i, _, _| chart(f, i)),
        ("sparklines+gauges", |f, i, _, _| gauges(f, i)),
        ("halfcast panes", panes),
        ("halfcast 3D view", view_only),
    ]
}

/// Maps a drawn buffer's 24-bit colours to the palette, as the lean backend does at `level`
/// (what a stock backend must be given to show the same screen).
fn quantized(buf: &mut Buffer, level: ColorLevel) {
    let palette = Palette::new(level);
    for cell in &mut buf.content {
        for c in [&mut cell.fg, &mut cell.bg] {
            if let Color::Rgb(r, g, b) = *c {
                *c = Color::Indexed(palette.code(halfcast::Rgb::new(r, g, b)) as u8);
            }
        }
    }
}

/// Everything vt100 knows about a screen's cells. A half-block cell is read as what it shows
/// (its upper and lower colour), so `▀` a/b equals `▄` b/a, a space on b equals `█` in b: the
/// lean backend may send a picture's cells either way.
fn seen(p: &vt100::Parser) -> Vec<String> {
    let s = p.screen();
    let mut rows = Vec::new();
    for y in 0..ROWS {
        let mut line = String::new();
        for x in 0..COLS {
            let c = s.cell(y, x).expect("inside the screen");
            let attrs = [c.bold(), c.italic(), c.underline(), c.inverse()];
            let (fg, bg) = (c.fgcolor(), c.bgcolor());
            let glyph = match c.contents().as_str() {
                "" => " ".to_owned(),
                g => g.to_owned(),
            };
            let (glyph, fg, bg) = match glyph.as_str() {
                _ if attrs.iter().any(|&a| a) => (glyph, fg, bg),
                "▀" => ("▀".into(), fg, bg),
                "▄" => ("▀".into(), bg, fg),
                " " => ("▀".into(), bg, bg),
                "█" => ("▀".into(), fg, fg),
                _ => (glyph, fg, bg),
            };
            let a = attrs.map(u8::from);
            line.push_str(&format!("[{glyph}|{fg:?}|{bg:?}|{a:?}]"));
        }
        rows.push(line);
    }
    rows
}

/// Runs every frame of `screen` through a stock terminal (colours quantized to `level` first)
/// and through `LeanBackend` at `level`; checks the screens match after each frame and returns
/// the bytes per frame (stock, lean).
fn both(world: &World, screen: Screen, level: ColorLevel, name: &str) -> (Vec<usize>, Vec<usize>) {
    let (stock_out, lean_out) = (Capture::default(), Capture::default());
    let mut stock = fixed(CrosstermBackend::new(stock_out.clone()));
    let mut lean = fixed(LeanBackend::new(lean_out.clone(), level).with_size(COLS, ROWS));
    let (mut a, mut b) = (
        vt100::Parser::new(ROWS, COLS, 0),
        vt100::Parser::new(ROWS, COLS, 0),
    );
    let (mut stock_bytes, mut lean_bytes) = (Vec::new(), Vec::new());
    for i in 0..FRAMES {
        stock
            .draw(|f| {
                screen(f, i, world, level);
                if level != ColorLevel::TrueColor {
                    quantized(f.buffer_mut(), level);
                }
            })
            .unwrap();
        lean.draw(|f| screen(f, i, world, level)).unwrap();
        let (sb, lb) = (stock_out.take(), lean_out.take());
        a.process(&sb);
        b.process(&lb);
        let (sa, sb_) = (seen(&a), seen(&b));
        for (y, (x, z)) in sa.iter().zip(&sb_).enumerate() {
            assert_eq!(x, z, "{name} at {level}: frame {i}, row {y} differs");
        }
        stock_bytes.push(sb.len());
        lean_bytes.push(lb.len());
    }
    (stock_bytes, lean_bytes)
}

fn mean_after_first(v: &[usize]) -> f64 {
    v[1..].iter().sum::<usize>() as f64 / (v.len() - 1) as f64
}

#[test]
fn lean_and_stock_backends_leave_identical_screens_at_truecolor_and_256() {
    let world = World::default_world();
    for (name, screen) in screens() {
        for level in [
            ColorLevel::TrueColor,
            ColorLevel::Ansi256,
            ColorLevel::Ansi16,
        ] {
            both(&world, screen, level, name);
        }
    }
}

/// The bytes table (printed with `--nocapture`): mean bytes per frame after the first.
#[test]
fn lean_backend_sends_fewer_bytes_on_every_screen() {
    let world = World::default_world();
    println!(
        "\n{COLS}x{ROWS}, {FRAMES} frames, mean bytes/frame after the first\n\
         | screen | CrosstermBackend truecolor | LeanBackend truecolor | ratio | LeanBackend 256 | ratio |\n\
         |---|---:|---:|---:|---:|---:|"
    );
    for (name, screen) in screens() {
        let (stock, lean) = both(&world, screen, ColorLevel::TrueColor, name);
        let (_, lean256) = both(&world, screen, ColorLevel::Ansi256, name);
        let (s, l, l256) = (
            mean_after_first(&stock),
            mean_after_first(&lean),
            mean_after_first(&lean256),
        );
        println!(
            "| {name} | {s:.0} | {l:.0} | {:.1} % | {l256:.0} | {:.1} % |",
            100.0 * l / s,
            100.0 * l256 / s
        );
        assert!(l < s, "{name}: lean {l} vs stock {s}");
        assert!(lean[0] < stock[0], "{name} first frame");
    }
}

/// The 3D view through `Presenter` (the game's path: the cell writer for the panes, the frame
/// encoder for the view's pixels) against `LeanBackend` drawing `HalfBlockView`'s `▀` cells:
/// the lean backend must be as lean (within 5 %).
#[test]
fn the_lean_backend_sends_the_3d_view_as_lean_as_the_presenter() {
    let world = World::default_world();
    println!("\n3D view {COLS}x{ROWS}, mean bytes/frame after the first");
    println!("| level | CrosstermBackend | LeanBackend | Presenter (view shortcut) |\n|---|---:|---:|---:|");
    for level in [ColorLevel::TrueColor, ColorLevel::Ansi256] {
        let (stock, lean) = both(&world, view_only, level, "3D view");
        let mut p = Presenter::new(EncodeOptions::new(level));
        let area = Rect::new(0, 0, COLS, ROWS);
        let mut term = vt100::Parser::new(ROWS, COLS, 0);
        let mut lean_term = vt100::Parser::new(ROWS, COLS, 0);
        let lean_out = Capture::default();
        let mut lean_t = fixed(LeanBackend::new(lean_out.clone(), level).with_size(COLS, ROWS));
        let mut presented = Vec::new();
        for i in 0..FRAMES {
            let fb = Scene::new(&world, turning(&world, i)).render(COLS, ROWS);
            let bytes = p.frame(&Buffer::empty(area), &fb, area).to_vec();
            term.process(&bytes);
            presented.push(bytes.len());
            lean_t.draw(|f| view_only(f, i, &world, level)).unwrap();
            lean_term.process(&lean_out.take());
            if level == ColorLevel::TrueColor {
                // Same pixels on screen (the shortcut may draw a cell as `▄`, ` ` or `█`).
                let shown = halfcast::termframe::TermFrame::from_buffer(&{
                    let mut b = Buffer::empty(area);
                    ratatui::widgets::Widget::render(HalfBlockView::new(&fb), area, &mut b);
                    b
                });
                for y in 0..usize::from(ROWS) {
                    for x in 0..usize::from(COLS) {
                        // This binary builds without the `vt100` feature: the cell by hand.
                        let c = term.screen().cell(y as u16, x as u16).unwrap();
                        let rgb = |v: vt100::Color| match v {
                            vt100::Color::Rgb(r, g, b) => Some(halfcast::Rgb::new(r, g, b)),
                            _ => None,
                        };
                        use halfcast::termframe::{appearance, CellRgb, TermCell};
                        let got = TermCell::rgb(
                            c.contents().as_str(),
                            rgb(c.fgcolor()),
                            rgb(c.bgcolor()),
                        );
                        assert_eq!(
                            appearance(&got),
                            appearance(shown.cell(x, y)),
                            "frame {i} ({x},{y})"
                        );
                    }
                }
            }
        }
        let (s, l, v) = (
            mean_after_first(&stock),
            mean_after_first(&lean),
            mean_after_first(&presented),
        );
        println!(
            "| {level} | {s:.0} | {l:.0} ({:.1} %) | {v:.0} ({:.1} %) |",
            100.0 * l / s,
            100.0 * v / s
        );
        assert!(l <= 1.05 * v, "{level}: lean backend {l} vs presenter {v}");
    }
}

/// Any ratatui app can show a framebuffer in octants: `HalfBlockView` draws an octant-grid
/// frame as octant cells and `LeanBackend` sends those characters as drawn.
#[test]
fn an_octant_frame_reaches_the_terminal_through_the_lean_backend() {
    let world = World::default_world();
    let start = world.map.start;
    let scene = Scene::new(
        &world,
        Camera::from_angle(start.pos(), start.angle_deg(), 66.0),
    );
    let mut fb = Framebuffer::for_glyphs(40, 12, halfcast::Glyphs::Octant);
    scene.render_into(&mut fb, None);
    let out = Capture::default();
    let mut t = fixed(LeanBackend::new(out.clone(), ColorLevel::TrueColor).with_size(COLS, ROWS));
    t.draw(|f| f.render_widget(HalfBlockView::new(&fb), Rect::new(0, 0, 40, 12)))
        .unwrap();
    let text = String::from_utf8(out.take()).unwrap();
    let octants = text
        .chars()
        .filter(|&c| (0x1CD00..=0x1CDE5).contains(&u32::from(c)))
        .count();
    assert!(octants > 40, "{octants} octant cells");
}
