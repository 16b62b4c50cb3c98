//! Stock ratatui (`Terminal<CrosstermBackend<Vec<u8>>>`) drawing the same half-block cells: the
//! baseline the encoder's byte counts are compared with.

use std::cell::RefCell;
use std::io::Write;
use std::rc::Rc;

use ratatui::backend::CrosstermBackend;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::{Terminal, TerminalOptions, Viewport};

use crate::encode::palette::Palette;
use crate::encode::quantize::mono_char;
use crate::encode::ColorLevel;
use crate::render::framebuffer::Framebuffer;

/// An in-memory writer the reference can read back (the backend's own accessor is unstable).
#[derive(Clone, Default)]
struct Capture(Rc<RefCell<Vec<u8>>>);

impl Write for Capture {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.borrow_mut().extend_from_slice(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// A ratatui terminal writing into memory, at a fixed size, drawing `▀` with fg/bg per cell.
pub struct RatatuiReference {
    terminal: Terminal<CrosstermBackend<Capture>>,
    bytes: Capture,
    palette: Palette,
}

impl RatatuiReference {
    /// A reference terminal of `cols × rows` cells at `level` (colours mapped as the encoder maps).
    ///
    /// # Panics
    /// Never in practice: a fixed viewport asks nothing of the (in-memory) backend.
    #[must_use]
    pub fn new(cols: u16, rows: u16, level: ColorLevel) -> Self {
        let bytes = Capture::default();
        let backend = CrosstermBackend::new(bytes.clone());
        let terminal = Terminal::with_options(
            backend,
            TerminalOptions {
                viewport: Viewport::Fixed(Rect::new(0, 0, cols, rows)),
            },
        )
        .expect("a fixed viewport needs no terminal");
        Self {
            terminal,
            bytes,
            palette: Palette::new(level),
        }
    }

    /// Draws `fb` and returns the bytes ratatui wrote for it.
    ///
    /// # Panics
    /// Never: writing to memory cannot fail.
    pub fn draw(&mut self, fb: &Framebuffer) -> Vec<u8> {
        self.bytes.0.borrow_mut().clear();
        let palette = &self.palette;
        self.terminal
            .draw(|frame| {
                let buf = frame.buffer_mut();
                let area = buf.area;
                for cy in 0..usize::from(area.height).min(fb.cell_rows()) {
                    for cx in 0..usize::from(area.width).min(fb.width()) {
                        let (t, b) = fb.cell(cx, cy);
                        let cell = &mut buf[(cx as u16, cy as u16)];
                        if palette.level() == ColorLevel::Mono {
                            cell.set_char(mono_char(t, b));
                            continue;
                        }
                        let colour = |c| {
                            let code = palette.code(c);
                            match palette.level() {
                                ColorLevel::TrueColor => {
                                    Color::Rgb((code >> 16) as u8, (code >> 8) as u8, code as u8)
                                }
                                _ => Color::Indexed(code as u8),
                            }
                        };
                        cell.set_char('▀').set_fg(colour(t)).set_bg(colour(b));
                    }
                }
            })
            .expect("writing to memory cannot fail");
        std::mem::take(&mut *self.bytes.0.borrow_mut())
    }
}
