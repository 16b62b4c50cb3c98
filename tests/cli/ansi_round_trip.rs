//! The real bytes read back at the real size: any ratatui buffer (random glyphs, clusters, wide
//! characters, colours of every kind, attributes) drawn through `LeanBackend` or stock
//! `CrosstermBackend` and read back with `termframe::from_ansi_sized` shows the buffer, cell for
//! cell, as far as the terminal model can tell (see `expected`).

use crate::capture::Capture;
use halfcast::termframe::{self, named_colour, TermFrame};
use halfcast::{ColorLevel, LeanBackend};
use proptest::prelude::*;
use ratatui::backend::{Backend, CrosstermBackend};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};

/// What one cell may hold: letters, block characters, a space, clusters with combining marks,
/// wide characters (CJK, an emoji). Not an emoji with a skin tone (`👍🏽`): the vt100 model
/// (0.15) gives the modifier two columns of its own, so every cell after it reads shifted
/// (terminals differ here too); the buffer side keeps it whole (tests/lib/ratatui_dashboard.rs).
const GLYPHS: [&str; 14] = [
    "a",
    "Z",
    "7",
    " ",
    "▀",
    "▄",
    "█",
    "─",
    "é",
    "e\u{301}",
    "e\u{300}",
    "界",
    "👍",
    "ü\u{323}",
];

fn colour() -> impl Strategy<Value = Color> {
    prop_oneof![
        Just(Color::Reset),
        (0u8..16).prop_map(|n| named_colour(n).unwrap()),
        any::<u8>().prop_map(Color::Indexed),
        any::<(u8, u8, u8)>().prop_map(|(r, g, b)| Color::Rgb(r, g, b)),
    ]
}

fn style() -> impl Strategy<Value = Style> {
    (colour(), colour(), colour(), any::<u16>()).prop_map(|(fg, bg, ul, m)| {
        Style::new()
            .fg(fg)
            .bg(bg)
            .underline_color(ul)
            .add_modifier(Modifier::from_bits_truncate(m))
    })
}

/// A buffer of `cols` × `rows` filled row by row with random clusters in random styles (a wide
/// one that would not fit at a row's end is left out, as ratatui leaves it).
fn buffer() -> impl Strategy<Value = Buffer> {
    (1u16..16, 1u16..6).prop_flat_map(|(cols, rows)| {
        let n = usize::from(cols) * usize::from(rows);
        prop::collection::vec((0..GLYPHS.len(), style()), n).prop_map(move |cells| {
            let mut buf = Buffer::empty(Rect::new(0, 0, cols, rows));
            let mut cells = cells.into_iter();
            for y in 0..rows {
                let mut x = 0;
                while x < cols {
                    let (g, style) = cells.next().unwrap();
                    let end = buf.set_stringn(x, y, GLYPHS[g], usize::from(cols - x), style);
                    x = end.0.max(x + 1);
                }
            }
            buf
        })
    })
}

/// The buffer as the vt100 model can show it: it keeps bold, italic, underlined and reversed
/// (not dim, blinking, hidden, crossed out, nor the underline colour), and reads colours 0–15
/// as named however they were sent (`Indexed(2)` is `ESC[32m` on the wire, as `Green` is).
fn expected(buf: &Buffer) -> TermFrame {
    let kept = Modifier::BOLD | Modifier::ITALIC | Modifier::UNDERLINED | Modifier::REVERSED;
    let named = |c: Color| match c {
        Color::Indexed(n) => named_colour(n).unwrap_or(c),
        c => c,
    };
    let mut frame = TermFrame::from(buf);
    for c in &mut frame.cells {
        c.modifiers &= kept;
        c.underline = Color::Reset;
        c.fg = named(c.fg);
        c.bg = named(c.bg);
    }
    frame
}

/// Draws `buf` on a blank terminal through `backend`, as ratatui's first frame does.
fn draw<B: Backend>(backend: &mut B, buf: &Buffer) {
    let updates = Buffer::empty(buf.area).diff(buf);
    backend.draw(updates.into_iter()).ok().unwrap();
    backend.flush().ok().unwrap();
}

fn assert_shows(bytes: &[u8], buf: &Buffer, backend: &str) {
    let (cols, rows) = (buf.area.width, buf.area.height);
    let seen = termframe::from_ansi_sized(bytes, cols, rows);
    let report = termframe::diff(&expected(buf), &seen);
    assert!(
        report.is_equal(),
        "{backend}: {}\n{:?}",
        report.summary(),
        String::from_utf8_lossy(bytes)
    );
}

#[test]
fn the_re_exported_terminal_model_reads_the_same_screen() {
    // A test that builds its own parser uses halfcast's vt100, so the types match.
    let bytes = b"\x1b[2;3H\x1b[1;4;38;5;120mhi\x1b[0m";
    let mut parser = halfcast::vt100::Parser::new(5, 20, 0);
    parser.process(bytes);
    let own = TermFrame::from(parser.screen());
    assert_eq!(own, termframe::from_ansi_sized(bytes, 20, 5));
    assert_eq!(
        own.cell(3, 1).modifiers,
        Modifier::BOLD | Modifier::UNDERLINED
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn lean_backend_bytes_read_back_as_the_buffer(buf in buffer()) {
        let (cols, rows) = (buf.area.width, buf.area.height);
        let mut lean = LeanBackend::new(Vec::new(), ColorLevel::TrueColor).with_size(cols, rows);
        draw(&mut lean, &buf);
        assert_shows(lean.writer(), &buf, "LeanBackend");
    }

    #[test]
    fn crossterm_backend_bytes_read_back_as_the_buffer(buf in buffer()) {
        let out = Capture::default();
        let mut stock = CrosstermBackend::new(out.clone());
        draw(&mut stock, &buf);
        assert_shows(&out.take(), &buf, "CrosstermBackend");
    }
}
