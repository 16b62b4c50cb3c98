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

fn l(s: impl Into<std::borrow::Cow<'static, str>>) -> Span<'static> {
    Span::raw(s)
}

/// A piece of the status line; when the row is too narrow the lowest `keep` goes first.
struct Segment {
    keep: u8,
    spans: Vec<Span<'static>>,
}

fn seg(keep: u8, spans: Vec<Span<'static>>) -> Segment {
    Segment { keep, spans }
}

/// The status line for this frame, fitted to `width` columns by dropping the least useful parts.
#[must_use]
pub fn status_line(
    state: &GameState,
    stats: &FrameStats,
    mode: InputMode,
    steps: Option<usize>,
    width: u16,
) -> Line<'static> {
    let cam = &state.camera;
    let mut segs = if state.debugger.paused {
        paused_segments(state, steps)
    } else {
        running_segments(state, stats)
    };
    segs.push(seg(
        6,
        vec![l("pos "), v(format!("{:.2},{:.2}", cam.pos.x, cam.pos.y))],
    ));
    // Mono terminals get plain ASCII (the degree sign is not).
    let deg = if stats.level.map(|c| c.level) == Some(crate::encode::ColorLevel::Mono) {
        " deg"
    } else {
        "°"
    };
    segs.push(seg(
        5,
        vec![l("angle "), v(format!("{:.1}{deg}", cam.heading_deg()))],
    ));
    segs.push(seg(
        0,
        vec![l("FOV "), v(format!("{:.0}{deg}", cam.fov_deg()))],
    ));
    // The map's name goes before the input mode (which says whether taps are exact).
    segs.push(seg(1, vec![v(state.world.map.name.clone())]));
    segs.push(seg(3, vec![l(mode.label())]));
    segs.push(seg(
        10,
        vec![
            Span::styled("?", HINT_KEY),
            l(" help  "),
            Span::styled("q", HINT_KEY),
            l(" quit"),
        ],
    ));
    fit(&mut segs, usize::from(width));
    let mut spans = Vec::new();
    for (i, s) in segs.into_iter().enumerate() {
        if i > 0 {
            spans.push(sep());
        }
        spans.extend(s.spans);
    }
    Line::from(spans).style(BAR)
}

/// While paused: the debugged column and step, the debugger's keys and the pane's scroll keys.
fn paused_segments(state: &GameState, steps: Option<usize>) -> Vec<Segment> {
    let mut segs = Vec::new();
    let shown = match (state.debugger.cursor, steps) {
        (Cursor::Steps(n), Some(all)) if n < all => format!("{n}/{all}"),
        (_, Some(all)) => format!("{all}/{all} hit"),
        (_, None) => "-".to_owned(),
    };
    segs.push(seg(
        9,
        vec![
            Span::styled(" PAUSED ", PAUSED),
            l(" col "),
            v(state.debug_column().to_string()),
            l("  step "),
            v(shown),
        ],
    ));
    let mut hints = Vec::new();
    for (k, what) in [
        ("←→[]", " column  "),
        ("n", " step  "),
        ("⏎", " hit  "),
        ("space", " resume"),
    ] {
        hints.push(Span::styled(k, HINT_KEY));
        hints.push(l(what));
    }
    segs.push(seg(7, hints));
    segs.push(seg(
        4,
        vec![Span::styled("↑↓", HINT_KEY), l(" scroll the ray pane")],
    ));
    segs
}

/// While running: the game's figures, then the speed figures, the colour level and the blocks.
fn running_segments(state: &GameState, stats: &FrameStats) -> Vec<Segment> {
    let mut segs = hud(state);
    segs.push(seg(8, vec![v(format!(" {:>3.0}", stats.fps)), l(" fps")]));
    segs.push(seg(
        3,
        vec![
            l("render "),
            v(format!("{:.1}", stats.render_ms)),
            l(" ms  draw "),
            v(format!("{:.1}", stats.draw_ms)),
            l(" ms"),
        ],
    ));
    if stats.bytes_per_frame > 0.0 {
        let out = vec![
            v(format!("{:.1}", stats.bytes_per_frame / 1000.0)),
            l(" kB/f "),
            v(format!("{:.0}", stats.kbit_s)),
            l(" kbit/s"),
        ];
        segs.push(seg(4, out));
    }
    // The colour level and how it was decided (`256 (TERM)`; O cycles it): kept at 80
    // columns, since a player who sees grey should learn why at a glance.
    if let Some(choice) = stats.level {
        segs.push(seg(
            7,
            vec![
                v(choice.level.name().to_owned()),
                l(format!(" ({})", choice.reason.label())),
            ],
        ));
    }
    // The block characters when not the default half-blocks (U cycles them), so a player
    // who switched knows which: kept at 80 columns, before the position.
    if stats.glyphs != crate::render::glyphs::Glyphs::Half {
        segs.push(seg(
            7,
            vec![v(stats.glyphs.name().to_owned()), l(" blocks")],
        ));
    }
    segs
}

/// The game's figures (on maps with something to find), as one segment kept before the speed
/// figures: points, keys held (each in its colour) and treasures left; then the time, which yields
/// to the position on a short row.
fn hud(state: &GameState) -> Vec<Segment> {
    let level = &state.level;
    if !state.world.map.has_game() {
        return Vec::new();
    }
    let score = &state.score;
    let mut spans = vec![v(format!(" {}", score.points)), l(" pts")];
    if !score.keys.is_empty() {
        spans.push(l("  keys"));
        for k in &score.keys {
            let c = crate::texture::key_tint::key_colour(k);
            spans.push(l(" "));
            spans.push(Span::styled(
                k.clone(),
                Style::new()
                    .fg(Color::Rgb(c.r, c.g, c.b))
                    .add_modifier(Modifier::BOLD),
            ));
        }
    }
    if level.treasures_total() > 0 {
        spans.push(l("  "));
        spans.push(v(level.treasures_left(&state.world.map).to_string()));
        spans.push(l(" left"));
    }
    // The time goes before the position when the row is short (the results show it too).
    vec![
        seg(9, spans),
        seg(2, vec![v(super::results::clock(state.time))]),
    ]
}

/// Drops the least useful segments until the line (with separators) fits.
fn fit(segs: &mut Vec<Segment>, width: usize) {
    let len = |segs: &[Segment]| {
        let text: usize = segs
            .iter()
            .flat_map(|s| &s.spans)
            .map(|s| s.content.chars().count())
            .sum();
        text + 3 * segs.len().saturating_sub(1)
    };
    while segs.len() > 1 && len(segs) > width {
        let lowest = segs
            .iter()
            .enumerate()
            .min_by_key(|(_, s)| s.keep)
            .map(|(i, _)| i)
            .expect("not empty");
        segs.remove(lowest);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::world::World;
    use std::sync::Arc;

    /// The default map's game at its start, facing east.
    fn at_start() -> GameState {
        let world = Arc::new(World::default_world());
        let cam = Camera::from_angle(world.map.start.pos(), 90.0, 66.0);
        GameState::new(world, cam, 80)
    }

    /// [`at_start`], with the figures a game at 256 colours (from `TERM`) shows after a frame.
    fn at_start_with_256_colours() -> (GameState, FrameStats) {
        let mut stats = FrameStats::default();
        stats.record_bytes(1000);
        stats.level = Some(crate::encode::ColourChoice::from_env(
            None,
            Some("xterm-256color"),
            None,
        ));
        (at_start(), stats)
    }

    fn text(width: u16, paused: bool) -> String {
        let mut state = at_start();
        if paused {
            state.debugger.toggle_pause();
        }
        status_line(
            &state,
            &FrameStats::default(),
            InputMode::Kitty,
            Some(5),
            width,
        )
        .to_string()
    }

    #[test]
    fn wide_rows_show_everything() {
        let t = text(200, false);
        for part in [
            "fps",
            "render",
            "pos 15.50,5.50",
            "angle 90.0°",
            "FOV 66°",
            "default.cub",
            "kitty keys",
            "q quit",
        ] {
            assert!(t.contains(part), "{part}: {t}");
        }
    }

    #[test]
    fn the_colour_level_shows_with_its_reason() {
        let (state, stats) = at_start_with_256_colours();
        // Also at 80 columns, the size most people play at (the pane beside the view takes
        // none of the status row), with the game's figures.
        for width in [200, 100, 80] {
            let t = status_line(&state, &stats, InputMode::Emulated, None, width).to_string();
            assert!(t.contains("256 (TERM)"), "{width}: {t}");
            assert!(
                t.contains(" 0 pts  12 left │ ")
                    && t.contains("pos 15.50,5.50")
                    && t.contains("q quit"),
                "{width}: {t}"
            );
        }
    }

    #[test]
    fn a_finer_glyph_setting_shows_at_80_columns_beside_the_colour_level() {
        let (state, mut stats) = at_start_with_256_colours();
        stats.glyphs = crate::render::glyphs::Glyphs::Quadrant;
        // A player who just pressed U at the size most people play at sees what it chose.
        let t = status_line(&state, &stats, InputMode::Emulated, None, 80).to_string();
        assert!(t.chars().count() <= 80, "{t}");
        for part in ["256 (TERM)", "quadrant blocks", "q quit"] {
            assert!(t.contains(part), "{part}: {t}");
        }
    }

    #[test]
    fn narrow_rows_keep_the_game_fps_and_the_quit_hint() {
        let t = text(60, false);
        assert!(t.chars().count() <= 60, "{t}");
        for part in [" 0 pts", "12 left", "fps", "q quit"] {
            assert!(t.contains(part), "{part}: {t}");
        }
        assert!(!t.contains("kitty"));
        let t = text(70, true);
        assert!(t.contains("PAUSED") && t.contains("q quit"), "{t}");
    }

    #[test]
    fn the_game_hud_shows_points_keys_treasures_left_and_time_only_on_maps_with_a_game() {
        let mut state = at_start();
        state.score.points = 120;
        state.score.keys.insert("gold".into());
        state.time = 83.4;
        let line = status_line(
            &state,
            &FrameStats::default(),
            InputMode::Emulated,
            None,
            200,
        );
        let t = line.to_string();
        assert!(t.contains(" 120 pts  keys gold  12 left │ 1:23"), "{t}");
        // The key is written in its own colour.
        let gold = crate::texture::key_tint::key_colour("gold");
        let span = line
            .spans
            .iter()
            .find(|s| s.content == "gold")
            .expect("key span");
        assert_eq!(span.style.fg, Some(Color::Rgb(gold.r, gold.g, gold.b)));
        // A map without game lines keeps the old status line (position at 60 columns).
        let (plain, _) = World::load(
            crate::map::grid_map("111\n1N1\n111\n"),
            &crate::world::TextureSource::Embedded,
            false,
        )
        .expect("plain world");
        let cam = Camera::from_angle(plain.map.start.pos(), 90.0, 66.0);
        let state = GameState::new(Arc::new(plain), cam, 80);
        let t = status_line(
            &state,
            &FrameStats::default(),
            InputMode::Emulated,
            None,
            60,
        )
        .to_string();
        assert!(t.contains("pos 1.50,1.50") && !t.contains("pts"), "{t}");
    }
}
