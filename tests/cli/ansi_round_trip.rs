//! The real bytes read back at the real size: any ratatui buffer (random grapheme clusters of
//! every kind a buffer holds, colours of every kind, every attribute, underline colours) drawn
//! through `LeanBackend` or stock `CrosstermBackend` and read back with
//! `termframe::from_ansi_sized` (ratatui-cells' one-pass reader) is the buffer, cell for cell,
//! strictly.

use crate::capture::Capture;
use halfcast::termframe::{self, named_colour, TermFrame};
use halfcast::{ColorLevel, LeanBackend};
use proptest::prelude::*;
use ratatui::backend::{Backend, CrosstermBackend};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};

/// What one cell may hold: letters, block characters, a space, clusters with combining marks,
/// wide characters (CJK, Hangul), emoji with a skin tone, flags, ZWJ sequences (a family, a
/// rainbow flag, a technologist with a skin tone), keycaps, emoji made so by VS16, a halfwidth
/// letter with its sound mark, Devanagari and Thai clusters, a tag-sequence flag, a soft
/// hyphen, a letter in an enclosing keycap, a fullwidth letter. Not a lone regional indicator or
/// skin-tone modifier: two such neighbours are one cluster in the bytes (see ratatui-cells'
/// README, "What cannot come back").
const GLYPHS: [&str; 36] = [
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
    "👍🏽",
    "🇯🇵",
    "🇫🇷",
    "👨\u{200d}👩\u{200d}👧",
    "🏳\u{fe0f}\u{200d}🌈",
    "👩🏾\u{200d}💻",
    "1\u{fe0f}\u{20e3}",
    "#\u{fe0f}\u{20e3}",
    "❤\u{fe0f}",
    "☺\u{fe0f}",
    "한",
    "\u{1100}\u{1161}\u{11a8}",
    "ｱ\u{ff9f}",
    "क्षि",
    "กำ",
    "ℹ\u{fe0f}",
    "🏴\u{e0067}\u{e0062}\u{e0073}\u{e0063}\u{e0074}\u{e007f}",
    "🧑🏻\u{200d}🤝\u{200d}🧑🏿",
    "\u{ad}",
    "a\u{20e3}",
    "界\u{fe0f}",
    "Ａ",
];

fn colour() -> impl Strategy<Value = Color> {
    prop_oneof![
        Just(Color::Reset),
        (0u8..16).prop_map(|n| named_colour(n).unwrap()),
        any::<u8>().prop_map(Color::Indexed),
        any::<(u8, u8, u8)>().prop_map(|(r, g, b)| Color::Rgb(r, g, b)),
    ]
}

/// A random style; with `both_blinks` false, never slow and rapid blink together (see
/// `crossterm_backend_drops_a_blink_lean_backend_keeps`).
fn style(both_blinks: bool) -> impl Strategy<Value = Style> {
    (colour(), colour(), colour(), any::<u16>()).prop_map(move |(fg, bg, ul, m)| {
        let mut m = Modifier::from_bits_truncate(m);
        if !both_blinks && m.contains(Modifier::SLOW_BLINK) {
            m.remove(Modifier::RAPID_BLINK);
        }
        Style::new()
            .fg(fg)
            .bg(bg)
            .underline_color(ul)
            .add_modifier(m)
    })
}

/// A buffer of `cols` × `rows` filled row by row with random clusters in random styles (a wide
/// one that would not fit at a row's end is left out, as ratatui leaves it).
fn buffer(both_blinks: bool) -> impl Strategy<Value = Buffer> {
    (1u16..16, 1u16..6).prop_flat_map(move |(cols, rows)| {
        let n = usize::from(cols) * usize::from(rows);
        prop::collection::vec((0..GLYPHS.len(), style(both_blinks)), n).prop_map(move |cells| {
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

/// The buffer as the terminal shows it, with `Indexed(0..16)` as the named colour it selects
/// (`Indexed(2)` and `Green` are the same bytes, `ESC[38;5;2m`, and the same palette entry).
fn expected(buf: &Buffer) -> TermFrame {
    let named = |c: Color| match c {
        Color::Indexed(n) => named_colour(n).unwrap_or(c),
        c => c,
    };
    let mut frame = TermFrame::from(buf);
    for c in &mut frame.cells {
        c.fg = named(c.fg);
        c.bg = named(c.bg);
        c.underline = named(c.underline);
    }
    frame
}

/// Draws `buf` on a blank terminal through `backend`, as ratatui's first frame does.
fn draw<B: Backend>(backend: &mut B, buf: &Buffer) {
    let updates = Buffer::empty(buf.area).diff(buf);
    backend.draw(updates.into_iter()).ok().unwrap();
    backend.flush().ok().unwrap();
}

/// Reads `bytes` back at the buffer's size and compares strictly: every part of every cell.
fn assert_shows(bytes: &[u8], buf: &Buffer, backend: &str) {
    let (cols, rows) = (buf.area.width, buf.area.height);
    let seen = termframe::from_ansi_sized(bytes, cols, rows);
    let report = termframe::diff_strict(&expected(buf), &seen);
    assert!(
        report.is_equal(),
        "{backend}: {}\n{:?}",
        report.summary(),
        String::from_utf8_lossy(bytes)
    );
}

/// Reads `bytes` back and compares what the screen shows (`LeanBackend` by default may draw a
/// plain `▀` as `▄`, a space or `█` with the colours arranged to match).
fn assert_looks(bytes: &[u8], buf: &Buffer) {
    let (cols, rows) = (buf.area.width, buf.area.height);
    let seen = termframe::from_ansi_sized(bytes, cols, rows);
    let report = termframe::diff(&expected(buf), &seen);
    assert!(
        report.is_equal(),
        "LeanBackend: {}\n{:?}",
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
    let own = termframe::from_parser(&parser);
    assert_eq!(own, termframe::from_ansi_sized(bytes, 20, 5));
    assert_eq!(
        own.cell(3, 1).modifiers,
        Modifier::BOLD | Modifier::UNDERLINED
    );
}

/// Found by the property: going from slow + rapid blink to rapid blink alone, ratatui's
/// crossterm backend (ratatui-crossterm 0.1.2) sends "no blink" (SGR 25, which ends both) and
/// does not switch rapid blink back on, so the terminal shows the cell without blinking.
/// `LeanBackend` sends 25 and then 6.
#[test]
fn crossterm_backend_drops_a_blink_lean_backend_keeps() {
    let mut buf = Buffer::empty(Rect::new(0, 0, 2, 1));
    let both = Modifier::SLOW_BLINK | Modifier::RAPID_BLINK;
    buf.set_string(0, 0, "a", Style::new().add_modifier(both));
    buf.set_string(1, 0, "b", Style::new().add_modifier(Modifier::RAPID_BLINK));
    let mut lean = LeanBackend::new(Vec::new(), ColorLevel::TrueColor).with_size(2, 1);
    draw(&mut lean, &buf);
    let lean_seen = termframe::from_ansi_sized(lean.writer(), 2, 1);
    assert_eq!(lean_seen.cell(1, 0).modifiers, Modifier::RAPID_BLINK);
    let out = Capture::default();
    draw(&mut CrosstermBackend::new(out.clone()), &buf);
    let stock_seen = termframe::from_ansi_sized(&out.take(), 2, 1);
    assert_eq!(stock_seen.cell(0, 0).modifiers, both);
    assert_eq!(stock_seen.cell(1, 0).modifiers, Modifier::empty());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn lean_backend_bytes_read_back_as_the_buffer(buf in buffer(true)) {
        let (cols, rows) = (buf.area.width, buf.area.height);
        let mut lean = LeanBackend::new(Vec::new(), ColorLevel::TrueColor)
            .with_size(cols, rows)
            .keeping_glyphs();
        draw(&mut lean, &buf);
        assert_shows(lean.writer(), &buf, "LeanBackend");
    }

    #[test]
    fn lean_backend_bytes_look_as_the_buffer_when_it_plans_half_blocks(buf in buffer(true)) {
        let (cols, rows) = (buf.area.width, buf.area.height);
        let mut lean = LeanBackend::new(Vec::new(), ColorLevel::TrueColor).with_size(cols, rows);
        draw(&mut lean, &buf);
        assert_looks(lean.writer(), &buf);
    }

    #[test]
    fn crossterm_backend_bytes_read_back_as_the_buffer(buf in buffer(false)) {
        let out = Capture::default();
        let mut stock = CrosstermBackend::new(out.clone());
        draw(&mut stock, &buf);
        assert_shows(&out.take(), &buf, "CrosstermBackend");
    }
}
