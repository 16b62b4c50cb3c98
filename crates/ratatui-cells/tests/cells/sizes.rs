//! The sizes the README states, measured on a chat screen drawn with ratatui's widgets at
//! 80×24 and 60×16: the cells text against what insta stores for a `Buffer`'s `Debug` and a
//! `TestBackend`'s `Display`. The README's sentence must hold these very numbers.

use ratatui::backend::TestBackend;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style, Stylize};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Gauge, List, Paragraph};
use ratatui::Terminal;
use ratatui_cells::cells_text;

/// A chat app: a title bar, messages from people with coloured names (a flag, skin tones, a
/// ZWJ family, a keycap, CJK names), an unread marker with an underline colour, an upload
/// gauge and a popup over it all.
fn chat(cols: u16, rows: u16) -> Terminal<TestBackend> {
    let mut terminal = Terminal::new(TestBackend::new(cols, rows)).unwrap();
    terminal
        .draw(|frame| {
            let [top, body, gauge, status] = Layout::vertical([
                Constraint::Length(1),
                Constraint::Fill(1),
                Constraint::Length(1),
                Constraint::Length(1),
            ])
            .areas(frame.area());
            frame.render_widget(
                Line::from(" #general · 5 online ".bold()).style(Style::new().bg(Color::Blue)),
                top,
            );
            let say = |who: &str, colour: Color, text: &str| {
                Line::from(vec![
                    Span::styled(format!("{who}: "), Style::new().fg(colour).bold()),
                    Span::raw(text.to_string()),
                ])
            };
            let unread = Style::new()
                .add_modifier(Modifier::UNDERLINED)
                .underline_color(Color::Rgb(255, 99, 71));
            let messages = List::new([
                say("Aiko 🇯🇵", Color::Cyan, "おはよう! 👋🏽"),
                say("Bram", Color::Indexed(208), "family photo 👨‍👩‍👧 coming up"),
                say("李雷", Color::Green, "meeting at 3️⃣ in room 界"),
                say("Zoë", Color::Rgb(200, 120, 255), "👍🏿 sounds good"),
                Line::from("── new messages ──").style(unread),
                say("Aiko 🇯🇵", Color::Cyan, "see you there ❤️"),
            ])
            .block(Block::bordered().title("messages"));
            frame.render_widget(messages, body);
            frame.render_widget(
                Gauge::default()
                    .gauge_style(Style::new().fg(Color::Green).bg(Color::DarkGray))
                    .percent(42)
                    .label("upload 42%"),
                gauge,
            );
            frame.render_widget(
                Paragraph::new(" ctrl-q quit · ↑↓ scroll").style(Style::new().reversed()),
                status,
            );
            let popup = Rect::new(cols / 4, rows / 3, cols / 2, 4);
            frame.render_widget(Clear, popup);
            frame.render_widget(
                Paragraph::new("Send the photo to #general?\n[y] yes  [n] no")
                    .block(Block::bordered().title("confirm").yellow()),
                popup,
            );
        })
        .unwrap();
    terminal
}

/// The three forms' sizes in bytes: cells text, `Debug` (as insta's
/// `assert_debug_snapshot!` writes it), `Display`.
fn sizes(cols: u16, rows: u16) -> (usize, usize, usize) {
    let terminal = chat(cols, rows);
    let backend = terminal.backend();
    (
        cells_text(backend).len(),
        format!("{:#?}", backend.buffer()).len(),
        backend.to_string().len(),
    )
}

/// Thousands with a thin space, as the README writes them.
fn bytes(n: usize) -> String {
    if n < 1000 {
        n.to_string()
    } else {
        format!("{} {:03}", n / 1000, n % 1000)
    }
}

#[test]
fn the_readme_states_the_sizes_measured_here() {
    let readme = include_str!("../../README.md").replace('\n', " ");
    for (cols, rows) in [(80, 24), (60, 16)] {
        let (cells, debug, display) = sizes(cols, rows);
        let claim = format!(
            "{cols}×{rows}: cells text {} B, `Debug` {} B ({}%), `Display` {} B",
            bytes(cells),
            bytes(debug),
            100 * cells / debug,
            bytes(display)
        );
        eprintln!("{claim}");
        assert!(readme.contains(&claim), "the README should say: {claim}");
    }
}
