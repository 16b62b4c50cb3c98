//! Which cells of a screen differ from the last one's: exactly the updates ratatui's
//! `Buffer::diff` finds, found cheaper. Every SSH session diffs its panes each frame, and
//! ratatui's diff asked Unicode for the width of every cell's symbol and compared cells out of
//! line: a tenth of a session's frame. Here the widths of ASCII, box-drawing and block cells,
//! which panes are made of, are known without a lookup, and cells are compared inline.
//!
//! The rules are ratatui's (ratatui-core 0.1): skipped cells are never sent; a wide symbol
//! covers the cells after it; a narrow symbol over a wide one whose style shows on blanks
//! resends the cells the wide one covered; an emoji with VS16 resends the covered cells whose
//! symbol changed. A test holds the two equal on random screens of every kind of cell, so a
//! ratatui whose rules change fails it. Where ratatui's diff panics (a wide symbol in the
//! screen's last cell, which no widget writes) this one does not.

use ratatui::buffer::{Buffer, Cell, CellDiffOption, CellWidth};
use ratatui::style::{Color, Modifier};

/// Modifiers that show on a blank cell (a wide symbol's leftover style is visible).
const VISIBLE_ON_BLANK: Modifier = Modifier::REVERSED
    .union(Modifier::UNDERLINED)
    .union(Modifier::SLOW_BLINK)
    .union(Modifier::RAPID_BLINK)
    .union(Modifier::CROSSED_OUT);

/// The cells of `next` to send over a terminal that shows `prev`, as `(x, y, cell)`, in order
/// (what `prev.diff(next)` returns, wherever that does not panic).
///
/// # Panics
/// If the buffers differ in x, y or width, as ratatui's diff does.
#[must_use]
pub fn cell_diff<'n>(prev: &Buffer, next: &'n Buffer) -> Vec<(u16, u16, &'n Cell)> {
    assert!(
        prev.area.x == next.area.x
            && prev.area.y == next.area.y
            && prev.area.width == next.area.width,
        "buffer areas must have the same x, y and width"
    );
    let (old, new) = (&prev.content, &next.content);
    let len = old.len().min(new.len());
    let w = usize::from(next.area.width).max(1);
    let at = |i: usize| ((i % w) as u16 + next.area.x, (i / w) as u16 + next.area.y);
    let mut out = Vec::new();
    let mut send = |i: usize| {
        let (x, y) = at(i);
        out.push((x, y, &new[i]));
    };
    let mut pos = 0;
    while pos < len {
        let i = pos;
        pos += 1;
        let (cur, was) = (&new[i], &old[i]);
        match cur.diff_option {
            CellDiffOption::Skip => {}
            _ if is_skip(cur) => {}
            CellDiffOption::ForcedWidth(width) => {
                pos = pos.saturating_add(usize::from(width.get()) - 1);
                if cur != was {
                    send(i);
                }
            }
            CellDiffOption::None | CellDiffOption::AlwaysUpdate => {
                let width = usize::from(cell_width(cur));
                if cur.diff_option == CellDiffOption::None && cur == was {
                    pos += width.saturating_sub(1);
                    continue;
                }
                send(i);
                let was_width = usize::from(cell_width(was));
                // The cells this one or the one before covered, and whether to resend them all
                // or only those whose symbol changed.
                let covered = if width > 1 && cur.symbol().contains('\u{FE0F}') {
                    Some(((i + width).min(len), false))
                } else if width > 1 {
                    pos += width - 1;
                    None
                } else if was_width > width
                    && (was.bg != Color::Reset || was.modifier.intersects(VISIBLE_ON_BLANK))
                {
                    Some((i + was_width, true))
                } else {
                    None
                };
                if let Some((mut end, all)) = covered {
                    // Past the shorter screen only where ratatui would index past it too (a
                    // taller `next`); never past `next`, where ratatui would panic.
                    let mut j = i + 1;
                    while j < end && j < new.len() {
                        let c = &new[j];
                        let k = j;
                        j += usize::from(cell_width(c).max(1));
                        end = end.max(j).min(len);
                        if !is_skip(c) && (all || old[k].symbol() != c.symbol()) {
                            send(k);
                        }
                    }
                    pos = end;
                }
            }
        }
    }
    out
}

/// Whether ratatui's diff leaves `cell` alone (its skip option, or the old skip flag).
#[allow(deprecated)]
fn is_skip(cell: &Cell) -> bool {
    cell.diff_option == CellDiffOption::Skip
        || (cell.skip && cell.diff_option == CellDiffOption::None)
}

/// The columns a cell takes, as ratatui counts them: one for ASCII, box drawing and block
/// elements (U+2500–U+259F, what pane frames and the view are drawn with), else ratatui's own
/// count.
#[inline]
fn cell_width(cell: &Cell) -> u16 {
    if let CellDiffOption::ForcedWidth(w) = cell.diff_option {
        return w.get();
    }
    let s = cell.symbol().as_bytes();
    match s {
        [_] => 1,
        // U+2500–U+259F in UTF-8: E2 94 80 to E2 96 9F.
        [0xE2, 0x94..=0x95, _] | [0xE2, 0x96, 0x80..=0x9F] => 1,
        _ => cell.cell_width(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use ratatui::layout::Rect;
    use ratatui::style::Style;

    #[test]
    fn box_drawing_and_blocks_are_one_column_as_ratatui_counts_them() {
        for c in ('\u{2500}'..='\u{259F}').chain(' '..='~') {
            let mut cell = Cell::default();
            cell.set_char(c);
            assert_eq!(cell_width(&cell), cell.cell_width(), "{c:?}");
        }
        // Just outside the range: left to ratatui.
        for c in [
            '\u{24FF}', '\u{25A0}', '\u{25FE}', '\u{2190}', '·', '−', 'コ',
        ] {
            let mut cell = Cell::default();
            cell.set_char(c);
            assert_eq!(cell_width(&cell), cell.cell_width(), "{c:?}");
        }
    }

    /// Symbols of every width and kind the rules treat apart.
    const SYMBOLS: &[&str] = &[
        " ",
        "a",
        "─",
        "▀",
        "·",
        "コ",
        "界",
        "❤\u{FE0F}",
        "👍",
        "e\u{301}",
        "ｶﾞ",
        "",
    ];

    fn cell_strategy() -> impl Strategy<Value = Cell> {
        (0..SYMBOLS.len(), 0u8..4, 0u8..4, 0u8..4, 0u8..7).prop_map(|(s, fg, bg, m, opt)| {
            let colour = |k: u8| match k {
                0 => Color::Reset,
                1 => Color::Red,
                2 => Color::Rgb(10, 20, 30),
                _ => Color::Indexed(200),
            };
            let mut cell = Cell::default();
            cell.set_symbol(SYMBOLS[s]);
            let modifier = [
                Modifier::empty(),
                Modifier::BOLD,
                Modifier::REVERSED,
                Modifier::UNDERLINED | Modifier::ITALIC,
            ][usize::from(m)];
            cell.set_style(
                Style::new()
                    .fg(colour(fg))
                    .bg(colour(bg))
                    .add_modifier(modifier),
            );
            #[allow(deprecated)]
            match opt {
                0 | 1 => {}
                2 => {
                    cell.set_diff_option(CellDiffOption::Skip);
                }
                3 => {
                    cell.set_diff_option(CellDiffOption::AlwaysUpdate);
                }
                4 => {
                    cell.set_diff_option(CellDiffOption::ForcedWidth(
                        std::num::NonZeroU16::new(2).unwrap(),
                    ));
                }
                5 => cell.skip = true,
                _ => {
                    cell.set_diff_option(CellDiffOption::ForcedWidth(
                        std::num::NonZeroU16::new(1).unwrap(),
                    ));
                }
            }
            cell
        })
    }

    /// A screen over `area`, each cell by `how` in turn: 0 or 1, `base`'s own (so many are
    /// equal to the other screen's); 2, the next of `cells`; 3 to 5, `base`'s with its skip flag,
    /// its diff option or its boldness changed.
    fn screen(area: Rect, cells: &[Cell], base: Option<&Buffer>, how: &[u8]) -> Buffer {
        let mut b = Buffer::empty(area);
        for (k, cell) in b.content.iter_mut().enumerate() {
            let how = how[k % how.len()];
            *cell = match base.and_then(|p| p.content.get(k)) {
                Some(c) if how != 2 => {
                    let mut c = c.clone();
                    #[allow(deprecated)]
                    match how {
                        3 => c.skip = !c.skip,
                        4 => {
                            c.set_diff_option(CellDiffOption::None);
                        }
                        5 => c.modifier.toggle(Modifier::BOLD),
                        _ => {}
                    }
                    c
                }
                _ => cells[k % cells.len()].clone(),
            };
        }
        // Well-formed, as ratatui's diff assumes (it indexes past the end otherwise): nothing
        // wide in the last cell.
        if let Some(last) = b.content.last_mut() {
            *last = Cell::default();
        }
        b
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        #[test]
        fn the_updates_are_ratatuis(
            x in 0u16..3,
            y in 0u16..3,
            w in 1u16..9,
            h in 1u16..5,
            taller in 0u16..2,
            first in prop::collection::vec(cell_strategy(), 1..40),
            second in prop::collection::vec(cell_strategy(), 1..40),
            how in prop::collection::vec(0u8..6, 1..40),
        ) {
            let prev = screen(Rect::new(x, y, w, h), &first, None, &[2]);
            // Heights may differ: both diffs stop at the shorter.
            let next = screen(Rect::new(x, y, w, h + taller), &second, Some(&prev), &how);
            let want: Vec<(u16, u16, &Cell)> = prev.diff(&next);
            let got = cell_diff(&prev, &next);
            prop_assert_eq!(got, want);
        }
    }

    #[test]
    fn equal_screens_send_nothing_and_a_changed_border_cell_is_sent() {
        let area = Rect::new(0, 0, 20, 4);
        let mut a = Buffer::empty(area);
        ratatui::widgets::Widget::render(
            ratatui::widgets::Block::bordered().title("ray"),
            area,
            &mut a,
        );
        assert!(cell_diff(&a, &a.clone()).is_empty());
        let mut b = a.clone();
        b[(5, 0)].set_char('═');
        let d = cell_diff(&a, &b);
        assert_eq!(d.len(), 1);
        assert_eq!((d[0].0, d[0].1, d[0].2.symbol()), (5, 0, "═"));
    }
}
