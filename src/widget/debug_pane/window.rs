//! Cutting the pane's lines to its rows around the focus, with notes of what is above and below.

use ratatui::text::Line;

use super::row::LABEL;

/// The `rows` lines ending at `focus_end` (or later, if they fit): the first says how many are
/// above when some are cut, the last how many below.
pub(super) fn window(
    lines: Vec<Line<'static>>,
    starts: &[bool],
    pinned: &[Line<'static>],
    rows: usize,
    focus_end: usize,
    ascii: bool,
) -> Vec<Line<'static>> {
    let total = lines.len();
    if total <= rows || rows == 0 {
        return lines.into_iter().take(rows).collect();
    }
    let end = focus_end.max(rows).min(total);
    let mut start = end - rows;
    let (up, down, keys) = if ascii {
        ("^", "v", "w/s")
    } else {
        ("↑", "↓", "↑↓")
    };
    let keep = rows > pinned.len() + 4;
    if start > 0 {
        // The note (and the ray, when there is room) take the first rows; what follows starts
        // at the start of a line of the derivation, not half-way through one.
        start += 1 + if keep { pinned.len() } else { 0 };
        while start < end && !starts[start] {
            start += 1;
        }
    }
    let mut out: Vec<Line<'static>> = Vec::new();
    if start > 0 {
        out.push(Line::styled(
            format!("{up} {start} more above ({keys} scroll)"),
            LABEL,
        ));
        if keep {
            out.extend(pinned.iter().cloned());
        }
    }
    out.extend(lines.into_iter().take(end).skip(start));
    if end < total && rows > 1 {
        let last = out.len() - 1;
        out[last] = Line::styled(format!("{down} {} more below", total - end + 1), LABEL);
    }
    out
}
