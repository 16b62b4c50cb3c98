//! The status line: speed figures, pose, map, input mode and key hints (or debugger state).

use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};

use super::keys::InputMode;
use super::stats::FrameStats;
use crate::game::{Cursor, GameState};

/// Background of the whole status row.
pub const BAR: Style = Style::new()
    .bg(Color::Rgb(28, 30, 38))
    .fg(Color::Rgb(150, 154, 168));
const VALUE: Style = Style::new().fg(Color::Rgb(232, 232, 240));
const SEP: Style = Style::new().fg(Color::Rgb(72, 76, 92));
const PAUSED: Style = Style::new()
    .bg(Color::Rgb(255, 214, 64))
    .fg(Color::Rgb(20, 20, 20))
    .add_modifier(Modifier::BOLD);
const HINT_KEY: Style = Style::new()
    .fg(Color::Rgb(255, 214, 110))
    .add_modifier(Modifier::BOLD);

fn sep() -> Span<'static> {
    Span::styled(" │ ", SEP)
}

fn v(s: String) -> Span<'static> {
    Span::styled(s, VALUE)
}

fn l(s: &'static str) -> Span<'static> {
    Span::raw(s)
}

/// The status line for this frame.
#[must_use]
pub fn status_line(
    state: &GameState,
    stats: &FrameStats,
    mode: InputMode,
    steps: Option<usize>,
) -> Line<'static> {
    let cam = &state.camera;
    let mut spans = Vec::new();
    if state.debugger.paused {
        spans.push(Span::styled(" PAUSED ", PAUSED));
        spans.push(l(" col "));
        spans.push(v(state.debug_column().to_string()));
        let shown = match (state.debugger.cursor, steps) {
            (Cursor::Steps(n), Some(all)) if n < all => format!("{n}/{all}"),
            (_, Some(all)) => format!("{all}/{all} hit"),
            (_, None) => "-".to_owned(),
        };
        spans.push(l("  step "));
        spans.push(v(shown));
        spans.push(sep());
        for (k, what) in [
            ("←→[]", " column  "),
            ("n", " step  "),
            ("⏎", " hit  "),
            ("space", " resume"),
        ] {
            spans.push(Span::styled(k, HINT_KEY));
            spans.push(l(what));
        }
        spans.push(sep());
    } else {
        spans.push(v(format!(" {:>3.0}", stats.fps)));
        spans.push(l(" fps  render "));
        spans.push(v(format!("{:.1}", stats.render_ms)));
        spans.push(l(" ms  draw "));
        spans.push(v(format!("{:.1}", stats.draw_ms)));
        spans.push(l(" ms"));
        spans.push(sep());
    }
    spans.push(l("pos "));
    spans.push(v(format!("{:.2},{:.2}", cam.pos.x, cam.pos.y)));
    spans.push(l("  angle "));
    spans.push(v(format!("{:.1}°", cam.angle_deg().rem_euclid(360.0))));
    spans.push(l("  FOV "));
    spans.push(v(format!("{:.0}°", cam.fov_deg())));
    spans.push(sep());
    spans.push(v(state.world.map.name.clone()));
    spans.push(sep());
    spans.push(l(mode.label()));
    spans.push(sep());
    spans.push(Span::styled("?", HINT_KEY));
    spans.push(l(" help  "));
    spans.push(Span::styled("q", HINT_KEY));
    spans.push(l(" quit"));
    Line::from(spans).style(BAR)
}
