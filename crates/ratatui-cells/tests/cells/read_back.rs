//! Bytes a ratatui backend sends, read back: the buffer again, strictly, for every kind of
//! grapheme cluster a buffer holds, every attribute and every kind of colour.

use proptest::prelude::*;
use ratatui::backend::{Backend, CrosstermBackend};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui_cells::ansi::Screen;
use ratatui_cells::colour::named_colour;
use ratatui_cells::{diff, from_ansi_sized, TermFrame};

/// Clusters of every kind: ASCII, blocks, combining marks, CJK, Hangul (precomposed and as
/// jamo), emoji with skin tones, flags (a tag sequence too), ZWJ sequences, keycaps, VS16 and
/// VS15 emoji, a halfwidth letter with its sound mark, Devanagari, Thai, Tamil, Arabic and
/// Hebrew clusters, a soft hyphen, a fullwidth letter.
const GLYPHS: [&str; 36] = [
    "a",
    " ",
    "▀",
    "▄",
    "e\u{301}",
    "ü\u{323}",
    "界",
    "한",
    "\u{1100}\u{1161}\u{11a8}",
    "👍",
    "👍🏽",
    "👍🏿",
    "🇯🇵",
    "🇺🇸",
    "👨\u{200d}👩\u{200d}👧\u{200d}👦",
    "🏳\u{fe0f}\u{200d}🌈",
    "👩🏾\u{200d}💻",
    "1\u{fe0f}\u{20e3}",
    "*\u{fe0f}\u{20e3}",
    "❤\u{fe0f}",
    "✌\u{fe0f}",
    "ｶ\u{ff9e}",
    "क्षि",
    "กำ",
    "x",
    "─",
    "🏴\u{e0067}\u{e0062}\u{e0073}\u{e0063}\u{e0074}\u{e007f}",
    "🧑🏻\u{200d}🤝\u{200d}🧑🏿",
    "\u{ad}",
    "لا",
    "שָׁ",
    "a\u{20e3}",
    "界\u{fe0f}",
    "நி",
    "☺\u{fe0e}",
    "Ａ",
];

/// What ratatui sends for a first frame: the diff from a blank screen, through crossterm.
fn crossterm_bytes(buf: &Buffer) -> Vec<u8> {
    let mut bytes = Vec::new();
    let mut backend = CrosstermBackend::new(&mut bytes);
    backend
        .draw(Buffer::empty(buf.area).diff(buf).into_iter())
        .unwrap();
    Backend::flush(&mut backend).unwrap();
    bytes
}

/// The buffer with `Indexed(0..16)` as the named colour it is sent as.
fn expected(buf: &Buffer) -> TermFrame {
    let named = |c: Color| match c {
        Color::Indexed(n) => named_colour(n).unwrap_or(c),
        c => c,
    };
    let mut frame = TermFrame::from(buf);
    for c in &mut frame.cells {
        (c.fg, c.bg, c.underline) = (named(c.fg), named(c.bg), named(c.underline));
    }
    frame
}

fn assert_reads_back(buf: &Buffer) {
    let bytes = crossterm_bytes(buf);
    let seen = from_ansi_sized(&bytes, buf.area.width, buf.area.height);
    let report = diff(&expected(buf), &seen);
    assert!(
        report.is_equal(),
        "{}\n{:?}",
        report.summary(),
        String::from_utf8_lossy(&bytes)
    );
}

#[test]
fn every_listed_cluster_reads_back_whole_in_a_row() {
    let mut buf = Buffer::empty(Rect::new(0, 0, 60, 2));
    let style = Style::new()
        .fg(Color::Rgb(9, 8, 7))
        .add_modifier(Modifier::UNDERLINED);
    buf.set_string(0, 0, GLYPHS[..13].concat(), style);
    buf.set_string(
        0,
        1,
        GLYPHS[13..].concat(),
        style.underline_color(Color::Indexed(100)),
    );
    assert_reads_back(&buf);
}

#[test]
fn a_flag_and_a_skin_tone_take_the_two_columns_ratatui_gives_them() {
    let mut screen = Screen::new(8, 1);
    screen.process("🇯🇵👍🏽ab".as_bytes());
    let frame = screen.frame();
    assert_eq!(frame.cell(0, 0).glyph, "🇯🇵");
    assert!(frame.cell(1, 0).glyph.is_continuation());
    assert_eq!(frame.cell(2, 0).glyph, "👍🏽");
    assert_eq!(frame.cell(4, 0).glyph, 'a');
    assert_eq!(screen.cursor(), (6, 0));
}

#[test]
fn bytes_split_anywhere_read_the_same() {
    let mut buf = Buffer::empty(Rect::new(0, 0, 12, 1));
    buf.set_string(
        0,
        0,
        "e\u{301}👨\u{200d}👩\u{200d}👧🇯🇵",
        Style::new().fg(Color::Rgb(1, 2, 3)),
    );
    let bytes = crossterm_bytes(&buf);
    let whole = from_ansi_sized(&bytes, 12, 1);
    for cut in 0..bytes.len() {
        let mut screen = Screen::new(12, 1);
        screen.process(&bytes[..cut]);
        screen.process(&bytes[cut..]);
        assert_eq!(screen.frame(), whole, "cut at {cut}");
    }
}

fn colour() -> impl Strategy<Value = Color> {
    prop_oneof![
        Just(Color::Reset),
        (0u8..16).prop_map(|n| named_colour(n).unwrap()),
        any::<u8>().prop_map(Color::Indexed),
        any::<(u8, u8, u8)>().prop_map(|(r, g, b)| Color::Rgb(r, g, b)),
    ]
}

/// A random style, never slow and rapid blink together: crossterm's backend (ratatui-crossterm
/// 0.1.2) switches both off with SGR 25 when only one goes, and does not send the other again.
fn style() -> impl Strategy<Value = Style> {
    (colour(), colour(), colour(), any::<u16>()).prop_map(|(fg, bg, ul, m)| {
        let mut m = Modifier::from_bits_truncate(m);
        if m.contains(Modifier::SLOW_BLINK) {
            m.remove(Modifier::RAPID_BLINK);
        }
        Style::new()
            .fg(fg)
            .bg(bg)
            .underline_color(ul)
            .add_modifier(m)
    })
}

/// A buffer of random clusters in random styles, row by row (a wide one that would not fit at
/// a row's end is left out, as ratatui leaves it).
fn buffer() -> impl Strategy<Value = Buffer> {
    (1u16..14, 1u16..5).prop_flat_map(|(cols, rows)| {
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

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn crossterm_backend_bytes_read_back_as_the_buffer(buf in buffer()) {
        assert_reads_back(&buf);
    }
}
