//! The `?` overlay: every key, and how keys are being read.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Clear, Paragraph, Widget};

use super::keys::InputMode;

/// The key table: (keys, what they do); an empty key starts a section.
pub const KEYS: &[(&str, &str)] = &[
    ("", "Move"),
    ("W S  ↑ ↓", "walk forward / back"),
    ("A D  ← →", "turn left / right"),
    ("Z X  , .", "strafe left / right"),
    ("mouse drag", "turn"),
    ("", "Ray debugger"),
    ("space  P", "pause / resume the world"),
    ("← →  [ ]", "move the debugged column (paused)"),
    ("shift+← →  { }", "… by 10 columns"),
    ("N", "single-step the DDA (pauses)"),
    ("enter  G", "run to the hit"),
    ("", "Screen"),
    ("M", "show / hide the minimap"),
    ("I", "show / hide the ray (DDA) pane"),
    ("O", "colours: truecolor → 256 → 16 → mono"),
    ("?  H  F1", "this help"),
    ("Q  esc  ctrl+C", "quit"),
];

const KEY: Style = Style::new()
    .fg(Color::Rgb(255, 214, 110))
    .add_modifier(Modifier::BOLD);
const TEXT: Style = Style::new().fg(Color::Rgb(220, 220, 228));
const SECTION: Style = Style::new()
    .fg(Color::Rgb(110, 200, 230))
    .add_modifier(Modifier::BOLD);
const DIM: Style = Style::new().fg(Color::Rgb(128, 132, 146));

/// A centred help box over whatever is drawn below it.
#[derive(Debug, Clone, Copy)]
pub struct HelpOverlay {
    pub mode: InputMode,
}

impl HelpOverlay {
    fn lines(self) -> Vec<Line<'static>> {
        let mut out = Vec::new();
        for &(keys, what) in KEYS {
            match (keys, what) {
                ("", section) => {
                    if !out.is_empty() {
                        out.push(Line::default());
                    }
                    out.push(Line::styled(section, SECTION));
                }
                (k, w) => out.push(Line::from(vec![
                    Span::styled(format!("  {k:<16}"), KEY),
                    Span::styled(w, TEXT),
                ])),
            }
        }
        out.push(Line::default());
        let how = match self.mode {
            InputMode::Kitty => "keys: kitty protocol (press/release)",
            InputMode::Emulated => "keys: held while auto-repeat continues",
        };
        out.push(Line::styled(how, DIM));
        out
    }
}

impl Widget for HelpOverlay {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let area = area.intersection(buf.area);
        let lines = self.lines();
        let w = 56.min(area.width);
        let h = (lines.len() as u16 + 2).min(area.height);
        if w < 4 || h < 3 {
            return;
        }
        let r = Rect::new(
            area.x + (area.width - w) / 2,
            area.y + (area.height - h) / 2,
            w,
            h,
        );
        Clear.render(r, buf);
        let block = Block::bordered()
            .border_type(BorderType::Rounded)
            .border_style(Style::new().fg(Color::Rgb(110, 200, 230)))
            .title(" halfcast · keys ")
            .title_bottom(Line::from(" ? or esc to close ").right_aligned())
            .style(Style::new().bg(Color::Rgb(22, 24, 32)));
        let inner = block.inner(r);
        block.render(r, buf);
        Paragraph::new(lines).render(inner, buf);
    }
}
