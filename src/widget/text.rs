//! Text into a buffer exactly as ratatui's `Buffer::set_stringn` and `set_line` write it, with
//! characters known to take one cell each written a cell at a time instead of through grapheme
//! segmentation and width tables: the panes' text (the ray pane, the status line, the header,
//! name tags) is redrawn every frame of every SSH session, and is nearly all ASCII.

use ratatui::buffer::Buffer;
use ratatui::style::Style;
use ratatui::text::Line;

/// Whether `c` is always a grapheme of its own one cell wide: printable ASCII and Latin-1, the
/// arrows, the box drawing lines and a few signs the panes use (`−`, `…`, `⏎`). None of them joins
/// its neighbours into a grapheme (each breaks as "any other" character) or is wide, so a cell
/// each is exactly how ratatui lays them out (the test below checks every one).
fn one_cell(c: char) -> bool {
    matches!(c,
        ' '..='~'
        | '\u{a1}'..='\u{ac}'
        | '\u{ae}'..='\u{ff}'
        | '\u{2013}' | '\u{2014}' | '\u{2026}' | '\u{2212}' | '\u{23ce}'
        | '\u{2190}'..='\u{21ff}'
        | '\u{2500}'..='\u{257f}')
}

/// Whether every character of `text` is [`one_cell`].
fn plain(text: &str) -> bool {
    text.chars().all(one_cell)
}

/// `buf.set_stringn(x, y, text, max_width, style)`: the same cells, the same returned position.
pub fn put_str(
    buf: &mut Buffer,
    x: u16,
    y: u16,
    text: &str,
    max_width: usize,
    style: Style,
) -> (u16, u16) {
    if !plain(text) {
        return buf.set_stringn(x, y, text, max_width, style);
    }
    let max_width = u16::try_from(max_width).unwrap_or(u16::MAX);
    let room = buf.area.right().saturating_sub(x).min(max_width);
    let n = text.chars().count().min(usize::from(room));
    if n == 0 {
        return (x, y);
    }
    // Panics where `set_stringn` would (its first cell outside the buffer).
    let at = buf.index_of(x, y);
    for (cell, c) in buf.content[at..at + n].iter_mut().zip(text.chars()) {
        cell.set_char(c).set_style(style);
    }
    (x + n as u16, y)
}

/// `buf.set_line(x, y, line, max_width)`: the same cells, the same returned position.
pub fn put_line(buf: &mut Buffer, x: u16, y: u16, line: &Line<'_>, max_width: u16) -> (u16, u16) {
    let mut remaining = max_width;
    let mut x = x;
    for span in line {
        if remaining == 0 {
            break;
        }
        let end = put_str(
            buf,
            x,
            y,
            span.content.as_ref(),
            usize::from(remaining),
            line.style.patch(span.style),
        );
        remaining = remaining.saturating_sub(end.0.saturating_sub(x));
        x = end.0;
    }
    (x, y)
}

/// `Paragraph::new(line).render(row, buf)` for a one-row `row`: a left-aligned line of
/// [`one_cell`] characters is written straight to its cells (a paragraph lays it out and truncates it to the
/// same cells); anything else goes through the paragraph.
#[cfg(any(feature = "ui", test))]
pub fn line_row(line: Line<'_>, row: ratatui::layout::Rect, buf: &mut Buffer) {
    use ratatui::layout::Alignment;
    use ratatui::widgets::{Paragraph, Widget};
    let row = row.intersection(buf.area);
    let plain = matches!(line.alignment, None | Some(Alignment::Left))
        && line.iter().all(|s| plain(&s.content));
    if !plain || row.height != 1 {
        Paragraph::new(line).render(row, buf);
        return;
    }
    put_line(buf, row.x, row.y, &line, row.width);
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::layout::Rect;
    use ratatui::style::{Color, Modifier};
    use ratatui::text::Span;
    use ratatui::widgets::{Paragraph, Widget};

    fn lines() -> Vec<Line<'static>> {
        let a = Style::new().fg(Color::Rgb(200, 100, 50));
        let b = Style::new()
            .bg(Color::Rgb(1, 2, 3))
            .add_modifier(Modifier::BOLD);
        vec![
            Line::from("plain ascii that runs off the edge of the row"),
            Line::from(vec![Span::styled("two ", a), Span::styled("spans", b)]).style(b),
            Line::from(vec![Span::styled("x → y", a), Span::raw(" │ ok")]),
            Line::from("wide 日本語 and ゙ marks"),
            Line::from("tab\there, line\nbreak"),
            Line::from(""),
            Line::from("centred").centered(),
            Line::from("right").right_aligned(),
        ]
    }

    #[test]
    fn every_one_cell_character_lands_where_ratatui_puts_it() {
        let all: String = (0..=0x2600u32)
            .filter_map(char::from_u32)
            .filter(|&c| one_cell(c))
            .collect();
        assert!(all.chars().count() > 400);
        // Alone, and each after every kind of neighbour (a grapheme would join them).
        let mut texts: Vec<String> = all.chars().map(String::from).collect();
        texts.push(all.clone());
        texts.push(all.chars().rev().collect());
        let style = Style::new().fg(Color::Rgb(1, 2, 3));
        for text in &texts {
            let n = text.chars().count() as u16;
            let area = Rect::new(0, 0, n + 2, 1);
            let (mut ours, mut theirs) = (Buffer::empty(area), Buffer::empty(area));
            assert_eq!(
                put_str(&mut ours, 1, 0, text, usize::MAX, style),
                theirs.set_stringn(1, 0, text, usize::MAX, style)
            );
            assert_eq!(ours, theirs, "{text:?}");
            let (mut ours, mut theirs) = (Buffer::empty(area), Buffer::empty(area));
            line_row(Line::raw(text.as_str()), area, &mut ours);
            Paragraph::new(text.as_str()).render(area, &mut theirs);
            assert_eq!(ours, theirs, "{text:?} as a paragraph");
        }
    }

    #[test]
    fn lines_land_in_the_same_cells_as_ratatuis() {
        for width in [0, 1, 5, 12, 30, 60] {
            for (k, line) in lines().into_iter().enumerate() {
                for max in [0, 3, 8, u16::MAX] {
                    let area = Rect::new(2, 1, width, 3);
                    let (mut ours, mut theirs) = (Buffer::empty(area), Buffer::empty(area));
                    for b in [&mut ours, &mut theirs] {
                        b.set_style(area, Style::new().bg(Color::Rgb(9, 9, 9)));
                    }
                    if width > 0 {
                        let x = area.x + width.min(2) - 1;
                        let end = put_line(&mut ours, x, 2, &line, max);
                        assert_eq!(end, theirs.set_line(x, 2, &line, max), "line {k}");
                    }
                    assert_eq!(ours, theirs, "line {k}, width {width}, max {max}");
                }
                let area = Rect::new(0, 0, width, 2);
                let (mut ours, mut theirs) = (Buffer::empty(area), Buffer::empty(area));
                let row = Rect::new(0, 1, width, 1);
                line_row(line.clone(), row, &mut ours);
                Paragraph::new(line).render(row, &mut theirs);
                assert_eq!(ours, theirs, "row, line {k}, width {width}");
            }
        }
    }
}
