//! The draw stage of a frame: lays the panes out in a terminal buffer. Reads state only.

use std::cell::RefCell;

use ratatui::buffer::{Buffer, Cell};
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Clear, Paragraph, Widget, Wrap};

use super::help::HelpOverlay;
use super::keymap::KeyMap;
use super::keys::InputMode;
use super::layout::{Panes, Toggles, MIN_SIZE};
use super::stats::FrameStats;
use super::status::{status_line, BAR};
use crate::encode::ColorLevel;
use crate::game::{Cursor, GameState};
use crate::render::cast::Cast;
use crate::render::framebuffer::Framebuffer;
use crate::widget::half_block::{row_cells, VIEW_CELL};
use crate::widget::minimap::Thing;
use crate::widget::{DebugPane, HalfBlockView, Minimap, RevealedTrace};

/// What a loop keeps for [`Screen::ray_text`].
pub use crate::widget::KeptLines;

const BORDER: Style = Style::new().fg(Color::Rgb(84, 90, 112));
const TITLE: Style = Style::new()
    .fg(Color::Rgb(110, 200, 230))
    .add_modifier(Modifier::BOLD);

/// Everything one frame shows, borrowed from the loop.
#[derive(Debug, Clone, Copy)]
pub struct Screen<'a> {
    pub state: &'a GameState,
    /// The 3D view, already rendered at the view pane's size.
    pub view: &'a Framebuffer,
    /// This frame's rays, with the debugged column's trace.
    pub cast: &'a Cast,
    pub stats: &'a FrameStats,
    pub toggles: Toggles,
    pub input_mode: InputMode,
    /// The results screen over everything, once the level's exit is reached.
    pub results: Option<&'a super::results::Results>,
    /// The ray pane's lines of the last frame, kept by a loop that draws every frame so an
    /// unchanged ray is not written out again (`None`: written each time).
    pub ray_text: Option<&'a RefCell<KeptLines>>,
}

/// Draws the 3D view pane. The one place the view reaches the terminal buffer, so a byte-lean
/// encoder can replace it (write the region itself, mark these cells as skipped for ratatui).
pub fn draw_view(fb: &Framebuffer, area: Rect, buf: &mut Buffer) {
    HalfBlockView::new(fb).render(area, buf);
}

/// What the view's cells hold in the buffer a frame is drawn into.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ViewCells {
    /// The view as [`HalfBlockView`] draws it: the buffer alone is the whole screen.
    Drawn,
    /// [`VIEW_CELL`]: the presenter (`crate::present`) encodes the view straight from the
    /// framebuffer, so nobody chooses its cells a second time.
    Presented,
}

/// Draws a whole frame into `buf` within `area`, per `panes` (from [`Panes::compute`]), with
/// the help listing the default keys.
pub fn draw(screen: &Screen, panes: &Panes, area: Rect, buf: &mut Buffer) {
    draw_with_keys(screen, panes, area, buf, KeyMap::shared_default());
}

/// [`draw`] with the help listing `keys` (the player's bindings).
pub fn draw_with_keys(screen: &Screen, panes: &Panes, area: Rect, buf: &mut Buffer, keys: &KeyMap) {
    draw_frame(screen, panes, area, buf, keys, ViewCells::Drawn);
}

/// [`draw_with_keys`] for a frame the presenter (`crate::present`) sends: the view's cells are
/// left as `VIEW_CELL` (anything drawn over them stays on top), and the presenter puts the
/// view there from the framebuffer.
pub fn draw_for_presenter(
    screen: &Screen,
    panes: &Panes,
    area: Rect,
    buf: &mut Buffer,
    keys: &KeyMap,
) {
    draw_frame(screen, panes, area, buf, keys, ViewCells::Presented);
}

fn draw_frame(
    screen: &Screen,
    panes: &Panes,
    area: Rect,
    buf: &mut Buffer,
    keys: &KeyMap,
    view_cells: ViewCells,
) {
    let area = area.intersection(buf.area);
    // The view's cells left to the presenter are filled once, not cleared first.
    let presented = match (*panes, view_cells) {
        (Panes::Game { view, .. }, ViewCells::Presented) => view.intersection(area),
        _ => Rect::default(),
    };
    clear_around(area, presented, buf);
    match *panes {
        Panes::TooSmall(r) => too_small(r.intersection(area), buf),
        Panes::Game {
            view,
            minimap,
            debug,
            status,
        } => {
            if view_cells == ViewCells::Drawn {
                draw_view(screen.view, view.intersection(area), buf);
            }
            if let Some(text) = message_now(screen.state) {
                draw_banner(text, view.intersection(area), buf);
            }
            let revealed = screen
                .cast
                .trace
                .as_ref()
                .map(|t| match screen.state.debugger.cursor {
                    Cursor::AtHit => RevealedTrace::full(t),
                    Cursor::Steps(n) => RevealedTrace::partial(t, n),
                });
            if let Some(r) = minimap {
                draw_minimap(screen, revealed, r.intersection(area), buf);
            }
            if let Some(r) = debug {
                draw_debug(
                    screen,
                    revealed,
                    (view.width, view.height),
                    r.intersection(area),
                    buf,
                );
            }
            let steps = screen.cast.trace.as_ref().map(|t| t.steps.len());
            let status = status.intersection(area);
            let line = status_line(
                screen.state,
                screen.stats,
                screen.input_mode,
                steps,
                status.width,
            );
            buf.set_style(status, BAR);
            crate::widget::text::line_row(line, status, buf);
            if screen.toggles.help {
                HelpOverlay {
                    mode: screen.input_mode,
                    keys,
                }
                .render(area, buf);
            }
            if let Some(results) = screen.results {
                results.render(view.intersection(area), buf);
            }
        }
    }
}

/// What `Clear` does to `area` (every cell reset), but with the cells of `view` (within `area`)
/// set to [`VIEW_CELL`] instead, row by row over the buffer's cells: every frame of every SSH
/// session clears its screen, and `Clear` walks it a column at a time through `buf[(x, y)]`.
fn clear_around(area: Rect, view: Rect, buf: &mut Buffer) {
    for y in area.top()..area.bottom() {
        let row = &mut buf.content[row_cells(buf.area, area, y)];
        if view.is_empty() || y < view.top() || y >= view.bottom() {
            row.fill(Cell::EMPTY);
            continue;
        }
        let (l, r) = (
            usize::from(view.left() - area.left()),
            usize::from(view.right() - area.left()),
        );
        row[..l].fill(Cell::EMPTY);
        row[l..r].fill(VIEW_CELL);
        row[r..].fill(Cell::EMPTY);
    }
}

/// How long a game message (a pickup, a locked door) stays over the view, in game seconds.
pub const MESSAGE_SECONDS: f64 = 4.0;

/// The game's message to show this frame, while it is fresh.
#[must_use]
pub fn message_now(state: &GameState) -> Option<&str> {
    state
        .message
        .as_ref()
        .filter(|m| (0.0..MESSAGE_SECONDS).contains(&(state.time - m.at)))
        .map(|m| m.text.as_str())
}

const BANNER: Style = Style::new()
    .bg(Color::Rgb(22, 24, 32))
    .fg(Color::Rgb(255, 226, 140))
    .add_modifier(Modifier::BOLD);

/// A one-row message centred at the top of the view (over it: the presenter draws such cells
/// on top of the view).
pub fn draw_banner(text: &str, view: Rect, buf: &mut Buffer) {
    if view.width < 3 || view.height == 0 {
        return;
    }
    let text = format!(" {text} ");
    let width = (text.chars().count() as u16).min(view.width);
    let x = view.x + (view.width - width) / 2;
    let row = Rect::new(x, view.y, width, 1);
    Clear.render(row, buf);
    buf.set_stringn(x, view.y, &text, usize::from(width), BANNER);
}

/// The game's objects as the minimap shows them: items left (treasure `$`, keys `k` in their
/// colour) and creatures (`c`; grey while tagged).
#[must_use]
pub fn minimap_things(state: &GameState) -> Vec<Thing> {
    let map = &state.world.map;
    let mut out = Vec::new();
    for (k, item) in map.items.iter().enumerate() {
        if state.level.is_taken(k) {
            continue;
        }
        let (colour, glyph) = match &item.key {
            Some(name) => (crate::texture::key_tint::key_colour(name), "k"),
            None => (crate::color::Rgb::new(255, 200, 60), "$"),
        };
        out.push(Thing {
            pos: item.pos,
            colour,
            glyph,
        });
    }
    for c in state.level.creatures() {
        let colour = if c.is_out() {
            crate::color::Rgb::new(120, 120, 130)
        } else {
            crate::color::Rgb::new(230, 70, 200)
        };
        out.push(Thing {
            pos: c.pos,
            colour,
            glyph: "c",
        });
    }
    out
}

fn pane(title: Line<'static>) -> Block<'static> {
    Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(BORDER)
        .title(title)
}

/// Draws a pane's frame, exactly as `pane(title).render(r, buf)` does, and returns the area
/// inside it. Every frame of every SSH session draws two; ratatui's `Block` restyles its whole
/// area and reaches each border cell through a lookup of its own, this walks row slices.
fn draw_pane(r: Rect, title: Line<'static>, buf: &mut Buffer) -> Rect {
    let area = r.intersection(buf.area);
    let inner = Block::bordered().inner(r);
    if area.width < 2 || area.height < 2 {
        // Sides and corners on the same cells: ratatui's order decides which is drawn.
        pane(title).render(r, buf);
        return inner;
    }
    let set = ratatui::symbols::border::ROUNDED;
    let (top, bottom) = (area.top(), area.bottom() - 1);
    for y in top..=bottom {
        let row = &mut buf.content[row_cells(buf.area, area, y)];
        let last = row.len() - 1;
        let (left, middle, right) = if y == top {
            (set.top_left, Some(set.horizontal_top), set.top_right)
        } else if y == bottom {
            (
                set.bottom_left,
                Some(set.horizontal_bottom),
                set.bottom_right,
            )
        } else {
            (set.vertical_left, None, set.vertical_right)
        };
        row[0].set_symbol(left).set_style(BORDER);
        if let Some(m) = middle {
            for c in &mut row[1..last] {
                c.set_symbol(m).set_style(BORDER);
            }
        }
        row[last].set_symbol(right).set_style(BORDER);
    }
    let room = area.width - 2;
    if room > 0 {
        let width = u16::try_from(title.width()).unwrap_or(u16::MAX).min(room);
        title.render(Rect::new(area.x + 1, top, width, 1), buf);
    }
    inner
}

fn draw_minimap(screen: &Screen, revealed: Option<RevealedTrace>, r: Rect, buf: &mut Buffer) {
    let inner = draw_pane(r, Line::from(Span::styled(" map ", TITLE)), buf);
    let s = screen.state;
    let things = minimap_things(s);
    let mut map = Minimap::new(&s.world, &s.camera, &screen.cast.columns)
        .ascii(screen.stats.level.map(|c| c.level) == Some(ColorLevel::Mono))
        .focus_on_ray(s.debugger.paused)
        .doors(&s.doors)
        .things(&things);
    if let Some(t) = revealed {
        map = map.debug_ray(t);
    }
    map.render(inner, buf);
}

fn draw_debug(
    screen: &Screen,
    revealed: Option<RevealedTrace>,
    view_cells: (u16, u16),
    r: Rect,
    buf: &mut Buffer,
) {
    let s = screen.state;
    let mut title = vec![Span::styled(" ray ", TITLE)];
    if let Some(t) = &revealed {
        title.push(Span::styled(
            format!("- column {} ", t.trace.column),
            BORDER,
        ));
    }
    if s.debugger.paused {
        title.push(Span::styled(
            "- paused ",
            Style::new().fg(Color::Rgb(255, 214, 64)),
        ));
    }
    let inner = draw_pane(r, Line::from(title), buf);
    if let Some(t) = revealed {
        let cells = (usize::from(view_cells.0), usize::from(view_cells.1));
        let mono = screen.stats.level.map(|c| c.level) == Some(ColorLevel::Mono);
        let mut pane = DebugPane::new(t, &s.world, &s.camera, cells)
            .scroll(s.debugger.scroll)
            .scroll_into_setup(s.debugger.into_setup)
            .ascii(mono);
        if let Some(col) = screen.cast.heights.get(t.trace.column) {
            pane = pane.heights(col);
        }
        match screen.ray_text {
            Some(kept) => pane.render_kept(inner, buf, &mut kept.borrow_mut()),
            None => pane.render(inner, buf),
        }
    }
}

/// A note over the status line (replacing it while it shows), e.g. that a pane is hidden.
pub fn draw_notice(text: &str, status: Rect, buf: &mut Buffer) {
    let status = status.intersection(buf.area);
    buf.set_style(status, BAR);
    Clear.render(status, buf);
    buf.set_style(status, BAR.add_modifier(Modifier::BOLD));
    buf.set_stringn(
        status.x + 1,
        status.y,
        text,
        usize::from(status.width.saturating_sub(1)),
        BAR.add_modifier(Modifier::BOLD),
    );
}

fn too_small(r: Rect, buf: &mut Buffer) {
    let text = format!(
        "terminal too small: {}x{} (need {}x{})",
        r.width, r.height, MIN_SIZE.0, MIN_SIZE.1
    );
    let y = r.y + r.height.saturating_sub(2) / 2;
    let msg = Rect::new(r.x, y, r.width, r.height.min(r.bottom() - y));
    Paragraph::new(text)
        .wrap(Wrap { trim: true })
        .centered()
        .render(msg, buf);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pane_frame_is_drawn_as_ratatuis_block_draws_it() {
        let titles = || {
            [
                Line::from(Span::styled(" map ", TITLE)),
                Line::from(vec![
                    Span::styled(" ray ", TITLE),
                    Span::styled("- column 12 ", BORDER),
                ]),
                Line::from(Span::styled(" \u{5730}\u{56f3} map ", TITLE)),
                Line::default(),
            ]
        };
        let screen = Rect::new(0, 0, 12, 7);
        // What was there before (the frame restyles cells, it does not replace them).
        let mut under = Buffer::empty(screen);
        under.set_string(0, 2, "abcdefghijkl", Style::new().bg(Color::Rgb(9, 8, 7)));
        under.set_style(
            Rect::new(3, 0, 4, 7),
            Style::new().add_modifier(Modifier::BOLD),
        );
        for (w, h) in (0..=12).flat_map(|w| (0..=7).map(move |h| (w, h))) {
            for (x, y) in [(0, 0), (2, 1), (9, 5)] {
                for (a, b) in titles().into_iter().zip(titles()) {
                    let r = Rect::new(x, y, w, h);
                    let mut ours = under.clone();
                    let mut theirs = under.clone();
                    let inner = draw_pane(r, a, &mut ours);
                    let block = pane(b);
                    assert_eq!(inner, block.inner(r), "{r:?}");
                    block.render(r, &mut theirs);
                    assert_eq!(ours, theirs, "{r:?}");
                }
            }
        }
    }
}
