//! A ratatui app's own screen (no raycaster): a 40×14 dashboard with a list whose selection is
//! shown only by `Modifier::REVERSED`, styled spans, a bar chart and a gauge. Every change a
//! reviewer would care about must show in the cells text, in `termframe::diff` and in
//! `snapshot::assert_frames_eq`, and the cells text must be no longer than ratatui's own
//! `Debug` of the buffer (what `insta::assert_debug_snapshot!(buffer)` pins).

use halfcast::snapshot::{assert_frames_eq, cells_text};
use halfcast::termframe::{self, TermFrame};
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{
    Bar, BarChart, BarGroup, Block, Gauge, List, ListState, Paragraph, StatefulWidget, Widget,
};

/// What the dashboard shows; each test changes one thing.
#[derive(Clone)]
struct Dash {
    selected: usize,
    title: Style,
    ok: Color,
    city: &'static str,
    progress_underline: Color,
    thumbs: &'static str,
}

impl Default for Dash {
    fn default() -> Self {
        Self {
            selected: 1,
            title: Style::new().fg(Color::Yellow).add_modifier(Modifier::BOLD),
            ok: Color::Green,
            city: "Orle\u{301}ans",
            progress_underline: Color::Reset,
            thumbs: "👍🏽",
        }
    }
}

fn dashboard(d: &Dash) -> Buffer {
    let area = Rect::new(0, 0, 40, 14);
    let mut buf = Buffer::empty(area);
    let [top, mid, bottom] = Layout::vertical([
        Constraint::Length(3),
        Constraint::Min(5),
        Constraint::Length(3),
    ])
    .areas(area);
    let status = Line::from(vec![
        Span::styled("Build ", d.title),
        Span::styled("ok", Style::new().fg(d.ok)),
        Span::raw(" · "),
        Span::styled(d.city, Style::new().add_modifier(Modifier::ITALIC)),
        Span::raw(" "),
        Span::raw(d.thumbs),
    ]);
    Paragraph::new(status)
        .block(Block::bordered().title("Status"))
        .render(top, &mut buf);
    let [jobs, chart] =
        Layout::horizontal([Constraint::Length(18), Constraint::Min(10)]).areas(mid);
    let list = List::new(["compile", "test", "lint", "deploy"])
        .block(Block::bordered().title("Jobs"))
        .highlight_style(Style::new().add_modifier(Modifier::REVERSED));
    let mut state = ListState::default().with_selected(Some(d.selected));
    StatefulWidget::render(list, jobs, &mut buf, &mut state);
    let bars = [("mon", 3), ("tue", 5), ("wed", 2), ("thu", 7)]
        .map(|(label, v)| Bar::default().label(Line::from(label)).value(v));
    BarChart::default()
        .block(Block::bordered().title("Runs"))
        .bar_width(3)
        .bar_style(Style::new().fg(Color::Cyan))
        .data(BarGroup::default().bars(&bars))
        .render(chart, &mut buf);
    Gauge::default()
        .block(Block::bordered().title("Progress"))
        .gauge_style(
            Style::new()
                .fg(Color::Green)
                .bg(Color::Indexed(236))
                .underline_color(d.progress_underline),
        )
        .ratio(0.6)
        .render(bottom, &mut buf);
    buf
}

/// The changes the dashboard must catch: the four a reviewer names first, then ones nobody
/// sees on a dark terminal.
fn changes() -> Vec<(&'static str, Dash)> {
    let base = Dash::default();
    vec![
        (
            "selection moved (REVERSED only)",
            Dash {
                selected: 2,
                ..base.clone()
            },
        ),
        (
            "bold removed",
            Dash {
                title: Style::new().fg(Color::Yellow),
                ..base.clone()
            },
        ),
        (
            "Green -> Rgb(0,205,0)",
            Dash {
                ok: Color::Rgb(0, 205, 0),
                ..base.clone()
            },
        ),
        (
            "combining mark changed",
            Dash {
                city: "Orle\u{300}ans",
                ..base.clone()
            },
        ),
        (
            "Green -> Indexed(2)",
            Dash {
                ok: Color::Indexed(2),
                ..base.clone()
            },
        ),
        (
            "dim added",
            Dash {
                title: base.title.add_modifier(Modifier::DIM),
                ..base.clone()
            },
        ),
        (
            "crossed out added",
            Dash {
                title: base.title.add_modifier(Modifier::CROSSED_OUT),
                ..base.clone()
            },
        ),
        (
            "underline colour",
            Dash {
                progress_underline: Color::Red,
                ..base.clone()
            },
        ),
        (
            "skin tone changed",
            Dash {
                thumbs: "👍🏿",
                ..base.clone()
            },
        ),
    ]
}

#[test]
fn every_change_shows_in_the_cells_text_the_diff_and_the_assertion() {
    let before = dashboard(&Dash::default());
    let text = cells_text(&before);
    for (name, dash) in changes() {
        let after = dashboard(&dash);
        assert_ne!(before, after, "{name}: the change is in the buffer");
        assert_ne!(cells_text(&after), text, "{name}: cells text");
        let report = termframe::diff(&TermFrame::from(&before), &TermFrame::from(&after));
        assert!(!report.is_equal(), "{name}: diff");
        let first = &report.differing[0];
        let cell = format!("cell ({},{})", first.x, first.y);
        assert!(
            report.summary().contains(&cell),
            "{name}: {}",
            report.summary()
        );
        let failure = std::panic::catch_unwind(|| assert_frames_eq(&before, &after))
            .expect_err("assert_frames_eq fails");
        let msg = failure
            .downcast_ref::<String>()
            .cloned()
            .unwrap_or_default();
        assert!(
            msg.starts_with("frames differ") && msg.contains(&cell),
            "{name}: {msg}"
        );
    }
    assert_frames_eq(&before, dashboard(&Dash::default()));
}

#[test]
fn an_underline_colour_is_named_as_what_changed() {
    let before = dashboard(&Dash::default());
    let after = dashboard(&Dash {
        progress_underline: Color::Red,
        ..Dash::default()
    });
    let report = termframe::diff(&TermFrame::from(&before), &TermFrame::from(&after));
    assert!(report.summary().contains(
        "cell (1,12) underline colour: \"█\" fg=green bg=idx236 -> \"█\" fg=green bg=idx236 ul=red\n"
    ));
    assert_eq!(report.max_colour_delta, 0);
}

#[test]
fn a_moved_selection_is_a_short_diff_that_names_the_rows() {
    let before = dashboard(&Dash::default());
    let after = dashboard(&Dash {
        selected: 2,
        ..Dash::default()
    });
    let report = termframe::diff(&TermFrame::from(&before), &TermFrame::from(&after));
    // The reversed row moves from "test" (row 5) to "lint" (row 6): 16 cells each.
    assert_eq!(report.differing.len(), 32);
    assert!(report
        .summary()
        .contains("cell (1,5) attributes: \"t\" reversed -> \"t\"\n"));
    let (a, b) = (cells_text(&before), cells_text(&after));
    let removed: Vec<&str> = a.lines().filter(|l| !b.lines().any(|m| m == *l)).collect();
    let added: Vec<&str> = b.lines().filter(|l| !a.lines().any(|m| m == *l)).collect();
    assert_eq!(
        (removed, added),
        (vec!["y5 x1-16 reversed"], vec!["y6 x1-16 reversed"])
    );
}

#[test]
fn a_screenshot_shows_the_visible_changes_and_only_those() {
    use halfcast::output::screenshot::screenshot;
    let before = screenshot(&TermFrame::from(dashboard(&Dash::default())));
    for (name, dash) in changes() {
        let after = screenshot(&TermFrame::from(dashboard(&dash)));
        let changed = before
            .pixels()
            .iter()
            .zip(after.pixels())
            .filter(|(a, b)| a != b)
            .count();
        // Green is xterm's (0, 205, 0), the font draws `e` for any `e` + accent and a box for
        // any emoji, and the gauge is not underlined: those changes are for the text to catch.
        let seen = matches!(
            name,
            "selection moved (REVERSED only)" | "bold removed" | "dim added" | "crossed out added"
        );
        assert_eq!(changed > 0, seen, "{name}: {changed} pixels");
    }
}

#[test]
fn the_cells_text_is_no_longer_than_ratatuis_debug() {
    let buf = dashboard(&Dash::default());
    let (ours, debug) = (cells_text(&buf).len(), format!("{buf:?}").len());
    println!("40x14 dashboard: cells text {ours} bytes, ratatui Debug {debug} bytes");
    assert!(ours <= debug, "cells text {ours} > Debug {debug}");
    insta::assert_snapshot!(cells_text(&buf));
}
