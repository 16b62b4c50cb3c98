//! The game a shared world plays: one [`Level`] for everybody (first to walk over an item gets
//! it; doors, creatures and shots are shared), the mode's rules, the scoreboard, and the pause
//! on the results before the next round starts by itself.
//!
//! - **coop**: one team score (points, keys and treasures pooled); the round ends when anyone
//!   reaches the exit.
//! - **tag**: one player is "it"; touching another passes it on (not straight back: the new
//!   "it" cannot pass it for a moment); seconds spent as "it" are the score (fewer is better).
//!   The round ends at the exit or after [`TAG_ROUND_SECONDS`].
//!
//! Pure (no clock, no channels): [`super::players::Players`] drives it once per tick.

use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

use crate::color::Rgb;
use crate::game::{Level, Score};
use crate::map::Map;
use crate::vec2::Vec2;

use super::PlayerId;

/// How long the results stay up before the next round, in seconds.
pub const RESULTS_SECONDS: f64 = 8.0;

/// Length of a round of tag, in seconds.
pub const TAG_ROUND_SECONDS: f64 = 180.0;

/// Centres this close (two bodies touching, and a little) pass "it" on, in cells.
pub const TAG_REACH: f64 = 0.6;

/// Seconds after a pass before "it" can be passed again (no instant tag-backs).
pub const TAG_GRACE: f64 = 2.0;

/// The rules a server plays by (`halfcast serve --mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Mode {
    /// Everyone on one team: shared points, the level ends when anyone reaches the exit.
    #[default]
    Coop,
    /// One player is "it"; touching passes it on; time as "it" is the score.
    Tag,
}

impl Mode {
    /// The word `--mode` takes and the header shows.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Mode::Coop => "coop",
            Mode::Tag => "tag",
        }
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Mode {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "coop" => Ok(Mode::Coop),
            "tag" => Ok(Mode::Tag),
            _ => Err(format!("unknown mode '{s}' (coop or tag)")),
        }
    }
}

/// One row of the scoreboard.
#[derive(Debug, Clone, PartialEq)]
pub struct BoardRow {
    /// The player's name.
    pub name: String,
    /// Their minimap colour.
    pub colour: Rgb,
    /// Their figure as shown ("120 pts", "12s it").
    pub figure: String,
    /// The same for the header, where the mode already says what it counts ("120", "12s").
    pub short: String,
    /// Whether they are "it" now (tag).
    pub it: bool,
}

/// One player's figures in a finished round, as the leaderboard records them.
#[derive(Debug, Clone, PartialEq)]
pub struct PlayerResult {
    /// The name they played under (unique among those connected).
    pub name: String,
    /// Their own points (coop pools them for the team; this is their part).
    pub points: i64,
    /// Treasures they picked up.
    pub items: usize,
    /// Seconds they were "it" (tag; 0 in coop).
    pub it_seconds: f64,
    /// Whether they were the one who reached the exit.
    pub reached_exit: bool,
}

/// A finished round, shown until the next starts.
#[derive(Debug, Clone, PartialEq)]
pub struct RoundEnd {
    /// Seconds until the next round.
    pub left: f64,
    /// Who reached the exit (none when a tag round ran out of time).
    pub by: Option<String>,
    /// How long the round lasted, in seconds.
    pub seconds: f64,
    /// The pooled score (coop) or the winner's (tag) at the end.
    pub points: i64,
    /// Treasures found of the level's total.
    pub treasures: (usize, usize),
    /// The final scoreboard, best first.
    pub board: Vec<BoardRow>,
    /// Everyone's figures, for the leaderboard.
    pub players: Vec<PlayerResult>,
    /// Which of the served maps this round played (filled in by `Players`).
    pub map: usize,
    /// The name of the map the next round plays (filled in by `Players`).
    pub next_map: String,
    /// Whether the round ended at the exit with every treasure found (a full clear).
    pub cleared: bool,
}

/// Who is here, as the round needs them: id, name, colour, where they stand.
#[derive(Debug, Clone, Copy)]
pub struct Here<'a> {
    /// Their id.
    pub id: PlayerId,
    /// Their (unique) name.
    pub name: &'a str,
    /// Their colour.
    pub colour: Rgb,
    /// Their centre.
    pub pos: Vec2,
    /// Their own score (tag mode keeps scores apart).
    pub score: &'a Score,
}

/// The shared game of one server.
#[derive(Debug, Clone)]
pub struct Round {
    /// The rules.
    pub mode: Mode,
    /// The level everybody plays this round.
    pub level: Level,
    /// Counts rounds from 1 (the level's seed is the server's plus this).
    pub number: u64,
    /// Seconds played this round.
    pub elapsed: f64,
    /// The team's pooled score (coop).
    pub team: Score,
    /// Who is "it" (tag).
    pub it: Option<PlayerId>,
    /// Seconds each player has been "it" this round (tag).
    pub it_seconds: BTreeMap<PlayerId, f64>,
    /// The results, once the round is over.
    pub ended: Option<RoundEnd>,
    /// Seconds a round lasts at most (`--round-minutes`); tag's default is
    /// [`TAG_ROUND_SECONDS`], coop's is none (it ends at the exit).
    pub limit: Option<f64>,
    /// How long the results show before the next round, in seconds.
    pub results_seconds: f64,
    grace: f64,
    seed: u64,
}

impl Round {
    /// Round 1 of `map` under `mode`; creatures seeded from `seed`.
    #[must_use]
    pub fn new(map: &Map, mode: Mode, seed: u64) -> Self {
        Self {
            mode,
            level: Level::new(map, seed.wrapping_add(1)),
            number: 1,
            elapsed: 0.0,
            team: Score::default(),
            it: None,
            it_seconds: BTreeMap::new(),
            ended: None,
            limit: None,
            results_seconds: RESULTS_SECONDS,
            grace: 0.0,
            seed,
        }
    }

    /// The next round on the same map: a fresh level, scores and "it" cleared.
    pub fn next(&mut self, map: &Map) {
        self.number += 1;
        self.level = Level::new(map, self.seed.wrapping_add(self.number));
        self.elapsed = 0.0;
        self.team = Score::default();
        self.it = None;
        self.it_seconds.clear();
        self.ended = None;
        self.grace = 0.0;
    }

    /// While the results show: counts down; true when the next round is due.
    pub fn wait(&mut self, dt: f64) -> bool {
        match &mut self.ended {
            Some(end) => {
                end.left -= dt;
                end.left <= 0.0
            }
            None => false,
        }
    }

    /// Tag's rules for one tick (after everyone moved): "it" goes to the first player here if
    /// nobody is, passes on to the nearest player it touches, and its holder's clock runs.
    /// Returns the name of a new "it", for the message line.
    pub fn tag_tick(&mut self, here: &[Here], dt: f64) -> Option<String> {
        if self.mode != Mode::Tag || here.is_empty() {
            return None;
        }
        self.grace = (self.grace - dt).max(0.0);
        let holder = self.it.and_then(|id| here.iter().find(|h| h.id == id));
        let Some(holder) = holder else {
            // Nobody is "it" (the round began, or "it" left): the first here is.
            self.it = Some(here[0].id);
            self.grace = TAG_GRACE;
            return Some(here[0].name.to_owned());
        };
        *self.it_seconds.entry(holder.id).or_insert(0.0) += dt;
        if self.grace > 0.0 {
            return None;
        }
        let touched = here
            .iter()
            .filter(|h| h.id != holder.id)
            .map(|h| (h, (h.pos - holder.pos).length()))
            .filter(|(_, d)| *d <= TAG_REACH)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(h, _)| *h)?;
        self.it = Some(touched.id);
        self.grace = TAG_GRACE;
        Some(touched.name.to_owned())
    }

    /// The round's length limit in seconds, if it has one.
    #[must_use]
    pub fn time_limit(&self) -> Option<f64> {
        match self.mode {
            Mode::Coop => self.limit,
            Mode::Tag => Some(self.limit.unwrap_or(TAG_ROUND_SECONDS)),
        }
    }

    /// Whether this tick ends the round: someone reached the exit, or the time ran out.
    #[must_use]
    pub fn is_over(&self) -> bool {
        self.level.finished().is_some() || self.time_limit().is_some_and(|t| self.elapsed >= t)
    }

    /// Ends the round: the results for everyone `here`, `by` the player who reached the exit.
    pub fn end(&mut self, here: &[Here], by: Option<&str>) {
        let board = self.board(here);
        let (points, found) = match self.mode {
            Mode::Coop => (self.team.points, self.team.found),
            Mode::Tag => (
                here.iter().map(|h| h.score.points).max().unwrap_or(0),
                here.iter().map(|h| h.score.found).sum(),
            ),
        };
        let players = here
            .iter()
            .map(|h| PlayerResult {
                name: h.name.to_owned(),
                points: h.score.points,
                items: h.score.found,
                it_seconds: self.it_seconds.get(&h.id).copied().unwrap_or(0.0),
                reached_exit: by == Some(h.name),
            })
            .collect();
        let total = self.level.treasures_total();
        self.ended = Some(RoundEnd {
            left: self.results_seconds,
            by: by.map(str::to_owned),
            seconds: self.elapsed,
            points,
            treasures: (found, total),
            board,
            players,
            map: 0,
            next_map: String::new(),
            cleared: by.is_some() && found >= total,
        });
    }

    /// The scoreboard now, best first: points (coop: each player's finds, the team's total in
    /// the header) or seconds as "it" (tag, fewest first).
    #[must_use]
    pub fn board(&self, here: &[Here]) -> Vec<BoardRow> {
        let mut rows: Vec<(f64, BoardRow)> = here
            .iter()
            .map(|h| match self.mode {
                Mode::Coop => (
                    -(h.score.points as f64),
                    BoardRow {
                        name: h.name.to_owned(),
                        colour: h.colour,
                        figure: format!("{} pts", h.score.points),
                        short: h.score.points.to_string(),
                        it: false,
                    },
                ),
                Mode::Tag => {
                    let s = self.it_seconds.get(&h.id).copied().unwrap_or(0.0);
                    (
                        s,
                        BoardRow {
                            name: h.name.to_owned(),
                            colour: h.colour,
                            figure: format!("{s:.0}s it"),
                            short: format!("{s:.0}s"),
                            it: self.it == Some(h.id),
                        },
                    )
                }
            })
            .collect();
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        rows.into_iter().map(|(_, r)| r).collect()
    }

    /// The header's game part: the mode, the team's score or who is "it", and the board.
    #[must_use]
    pub fn header(&self, here: &[Here]) -> Scoreboard {
        let rows = self
            .board(here)
            .into_iter()
            .map(|r| {
                let star = if r.it { "*" } else { "" };
                format!("{star}{} {}", r.name, r.short)
            })
            .collect();
        let left = self.level.items_left();
        let summary = match self.mode {
            Mode::Coop => {
                let mut s = format!(
                    "coop: team {} pts, {left} {} left",
                    self.team.points,
                    if left == 1 { "item" } else { "items" },
                );
                if let Some(limit) = self.limit {
                    let clock = (limit - self.elapsed).max(0.0) as u64;
                    s.push_str(&format!(", {}:{:02} to go", clock / 60, clock % 60));
                }
                s
            }
            Mode::Tag => {
                let it = self
                    .it
                    .and_then(|id| here.iter().find(|h| h.id == id))
                    .map_or("nobody", |h| h.name);
                let limit = self.time_limit().unwrap_or(TAG_ROUND_SECONDS);
                let clock = (limit - self.elapsed).max(0.0);
                format!(
                    "tag: it is {it}, {}:{:02} left",
                    clock as u64 / 60,
                    clock as u64 % 60,
                )
            }
        };
        Scoreboard { summary, rows }
    }
}

/// The header's game part in two pieces, so a narrow header can shorten the board's rows
/// (", +N more") instead of cutting the line.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scoreboard {
    /// The mode and the team's points or who is "it" and the time left.
    pub summary: String,
    /// One "name figure" per player ("ann 120", "*bob 12s"), best first ("*" marks who is "it").
    pub rows: Vec<String>,
}

impl Scoreboard {
    /// Whether there is no game to show (a map without one).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.summary.is_empty()
    }
}

impl std::fmt::Display for Scoreboard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} | {}", self.summary, self.rows.join(", "))
    }
}

/// Coop's pooling: what each player gained this tick (points, treasures, keys) added to the
/// team, given each player's score before (`was`, the team's copy) and after the tick.
pub fn pool(team: &mut Score, was: &Score, now: &[Score]) {
    for s in now {
        team.points += s.points - was.points;
        team.found += s.found.saturating_sub(was.found);
        team.keys.extend(s.keys.iter().cloned());
    }
    team.points = team.points.max(0);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::World;

    fn map() -> Map {
        World::default_world().map
    }

    fn here<'a>(id: PlayerId, name: &'a str, pos: (f64, f64), score: &'a Score) -> Here<'a> {
        Here {
            id,
            name,
            colour: Rgb::new(255, 0, 0),
            pos: Vec2::new(pos.0, pos.1),
            score,
        }
    }

    #[test]
    fn modes_parse_and_name_themselves() {
        assert_eq!("coop".parse::<Mode>(), Ok(Mode::Coop));
        assert_eq!("tag".parse::<Mode>(), Ok(Mode::Tag));
        assert_eq!(
            "race".parse::<Mode>(),
            Err("unknown mode 'race' (coop or tag)".to_owned())
        );
        assert_eq!(Mode::Tag.to_string(), "tag");
    }

    #[test]
    fn it_goes_to_the_first_player_then_passes_on_touch_but_not_straight_back() {
        let mut r = Round::new(&map(), Mode::Tag, 7);
        let s = Score::default();
        let far = [
            here(1, "ann", (2.5, 2.5), &s),
            here(2, "bob", (6.5, 2.5), &s),
        ];
        assert_eq!(r.tag_tick(&far, 0.1).as_deref(), Some("ann"));
        assert_eq!(r.it, Some(1));
        // Within the grace nothing passes, even touching.
        let near = [
            here(1, "ann", (2.5, 2.5), &s),
            here(2, "bob", (2.9, 2.5), &s),
        ];
        assert_eq!(r.tag_tick(&near, 0.5), None);
        for _ in 0..40 {
            r.tag_tick(&far, 0.1);
        }
        assert_eq!(r.it, Some(1));
        assert_eq!(r.tag_tick(&near, 0.1).as_deref(), Some("bob"));
        assert_eq!(r.it, Some(2));
        // bob cannot hand it straight back.
        assert_eq!(r.tag_tick(&near, 0.1), None);
        assert_eq!(r.it, Some(2));
        let ann = r.it_seconds[&1];
        assert!((ann - 4.6).abs() < 1e-9, "{ann}");
        let board = r.board(&near);
        assert_eq!(board[0].name, "bob", "fewest seconds as it first");
        assert!(board[0].it && !board[1].it);
        // The round's clock is Players::tick's (tag_tick leaves it alone): 4.6 s played.
        r.elapsed = 4.6;
        let header = r.header(&near).to_string();
        assert!(
            header.starts_with("tag: it is bob, 2:55 left | *bob 0s, ann 5s"),
            "{header}"
        );
    }

    #[test]
    fn a_tag_round_ends_on_time_and_the_next_starts_after_the_results() {
        let m = map();
        let mut r = Round::new(&m, Mode::Tag, 1);
        assert!(!r.is_over());
        r.elapsed = TAG_ROUND_SECONDS;
        assert!(r.is_over());
        let s = Score::default();
        r.end(&[here(1, "ann", (2.5, 2.5), &s)], None);
        assert!(!r.wait(RESULTS_SECONDS - 0.5));
        assert!(r.wait(0.6));
        r.next(&m);
        assert_eq!((r.number, r.elapsed, r.it), (2, 0.0, None));
        assert!(r.ended.is_none());
    }

    #[test]
    fn a_limited_coop_round_ends_on_time_and_its_results_show_as_long_as_asked() {
        let m = map();
        let mut r = Round::new(&m, Mode::Coop, 1);
        r.elapsed = 10_000.0;
        assert!(!r.is_over(), "coop has no clock by default");
        r.limit = Some(60.0);
        r.results_seconds = 1.5;
        r.elapsed = 45.0;
        let s = Score::default();
        let ann = [here(1, "ann", (2.5, 2.5), &s)];
        assert!(r.header(&ann).summary.ends_with(", 0:15 to go"));
        assert!(!r.is_over());
        r.elapsed = 60.0;
        assert!(r.is_over());
        r.end(&ann, None);
        let end = r.ended.as_ref().expect("ended");
        assert_eq!(end.left, 1.5);
        assert!(!end.cleared);
        assert_eq!(end.players[0].name, "ann");
        assert!(!end.players[0].reached_exit);
        assert!(r.wait(1.6));
    }

    #[test]
    fn coop_pools_points_treasures_and_keys() {
        let mut team = Score::default();
        let was = team.clone();
        let mut a = was.clone();
        a.points += 10;
        a.found += 1;
        let mut b = was.clone();
        b.keys.insert("red".into());
        pool(&mut team, &was, &[a, b]);
        assert_eq!((team.points, team.found), (10, 1));
        assert!(team.has_key("red"));
    }
}
