//! The pane's rows: one logical line of the derivation in chunks it may wrap between, its
//! styles and number formats, and wrapping to the pane's width.

use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};

use crate::render::cast::Side;
use crate::render::derivation::num;

pub(super) const LABEL: Style = Style::new().fg(Color::Rgb(128, 132, 146));
pub(super) const VALUE: Style = Style::new().fg(Color::Rgb(226, 226, 232));
pub(super) const NAME: Style = Style::new().fg(Color::Rgb(110, 200, 230));
pub(super) const SIDE_X: Color = Color::Rgb(255, 176, 96);
pub(super) const SIDE_Y: Color = Color::Rgb(126, 192, 255);
pub(super) const CURRENT_BG: Color = Color::Rgb(64, 60, 22);
pub(super) const HIT: Style = Style::new()
    .fg(Color::Rgb(255, 96, 96))
    .add_modifier(Modifier::BOLD);

pub(super) fn side_style(side: Side) -> Style {
    Style::new().fg(match side {
        Side::X => SIDE_X,
        Side::Y => SIDE_Y,
    })
}

pub(super) fn axis(side: Side) -> &'static str {
    match side {
        Side::X => "X",
        Side::Y => "Y",
    }
}

pub(super) fn cell_text(c: (i64, i64)) -> String {
    format!("({},{})", c.0, c.1)
}

pub(super) fn pair(v: crate::vec2::Vec2) -> String {
    format!("({},{})", num(v.x), num(v.y))
}

pub(super) fn signed(s: i64) -> &'static str {
    if s < 0 {
        "−1"
    } else {
        "+1"
    }
}

/// A height in wall units, short: `1`, `0.25`, `-0.5` (at most 2 decimals).
pub(super) fn fmt_height(z: f64) -> String {
    let s = format!("{z:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

/// Panes at least this wide get the roomier forms (`step y` in folded steps).
pub(super) const WIDE: usize = 40;

/// One logical line of the derivation: chunks it may wrap between (a chunk never splits).
#[derive(Debug, Clone, Default)]
pub(super) struct Row {
    pub(super) chunks: Vec<Vec<Span<'static>>>,
    /// Drawn on the highlight background (the current step).
    pub(super) current: bool,
}

impl Row {
    pub(super) fn new() -> Self {
        Self::default()
    }

    /// Starts a new chunk (a place the line may wrap) with one span.
    pub(super) fn chunk(mut self, text: impl Into<String>, style: Style) -> Self {
        self.chunks.push(vec![Span::styled(text.into(), style)]);
        self
    }

    /// Adds a span to the current chunk.
    pub(super) fn and(mut self, text: impl Into<String>, style: Style) -> Self {
        let span = Span::styled(text.into(), style);
        match self.chunks.last_mut() {
            Some(c) => c.push(span),
            None => self.chunks.push(vec![span]),
        }
        self
    }
}

/// One row wrapped to `width`: chunks fill a line, the rest continue indented by two; plain
/// ASCII when `ascii`.
pub(super) fn wrap(row: Row, width: usize, ascii: bool) -> Vec<Line<'static>> {
    let current = row.current;
    let fix = |s: Span<'static>| -> Span<'static> {
        if ascii {
            Span::styled(to_ascii(&s.content), s.style)
        } else {
            s
        }
    };
    let bg = |s: Span<'static>| {
        if current {
            let st = s.style.bg(CURRENT_BG).add_modifier(Modifier::BOLD);
            s.style(st)
        } else {
            s
        }
    };
    let mut out: Vec<Vec<Span<'static>>> = vec![Vec::new()];
    let mut used = 0;
    for chunk in row.chunks {
        let spans: Vec<Span<'static>> = chunk.into_iter().map(fix).collect();
        let w: usize = spans.iter().map(|s| s.content.chars().count()).sum();
        if used > 0 && used + w > width {
            // Continue on a new line, indented, without the chunk's leading spaces.
            let mut first = true;
            let mut line = vec![Span::styled("  ", VALUE)];
            used = 2;
            for s in spans {
                let s = if first {
                    first = false;
                    let t = s.content.trim_start().to_owned();
                    Span::styled(t, s.style)
                } else {
                    s
                };
                used += s.content.chars().count();
                line.push(s);
            }
            out.push(line);
        } else {
            used += w;
            out.last_mut().expect("one line at least").extend(spans);
        }
    }
    out.into_iter()
        .map(|spans| Line::from(spans.into_iter().map(bg).collect::<Vec<_>>()))
        .collect()
}

/// Mono terminals get plain ASCII.
pub(super) fn to_ascii(s: &str) -> String {
    s.replace('−', "-")
        .replace('·', "*")
        .replace('→', "->")
        .replace('≥', ">=")
        .replace('Δ', "d")
        .replace('↑', "^")
        .replace('↓', "v")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heights_are_printed_short() {
        assert_eq!(fmt_height(0.25), "0.25");
        assert_eq!(fmt_height(1.0), "1");
        assert_eq!(fmt_height(-0.5), "-0.5");
        assert_eq!(fmt_height(-0.0001), "0");
    }
}
