//! The results screen shown when a level's exit is reached: time, points, treasures found, and
//! what the next key press does (the next map of a campaign, or the same level again). Its
//! words are plain ASCII, so it reads the same at every colour level.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Widget};

/// What follows the results.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Then {
    /// Enter plays the campaign's next map (its name).
    Level(String),
    /// Enter plays this level again.
    Again,
    /// A shared world starts the next round by itself, in `seconds`, on the map `map`.
    NewRound {
        /// Seconds until it starts.
        seconds: u64,
        /// The next round's map name.
        map: String,
    },
}

/// A lasting leaderboard shown under a shared world's results: the map's all-time best.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Board {
    /// Its heading ("All-time top 10").
    pub title: String,
    /// (rank and name, figure), best first; names already escaped for the terminal.
    pub rows: Vec<(String, String)>,
    /// The player's own best, if they have one.
    pub own: Option<String>,
}

/// One finished level's figures, and where the player goes from here.
#[derive(Debug, Clone, PartialEq)]
pub struct Results {
    /// The level's map name, as the title.
    pub level: String,
    /// Game seconds from the start to the exit.
    pub seconds: f64,
    /// Points at the exit.
    pub points: i64,
    /// Treasures found, of all the level has.
    pub treasures: (usize, usize),
    /// What comes after.
    pub then: Then,
    /// Who reached the exit, when that was someone else (a shared world).
    pub by: Option<String>,
    /// A shared world's scoreboard (name, figure), best first.
    pub board: Vec<(String, String)>,
    /// A server's lasting leaderboard for this map, when it keeps one.
    pub leaders: Option<Board>,
}

impl Results {
    /// The results of the level `level` as `state` finished it, going on to `next`.
    #[must_use]
    pub fn of(level: &str, state: &crate::game::GameState, then: Then) -> Self {
        Self {
            level: level.to_owned(),
            seconds: state.time,
            points: state.score.points,
            treasures: (state.score.found, state.level.treasures_total()),
            then,
            by: None,
            board: Vec::new(),
            leaders: None,
        }
    }
}

/// `m:ss` (or `h:mm:ss`), how long a level took.
#[must_use]
pub fn clock(seconds: f64) -> String {
    let s = if seconds.is_finite() {
        seconds.max(0.0) as u64
    } else {
        0
    };
    if s >= 3600 {
        format!("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
    } else {
        format!("{}:{:02}", s / 60, s % 60)
    }
}

const LABEL: Style = Style::new().fg(Color::Rgb(150, 154, 168));
const VALUE: Style = Style::new()
    .fg(Color::Rgb(255, 214, 110))
    .add_modifier(Modifier::BOLD);
const KEY: Style = Style::new()
    .fg(Color::Rgb(110, 200, 230))
    .add_modifier(Modifier::BOLD);

impl Results {
    /// The box's text rows.
    #[must_use]
    pub fn lines(&self) -> Vec<Line<'static>> {
        let row = |label: &str, value: String| {
            Line::from(vec![
                Span::styled(format!("{label:<10}"), LABEL),
                Span::styled(value, VALUE),
            ])
        };
        // A shared world's round can also end on its clock, with nobody at the exit.
        let timed_out = matches!(self.then, Then::NewRound { .. }) && self.by.is_none();
        let mut out = vec![Line::from(Span::styled(
            if timed_out {
                "Time is up!"
            } else {
                "Level complete!"
            },
            VALUE.fg(Color::Rgb(120, 255, 150)),
        ))];
        if let Some(who) = &self.by {
            out.push(Line::from(Span::styled(
                format!("{who} reached the exit"),
                LABEL,
            )));
        }
        out.push(Line::default());
        out.push(row("Time", clock(self.seconds)));
        out.push(row("Points", self.points.to_string()));
        out.push(row(
            "Treasures",
            format!("{} of {}", self.treasures.0, self.treasures.1),
        ));
        if !self.board.is_empty() {
            out.push(Line::default());
            for (name, figure) in &self.board {
                out.push(row(name, figure.clone()));
            }
        }
        out.push(Line::default());
        let then = match &self.then {
            Then::Level(name) => Some(format!(" next level: {name}")),
            Then::Again => Some(" play this level again".to_owned()),
            Then::NewRound { seconds, map } => {
                out.push(Line::from(vec![
                    Span::styled(format!("next round in {seconds} s on "), LABEL),
                    Span::styled(map.clone(), VALUE),
                ]));
                None
            }
        };
        if let Some(board) = &self.leaders {
            out.push(Line::default());
            out.extend(board.lines());
            out.push(Line::default());
        }
        if let Some(then) = then {
            out.push(Line::from(vec![
                Span::styled("Enter", KEY),
                Span::styled(then, LABEL),
            ]));
        }
        out.push(Line::from(vec![
            Span::styled("q", KEY),
            Span::styled(" quit", LABEL),
        ]));
        out
    }
}

impl Board {
    /// Its text rows: the heading, one row per entry (or "no rounds yet"), the own best.
    #[must_use]
    pub fn lines(&self) -> Vec<Line<'static>> {
        let mut out = vec![Line::from(Span::styled(self.title.clone(), LABEL))];
        if self.rows.is_empty() {
            out.push(Line::from(Span::styled("no rounds recorded yet", LABEL)));
        }
        for (name, figure) in &self.rows {
            out.push(Line::from(vec![
                Span::styled(format!("{name:<20}"), LABEL),
                Span::styled(figure.clone(), VALUE),
            ]));
        }
        if let Some(own) = &self.own {
            out.push(Line::from(vec![
                Span::styled(format!("{:<20}", "your best"), LABEL),
                Span::styled(own.clone(), VALUE),
            ]));
        }
        out
    }
}

impl Widget for &Board {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let border = Style::new().fg(Color::Rgb(110, 200, 230));
        draw_boxed(area, buf, self.lines(), " L: leaderboard ", border, 16);
    }
}

impl Widget for &Results {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let title = format!(" {} ", self.level);
        let border = Style::new().fg(Color::Rgb(120, 255, 150));
        draw_boxed(area, buf, self.lines(), &title, border, title.len());
    }
}

/// A centred, bordered box of `lines` (at least `min_width` wide), with a column of padding
/// inside the border so the figures line up on the left: the results and the leaderboard alike.
fn draw_boxed(
    area: Rect,
    buf: &mut Buffer,
    lines: Vec<Line<'static>>,
    title: &str,
    border: Style,
    min_width: usize,
) {
    let text_width = lines.iter().map(Line::width).max().unwrap_or(0);
    let block = Block::bordered()
        .border_set(ratatui::symbols::border::PLAIN)
        .border_style(border)
        .title(title.to_owned())
        .style(Style::new().bg(Color::Rgb(22, 24, 32)));
    let size = (text_width.max(min_width) as u16 + 4, lines.len() as u16 + 2);
    let Some(inner) = super::centred_box::draw(area, size, block, buf) else {
        return;
    };
    let inner = Rect::new(
        inner.x + 1,
        inner.y,
        inner.width.saturating_sub(1),
        inner.height,
    );
    Paragraph::new(lines).render(inner, buf);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(buf: &Buffer) -> String {
        let a = buf.area;
        (a.top()..a.bottom())
            .map(|y| {
                (a.left()..a.right())
                    .map(|x| buf[(x, y)].symbol().to_owned())
                    .collect::<String>()
            })
            .collect::<Vec<_>>()
            .join("\n")
    }

    #[test]
    fn clock_reads_minutes_and_seconds() {
        assert_eq!(clock(0.4), "0:00");
        assert_eq!(clock(83.9), "1:23");
        assert_eq!(clock(3723.0), "1:02:03");
        assert_eq!(clock(f64::NAN), "0:00");
    }

    #[test]
    fn the_box_shows_every_figure_and_the_next_step_in_plain_ascii_at_80x24() {
        let r = Results {
            level: "maps/level1.cub".into(),
            seconds: 83.2,
            points: 120,
            treasures: (8, 12),
            then: Then::Level("maps/level2.cub".into()),
            by: None,
            board: Vec::new(),
            leaders: None,
        };
        let mut buf = Buffer::empty(Rect::new(0, 0, 80, 24));
        (&r).render(buf.area, &mut buf);
        let t = text(&buf);
        for want in [
            "maps/level1.cub",
            "Level complete!",
            "1:23",
            "120",
            "8 of 12",
            "Enter next level: maps/level2.cub",
            "q quit",
        ] {
            assert!(t.contains(want), "{want} missing in\n{t}");
        }
        // The words are ASCII (the presenter turns the border into ASCII in mono).
        for line in r.lines() {
            assert!(line.to_string().is_ascii(), "{line}");
        }
        let again = Results {
            then: Then::Again,
            ..r
        };
        let mut buf = Buffer::empty(Rect::new(0, 0, 80, 24));
        (&again).render(buf.area, &mut buf);
        assert!(text(&buf).contains("Enter play this level again"));
    }
}
