//! One frame of a [`Scene`] in each form a test or tool needs: ratatui cells, the ANSI bytes a
//! terminal receives, a PNG, and the colour-aware text snapshots pin.

use crate::encode::{full_frame, ColorLevel, EncodeOptions};
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
    /// `halfcast render --format ansi --colors truecolor`); [`Scene::to_ansi_level`] at
    /// [`ColorLevel::TrueColor`].
    #[must_use]
    pub fn to_ansi(&self, cols: u16, rows: u16) -> String {
        crate::output::ansi::to_ansi_truecolor(&self.render(cols, rows))
    }

    /// The bytes a terminal at `level` receives to show the frame in one full redraw: 24-bit
    /// colours, the 256- or 16-colour palette (with the game's dithering), or mono's plain ASCII
    /// shades. The same bytes as `halfcast render --format ansi --colors LEVEL` writes for this
    /// scene (the command line also draws a level's items and creatures: give it
    /// [`Scene::with_sprites`] with [`Level::sprites`](crate::game::Level::sprites) to match it
    /// on a map with `ITEM` or `CREATURE` lines).
    ///
    /// ```
    /// use halfcast::{Camera, ColorLevel, Scene, World};
    ///
    /// let world = World::default_world();
    /// let start = world.map.start;
    /// let scene = Scene::new(&world, Camera::from_angle(start.pos(), start.angle_deg(), 66.0));
    /// let level: ColorLevel = "256".parse().unwrap(); // as `--colors 256` reads it
    /// let ansi256 = scene.to_ansi_level(80, 24, level);
    /// assert!(ansi256.contains("\x1b[38;5;") && !ansi256.contains("\x1b[38;2;"));
    /// let mono = scene.to_ansi_level(80, 24, ColorLevel::Mono);
    /// assert!(!mono.contains('\x1b') && mono.lines().count() == 24);
    /// assert_eq!(scene.to_ansi_level(80, 24, ColorLevel::TrueColor), scene.to_ansi(80, 24));
    /// ```
    #[must_use]
    pub fn to_ansi_level(&self, cols: u16, rows: u16, level: ColorLevel) -> String {
        let bytes = full_frame(&self.render(cols, rows), &EncodeOptions::new(level));
        String::from_utf8(bytes).expect("the encoder writes ASCII escapes and block glyphs only")
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
