//! One frame of a [`Scene`] in each form a test or tool needs: ratatui cells, the ANSI bytes a
//! terminal receives, a PNG, and the colour-aware text snapshots pin.

use crate::render::scene::Scene;
use crate::widget::HalfBlockView;

impl Scene<'_> {
    /// The frame as ratatui cells (`▀`, fg = upper pixel, bg = lower), as the TUI's view pane
    /// draws it: for tests of widgets and screens built around the view.
    #[must_use]
    pub fn to_buffer(&self, cols: u16, rows: u16) -> ratatui::buffer::Buffer {
        use ratatui::widgets::Widget;
        let area = ratatui::layout::Rect::new(0, 0, cols, rows);
        let mut buf = ratatui::buffer::Buffer::empty(area);
        HalfBlockView::new(&self.render(cols, rows)).render(area, &mut buf);
        buf
    }

    /// The bytes a truecolor terminal receives to show the frame in one full redraw (the same as
    /// `halfcast render --format ansi --colors truecolor`).
    #[must_use]
    pub fn to_ansi(&self, cols: u16, rows: u16) -> String {
        crate::output::ansi::to_ansi_truecolor(&self.render(cols, rows))
    }

    /// The frame as a PNG of `cols` × 2·`rows` pixels (`halfcast render --format png`).
    ///
    /// # Errors
    /// The PNG encoder's message (it does not fail for in-memory frames in practice).
    pub fn to_png(&self, cols: u16, rows: u16) -> Result<Vec<u8>, String> {
        self.render(cols, rows).to_png()
    }

    /// The frame in the colour-aware text form snapshots pin (`ratatui-cells v1`, see
    /// [`crate::snapshot::cells_text`]), so a test can `insta::assert_snapshot!` it.
    #[must_use]
    pub fn to_cells_text(&self, cols: u16, rows: u16) -> String {
        crate::snapshot::cells_text(&self.render(cols, rows))
    }
}
