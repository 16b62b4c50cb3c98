//! Reading a ratatui `Buffer`'s `Debug` form back into cells: what
//! `insta::assert_debug_snapshot!(buffer)` pins, so such a snapshot compares with any other
//! frame and migrates to cells text.

use ratatui_core::style::{Color, Modifier};

use crate::cell::TermCell;
use crate::colour::named_colour;
use crate::error::Error;
use crate::frame::{mark_continuations, TermFrame};
use crate::glyph::glyph_row;
use crate::limits::MAX_FRAME;

/// How a ratatui buffer's `Debug` form starts.
pub(crate) const BUFFER_DEBUG_HEADER: &str = "Buffer {";

/// The value after `key: ` up to the next `, ` (or the end).
fn field<'a>(line: &'a str, key: &str) -> Option<&'a str> {
    let start = line.find(&format!("{key}: "))? + key.len() + 2;
    let rest = &line[start..];
    // A colour such as `Rgb(1, 2, 3)` holds commas of its own.
    let end = if rest.starts_with("Rgb(") {
        rest.find(')')? + 1
    } else {
        rest.find(',').unwrap_or(rest.len())
    };
    Some(rest[..end].trim())
}

/// A colour as ratatui's `Debug` writes it: `Reset`, `Green`, `Indexed(2)`, `Rgb(0, 205, 0)`.
fn debug_colour(s: &str) -> Option<Color> {
    if s == "Reset" {
        return Some(Color::Reset);
    }
    if let Some(i) = s.strip_prefix("Indexed(").and_then(|r| r.strip_suffix(')')) {
        return i.parse().ok().map(Color::Indexed);
    }
    if let Some(rgb) = s.strip_prefix("Rgb(").and_then(|r| r.strip_suffix(')')) {
        let v: Vec<u8> = rgb
            .split(',')
            .map(|n| n.trim().parse().ok())
            .collect::<Option<_>>()?;
        return match v[..] {
            [r, g, b] => Some(Color::Rgb(r, g, b)),
            _ => None,
        };
    }
    (0..16)
        .filter_map(named_colour)
        .find(|c| format!("{c:?}") == s)
}

/// Attributes as ratatui's `Debug` writes them: `NONE` or `BOLD | REVERSED`.
fn debug_modifiers(s: &str) -> Option<Modifier> {
    if s == "NONE" {
        return Some(Modifier::empty());
    }
    s.split('|')
        .map(|name| Modifier::from_name(name.trim()))
        .try_fold(Modifier::empty(), |all, m| Some(all | m?))
}

/// Reads a ratatui buffer's `Debug` form: the area's size, the content rows (glyphs), then the
/// style changes in row-major order, each holding until the next.
///
/// # Errors
/// A form that is not a buffer's `Debug`, naming what is wrong; a size over [`MAX_FRAME`].
pub fn from_buffer_debug(text: &str) -> Result<TermFrame, Error> {
    let bad = |what: &str| Error::new(format!("not a ratatui Buffer's Debug form: {what}"));
    let mut lines = text.lines().map(str::trim);
    if lines.next() != Some(BUFFER_DEBUG_HEADER) {
        return Err(bad("no 'Buffer {' line"));
    }
    let area = lines.next().unwrap_or_default();
    let size = |key| field(area, key).and_then(|v| v.trim_end_matches('}').trim().parse().ok());
    let (cols, rows): (usize, usize) = match (size("width"), size("height")) {
        (Some(c), Some(r)) => (c, r),
        _ => return Err(bad("no 'area: Rect { .. width: W, height: H }' line")),
    };
    if cols > MAX_FRAME.0 || rows > MAX_FRAME.1 {
        return Err(Error::new(format!(
            "ratatui Buffer is {cols}x{rows} cells; the limit is {}x{}",
            MAX_FRAME.0, MAX_FRAME.1
        )));
    }
    let mut cells = Vec::with_capacity(cols * rows);
    if rows > 0 && cols > 0 {
        if lines.next() != Some("content: [") {
            return Err(bad("no 'content: [' line"));
        }
        for y in 0..rows {
            let line = lines.next().unwrap_or_default();
            let row = line
                .strip_prefix('"')
                .and_then(|l| {
                    l.strip_suffix("\",").or_else(|| {
                        l.rfind("\", // hidden by multi-width symbols: ")
                            .map(|end| &l[..end])
                    })
                })
                .ok_or_else(|| bad(&format!("content row {y} is not a quoted string")))?;
            let glyphs = glyph_row(row);
            if glyphs.len() != cols {
                return Err(bad(&format!(
                    "content row {y} is {} cells, not {cols}",
                    glyphs.len()
                )));
            }
            cells.extend(glyphs.into_iter().map(|glyph| TermCell {
                glyph,
                ..TermCell::default()
            }));
        }
        if lines.next() != Some("],") || lines.next() != Some("styles: [") {
            return Err(bad("no 'styles: [' after the content"));
        }
        let mut changes = Vec::new();
        for line in lines.by_ref().take_while(|l| *l != "]") {
            let number = |key| field(line, key).and_then(|v| v.parse::<usize>().ok());
            let colour = |key| field(line, key).and_then(debug_colour);
            let change = (|| {
                let (x, y) = (number("x")?, number("y")?);
                let underline = match field(line, "underline") {
                    Some(u) => debug_colour(u)?,
                    None => Color::Reset,
                };
                let modifiers = debug_modifiers(field(line, "modifier")?)?;
                let at = (y < rows && x < cols).then_some(y * cols + x)?;
                Some((at, (colour("fg")?, colour("bg")?, underline, modifiers)))
            })()
            .ok_or_else(|| bad(&format!("style line '{line}'")))?;
            changes.push(change);
        }
        if !changes.windows(2).all(|w| w[0].0 < w[1].0) {
            return Err(bad("style changes out of order"));
        }
        for (k, &(at, (fg, bg, underline, modifiers))) in changes.iter().enumerate() {
            let end = changes.get(k + 1).map_or(cells.len(), |c| c.0);
            for c in &mut cells[at..end] {
                (c.fg, c.bg, c.underline, c.modifiers) = (fg, bg, underline, modifiers);
            }
        }
    }
    let mut frame = TermFrame { cols, rows, cells };
    mark_continuations(&mut frame.cells, cols);
    Ok(frame)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui_core::buffer::Buffer;
    use ratatui_core::layout::Rect;
    use ratatui_core::style::Style;

    #[test]
    fn a_buffers_debug_reads_back_as_the_buffer() {
        let mut buf = Buffer::empty(Rect::new(0, 0, 8, 2));
        buf.set_string(0, 0, "ok", Style::new().fg(Color::Green).bold());
        buf.set_string(3, 0, "界e\u{301}", Style::new().bg(Color::Rgb(0, 205, 0)));
        buf.set_string(
            1,
            1,
            "sel",
            Style::new()
                .add_modifier(Modifier::REVERSED | Modifier::ITALIC)
                .underline_color(Color::Indexed(9)),
        );
        let back = from_buffer_debug(&format!("{buf:?}")).unwrap();
        assert_eq!(back, TermFrame::from(&buf));
    }

    #[test]
    fn what_is_not_a_buffer_says_why() {
        assert_eq!(
            from_buffer_debug("Buffer {\n    area: Rect { x: 0, y: 0, width: 2, height: 1 },\n    content: [\n        \"abc\",\n").unwrap_err().to_string(),
            "not a ratatui Buffer's Debug form: content row 0 is 3 cells, not 2"
        );
        assert!(from_buffer_debug("Buffer {\n").is_err());
    }
}
