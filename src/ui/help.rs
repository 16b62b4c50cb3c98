//! The `?` overlay: every key (as bound now, from the config file or the defaults), and how
//! keys are being read. Plain ASCII, so it reads the same at every colour level.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Widget};

use super::keymap::KeyMap;
use super::keys::InputMode;

/// The help's rows: a section title (no actions), or actions sharing one row (`a / b`) and
/// what they do. Every action of [`super::keymap::ACTIONS`] appears once.
pub const ROWS: &[(&[&str], &str)] = &[
    (&[], "Move"),
    (&["forward", "back"], "walk forward / back"),
    (
        &["turn_left", "turn_right"],
        "turn (paused: move the debugged column)",
    ),
    (&["strafe_left", "strafe_right"], "strafe left / right"),
    (&["look_up", "look_down"], "look up / down"),
    (&["centre_pitch"], "look straight ahead again"),
    (&["jump", "crouch"], "jump / crouch (hold)"),
    (&["use_door", "tag"], "open / close a door / throw a tag"),
    (&["night"], "night mode on / off"),
    (&[], "Ray debugger"),
    (&["pause"], "pause / resume the world"),
    (
        &["column_left", "column_right"],
        "debugged column left / right",
    ),
    (&["column_left_10", "column_right_10"], "... by 10 columns"),
    (&["step_dda"], "single-step the DDA (pauses)"),
    (
        &["run_to_hit", "save_figure"],
        "run the DDA to its hit / write its figure",
    ),
    (&[], "Screen"),
    (
        &["minimap", "ray_pane"],
        "show / hide the minimap / the ray pane",
    ),
    (
        &["colours", "glyphs"],
        "next colour level / next block characters",
    ),
    (&["help"], "this help"),
    (&["quit"], "quit (esc closes this help; ctrl+c quits)"),
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
pub struct HelpOverlay<'a> {
    pub mode: InputMode,
    pub keys: &'a KeyMap,
}

impl HelpOverlay<'_> {
    /// The text rows: (keys, what) with an empty `keys` for a section title, then the note on
    /// how keys are read.
    #[must_use]
    pub fn rows(&self) -> Vec<(String, String)> {
        let names: Vec<(&str, Vec<String>)> = self.keys.entries().map(|(n, _, k)| (n, k)).collect();
        let keys_of = |action: &str| {
            names
                .iter()
                .find(|(n, _)| *n == action)
                .map(|(_, k)| k.join(" "))
                .unwrap_or_default()
        };
        let mut out = Vec::new();
        for (actions, what) in ROWS {
            let keys: Vec<String> = actions.iter().map(|a| keys_of(a)).collect();
            out.push((keys.join(" / "), (*what).to_string()));
        }
        let how = match self.mode {
            InputMode::Kitty => "keys: kitty protocol (exact press / release)",
            InputMode::Emulated => "keys: a tap is one short step; hold to keep moving",
            InputMode::Released => "keys: browser (exact press / release)",
        };
        out.push((String::new(), String::new()));
        out.push((String::new(), how.to_string()));
        out
    }

    fn lines(&self, key_width: usize) -> Vec<Line<'static>> {
        self.rows()
            .into_iter()
            .map(|(keys, what)| {
                if keys.is_empty() {
                    let style = if what.starts_with("keys:") {
                        DIM
                    } else {
                        SECTION
                    };
                    Line::styled(what, style)
                } else {
                    Line::from(vec![
                        Span::styled(format!(" {keys:<key_width$} "), KEY),
                        Span::styled(what, TEXT),
                    ])
                }
            })
            .collect()
    }
}

impl Widget for HelpOverlay<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let area = area.intersection(buf.area);
        let rows = self.rows();
        let key_width = rows.iter().map(|(k, _)| k.len()).max().unwrap_or(0);
        let text_width = rows
            .iter()
            .map(|(k, w)| {
                if k.is_empty() {
                    w.len()
                } else {
                    key_width + 2 + w.len()
                }
            })
            .max()
            .unwrap_or(0);
        let lines = self.lines(key_width);
        let block = Block::bordered()
            .border_set(ratatui::symbols::border::PLAIN)
            .border_style(Style::new().fg(Color::Rgb(110, 200, 230)))
            .title(" halfcast keys ")
            .title_bottom(Line::from(" ? or esc closes ").right_aligned())
            .style(Style::new().bg(Color::Rgb(22, 24, 32)));
        let size = (text_width as u16 + 2, lines.len() as u16 + 2);
        let Some(inner) = super::centred_box::draw(area, size, block, buf) else {
            return;
        };
        Paragraph::new(lines).render(inner, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ui::keymap::ACTIONS;

    #[test]
    fn every_action_is_listed_once_and_fits_80x24() {
        let listed: Vec<&str> = ROWS.iter().flat_map(|(a, _)| a.iter().copied()).collect();
        let mut all: Vec<&str> = ACTIONS.iter().map(|a| a.0).collect();
        let mut sorted = listed.clone();
        sorted.sort_unstable();
        all.sort_unstable();
        assert_eq!(sorted, all);
        let keys = KeyMap::default();
        let help = HelpOverlay {
            mode: InputMode::Emulated,
            keys: &keys,
        };
        let rows = help.rows();
        assert!(rows.len() + 2 <= 24, "{} rows", rows.len());
        let key_width = rows.iter().map(|(k, _)| k.len()).max().unwrap();
        for (k, w) in &rows {
            assert!(k.is_ascii() && w.is_ascii(), "{k} {w}");
            let width = if k.is_empty() {
                w.len()
            } else {
                key_width + 2 + w.len()
            };
            assert!(width + 2 <= 80, "{k} {w}");
        }
        assert!(rows.contains(&("w up / s down".into(), "walk forward / back".into())));
    }
}
