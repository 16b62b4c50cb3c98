//! A ratatui [`Backend`] that writes the cell diff ratatui computes with halfcast's byte-lean
//! encoding, so any ratatui app sends fewer bytes (over SSH, a serial line, a recording).

use std::io::{self, Write};

use ratatui::backend::{Backend, ClearType, WindowSize};
use ratatui::buffer::Cell;
use ratatui::layout::{Position, Size};

use crate::encode::cells::CellWriter;
use crate::encode::{ColorLevel, SYNC_BEGIN, SYNC_END};

/// A drop-in ratatui backend over any [`Write`]: the same cells as `CrosstermBackend`, fewer bytes.
///
/// - one merged SGR per change (colours and attributes together, only what changed),
/// - the cheapest cursor move between changed cells (`ESC[nC`, `CR LF`, `ESC[nG`, or absolute),
/// - a run of plain `▀` cells (a half-block picture) sent as `▀`, `▄`, a space or `█`, whichever
///   needs fewer colour changes: the screen looks the same, the glyphs may differ
///   ([`LeanBackend::keeping_glyphs`] sends them as drawn, for tests that read the bytes back
///   cell for cell),
/// - colours mapped down the ladder: [`ColorLevel::Ansi256`] / [`ColorLevel::Ansi16`] pick the
///   nearest palette colour in OKLab, [`ColorLevel::Mono`] drops colours,
/// - each [`Backend::flush`] sends the frame as one write wrapped in one DEC 2026 synchronized
///   update (the terminal shows it whole, never torn); a flush with nothing drawn sends nothing.
///
/// Switching an app is one line:
///
/// ```no_run
/// use halfcast::{ColorLevel, LeanBackend};
/// use ratatui::Terminal;
///
/// # fn main() -> std::io::Result<()> {
/// // was: Terminal::new(CrosstermBackend::new(std::io::stdout()))
/// let mut terminal = Terminal::new(LeanBackend::new(std::io::stdout(), ColorLevel::from_env()))?;
/// terminal.draw(|frame| frame.render_widget("hello", frame.area()))?;
/// # Ok(())
/// # }
/// ```
///
/// The terminal's size comes from the terminal itself when the `crossterm` feature is on;
/// otherwise (or for a writer that is not the local terminal, such as an SSH channel) give it
/// with [`LeanBackend::with_size`] and [`LeanBackend::resize`]. The cursor position it reports
/// is where ratatui last put it (asked of the local terminal only with `crossterm` and no fixed
/// size), so an inline viewport on a remote writer starts at the top. Attributes are kept at
/// every level (mono drops colours only). ratatui's underline colour is sent at truecolor and
/// 256 colours (`58:2::R:G:B`, `58:5:N`), not at 16 colours or mono.
#[derive(Debug)]
pub struct LeanBackend<W: Write> {
    writer: W,
    cells: CellWriter,
    /// This frame's bytes, sent by `flush`.
    out: Vec<u8>,
    size: Option<Size>,
    /// Whether the cursor is shown, when known (so a hide per frame costs nothing).
    cursor_shown: Option<bool>,
    /// Where ratatui last put the cursor.
    position: Position,
    sync: bool,
}

impl<W: Write> LeanBackend<W> {
    /// A backend writing to `writer` at `level` (use [`ColorLevel::from_env`] to follow the
    /// environment, as halfcast does).
    pub fn new(writer: W, level: ColorLevel) -> Self {
        Self {
            writer,
            cells: CellWriter::new(level),
            out: Vec::new(),
            size: None,
            cursor_shown: None,
            position: Position::ORIGIN,
            // Mono terminals may not know DEC 2026, and mono frames carry no escapes but moves.
            sync: level != ColorLevel::Mono,
        }
    }

    /// The same backend with a fixed terminal size (columns × rows).
    #[must_use]
    pub fn with_size(mut self, cols: u16, rows: u16) -> Self {
        self.size = Some(Size::new(cols, rows));
        self
    }

    /// Tells the backend the terminal's new size (for writers that cannot be asked).
    pub fn resize(&mut self, cols: u16, rows: u16) {
        self.size = Some(Size::new(cols, rows));
    }

    /// Sends every cell's glyph as drawn. By default a run of plain `▀` cells (a half-block
    /// picture) may go out as `▄`, a space or `█` with the colours arranged to match, whichever
    /// needs fewer colour changes: the screen looks the same, but the bytes read back hold other
    /// glyphs. This keeps them, for a test that compares what is read back cell for cell.
    #[must_use]
    pub fn keeping_glyphs(mut self) -> Self {
        let level = self.level();
        self.cells =
            std::mem::replace(&mut self.cells, CellWriter::new(level)).keeping_half_blocks();
        self
    }

    /// Turns DEC 2026 synchronized updates on or off (on by default, except in mono).
    #[must_use]
    pub fn with_sync(mut self, sync: bool) -> Self {
        self.sync = sync;
        self
    }

    /// The colour level frames are written at.
    #[must_use]
    pub fn level(&self) -> ColorLevel {
        self.cells.level()
    }

    /// The writer (for example the `Vec<u8>` a test or a bench collects frames in).
    #[must_use]
    pub fn writer(&self) -> &W {
        &self.writer
    }

    /// The writer, mutably (to take what was written).
    pub fn writer_mut(&mut self) -> &mut W {
        &mut self.writer
    }
}

#[cfg(feature = "scrolling-regions")]
impl<W: Write> LeanBackend<W> {
    /// Scrolls rows `region` (0-based, end exclusive) by `n` lines: `S` up, `T` down, inside a
    /// scrolling margin that is reset afterwards (which homes the cursor).
    fn scroll_region(&mut self, region: std::ops::Range<u16>, n: u16, dir: u8) -> io::Result<()> {
        if region.is_empty() || n == 0 {
            return Ok(());
        }
        write!(
            self.out,
            "\x1b[{};{}r\x1b[{n}",
            region.start + 1,
            region.end
        )?;
        self.out.extend_from_slice(&[dir]);
        self.out.extend_from_slice(b"\x1b[r");
        self.cells.forget_cursor();
        Ok(())
    }
}

impl<W: Write> Backend for LeanBackend<W> {
    type Error = io::Error;

    fn draw<'a, I>(&mut self, content: I) -> io::Result<()>
    where
        I: Iterator<Item = (u16, u16, &'a Cell)>,
    {
        self.cells.draw(&mut self.out, content);
        Ok(())
    }

    fn append_lines(&mut self, n: u16) -> io::Result<()> {
        self.out.extend(std::iter::repeat_n(b'\n', usize::from(n)));
        self.cells.forget_cursor();
        Ok(())
    }

    fn hide_cursor(&mut self) -> io::Result<()> {
        if self.cursor_shown != Some(false) {
            self.out.extend_from_slice(b"\x1b[?25l");
            self.cursor_shown = Some(false);
        }
        Ok(())
    }

    fn show_cursor(&mut self) -> io::Result<()> {
        if self.cursor_shown != Some(true) {
            self.out.extend_from_slice(b"\x1b[?25h");
            self.cursor_shown = Some(true);
        }
        Ok(())
    }

    fn get_cursor_position(&mut self) -> io::Result<Position> {
        #[cfg(feature = "crossterm")]
        if self.size.is_none() {
            let (x, y) = crossterm::cursor::position()?;
            return Ok(Position::new(x, y));
        }
        Ok(self.position)
    }

    fn set_cursor_position<P: Into<Position>>(&mut self, position: P) -> io::Result<()> {
        let p = position.into();
        self.cells.move_to(&mut self.out, p.x, p.y);
        self.position = p;
        Ok(())
    }

    fn clear(&mut self) -> io::Result<()> {
        self.clear_region(ClearType::All)
    }

    fn clear_region(&mut self, clear_type: ClearType) -> io::Result<()> {
        self.out.extend_from_slice(match clear_type {
            ClearType::All => b"\x1b[2J",
            ClearType::AfterCursor => b"\x1b[J",
            ClearType::BeforeCursor => b"\x1b[1J",
            ClearType::CurrentLine => b"\x1b[2K",
            ClearType::UntilNewLine => b"\x1b[K",
        });
        Ok(())
    }

    fn size(&self) -> io::Result<Size> {
        if let Some(size) = self.size {
            return Ok(size);
        }
        #[cfg(feature = "crossterm")]
        {
            let (cols, rows) = crossterm::terminal::size()?;
            Ok(Size::new(cols, rows))
        }
        #[cfg(not(feature = "crossterm"))]
        Err(io::Error::other(
            "LeanBackend: terminal size unknown; give it with with_size (or enable the `crossterm` feature)",
        ))
    }

    fn window_size(&mut self) -> io::Result<WindowSize> {
        Ok(WindowSize {
            columns_rows: self.size()?,
            pixels: Size::new(0, 0),
        })
    }

    #[cfg(feature = "scrolling-regions")]
    fn scroll_region_up(&mut self, region: std::ops::Range<u16>, n: u16) -> io::Result<()> {
        self.scroll_region(region, n, b'S')
    }

    #[cfg(feature = "scrolling-regions")]
    fn scroll_region_down(&mut self, region: std::ops::Range<u16>, n: u16) -> io::Result<()> {
        self.scroll_region(region, n, b'T')
    }

    fn flush(&mut self) -> io::Result<()> {
        if !self.out.is_empty() {
            let framed = self.sync.then_some((SYNC_BEGIN, SYNC_END));
            let mut frame = Vec::with_capacity(self.out.len() + 16);
            if let Some((begin, _)) = framed {
                frame.extend_from_slice(begin);
            }
            frame.append(&mut self.out);
            if let Some((_, end)) = framed {
                frame.extend_from_slice(end);
            }
            self.writer.write_all(&frame)?;
            // Someone else may write between frames: the next frame starts with an absolute move.
            self.cells.forget_cursor();
        }
        self.writer.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::widgets::Paragraph;
    use ratatui::Terminal;

    fn terminal(level: ColorLevel) -> Terminal<LeanBackend<Vec<u8>>> {
        Terminal::new(LeanBackend::new(Vec::new(), level).with_size(20, 4)).unwrap()
    }

    #[test]
    fn each_draw_is_one_synchronized_update_and_an_unchanged_one_sends_nothing() {
        let mut t = terminal(ColorLevel::TrueColor);
        t.draw(|f| f.render_widget(Paragraph::new("hello"), f.area()))
            .unwrap();
        let first = std::mem::take(t.backend_mut().writer_mut());
        assert!(first.starts_with(SYNC_BEGIN) && first.ends_with(SYNC_END));
        assert_eq!(
            first
                .windows(SYNC_BEGIN.len())
                .filter(|w| *w == SYNC_BEGIN)
                .count(),
            1
        );
        t.draw(|f| f.render_widget(Paragraph::new("hello"), f.area()))
            .unwrap();
        assert!(
            t.backend().writer().is_empty(),
            "{:?}",
            t.backend().writer()
        );
        t.draw(|f| f.render_widget(Paragraph::new("help!"), f.area()))
            .unwrap();
        let third = String::from_utf8(t.backend().writer().clone()).unwrap();
        assert_eq!(third, "\x1b[?2026h\x1b[;4Hp!\x1b[?2026l");
    }

    #[cfg(feature = "scrolling-regions")]
    #[test]
    fn a_scrolled_region_moves_only_its_rows() {
        let mut b = LeanBackend::new(Vec::new(), ColorLevel::TrueColor).with_size(4, 4);
        let mut screen = vt100::Parser::new(4, 4, 0);
        screen.process(b"a\r\nb\r\nc\r\nd");
        b.scroll_region_up(1..3, 1).unwrap();
        b.flush().unwrap();
        screen.process(b.writer());
        assert_eq!(screen.screen().contents(), "a\nc\n\nd");
    }

    #[test]
    fn mono_frames_are_not_wrapped() {
        let mut t = terminal(ColorLevel::Mono);
        t.draw(|f| f.render_widget(Paragraph::new("x"), f.area()))
            .unwrap();
        let bytes = t.backend().writer();
        assert!(!bytes.starts_with(SYNC_BEGIN), "{bytes:?}");
    }

    #[test]
    fn a_given_size_wins_and_without_one_or_a_terminal_it_says_how_to_give_one() {
        let mut b = LeanBackend::new(Vec::new(), ColorLevel::TrueColor).with_size(30, 7);
        assert_eq!(b.size().unwrap(), Size::new(30, 7));
        b.resize(31, 8);
        assert_eq!(b.window_size().unwrap().columns_rows, Size::new(31, 8));
        let b = LeanBackend::new(Vec::new(), ColorLevel::TrueColor);
        if cfg!(not(feature = "crossterm")) {
            let e = b.size().unwrap_err().to_string();
            assert!(e.contains("with_size"), "{e}");
        }
    }

    #[test]
    fn wide_glyphs_and_the_cursor_land_where_ratatui_puts_them() {
        let mut t = terminal(ColorLevel::TrueColor);
        let mut screen = vt100::Parser::new(4, 20, 0);
        for text in ["aコb ok", "aコc no", "xyコ  z"] {
            t.draw(|f| {
                f.render_widget(Paragraph::new(text), f.area());
                f.set_cursor_position((5, 2));
            })
            .unwrap();
            screen.process(&std::mem::take(t.backend_mut().writer_mut()));
            assert_eq!(screen.screen().contents().lines().next(), Some(text));
            assert_eq!(screen.screen().cursor_position(), (2, 5));
            assert!(!screen.screen().hide_cursor());
        }
    }
}
