//! halfcast's game lines: what a level is made of beyond its walls.
//!
//! ```text
//! ITEM x,y texture [points=N] [key=NAME] [scale=S]
//! DOORLOCK x,y NAME
//! EXIT x,y
//! CREATURE x,y texture [speed=S] [behaviour=wander|patrol|chase] [scale=S] [frames=N]
//! ```
//!
//! Positions of items and creatures are map points (sub-cell); `DOORLOCK` names a door's grid
//! cell (whole numbers) and `EXIT` the cell holding the point (`3,4` and `3.5,4.5` both mean
//! cell (3, 4)). What needs the grid (floors under things, doors under locks, a key for every
//! lock) is checked once the grid is read, by [`GameLines::check`].

use std::collections::BTreeMap;

use super::words::words;
use super::{Cell, MapErrorKind, TextureRef};
use crate::vec2::Vec2;

/// Most `ITEM` lines a map may have (each is tested against every player every tick).
pub const MAX_ITEMS: usize = 1024;

/// Most `CREATURE` lines a map may have (each moves, looks and may path-find every tick).
pub const MAX_CREATURES: usize = 256;

/// Fastest a creature may walk, in cells per second (faster would outrun its collision steps).
pub const MAX_CREATURE_SPEED: f64 = 10.0;

/// Points a treasure gives when its line says nothing.
pub const DEFAULT_TREASURE_POINTS: i64 = 10;

/// Most points one item may give.
pub const MAX_ITEM_POINTS: i64 = 1_000_000;

/// A creature's walking speed when its line says nothing, in cells per second.
pub const DEFAULT_CREATURE_SPEED: f64 = 1.5;

/// A pickup: a treasure (points) or a key, drawn as a small sprite until someone takes it.
#[derive(Debug, Clone, PartialEq)]
pub struct ItemDef {
    /// Centre on the map plane, in cells.
    pub pos: Vec2,
    /// Its sprite (a path, or an embedded sprite's stem).
    pub texture: TextureRef,
    /// Points it gives (10 for a treasure, 0 for a key, unless `points=` says otherwise).
    pub points: i64,
    /// `key=NAME`: taking it gives this key.
    pub key: Option<String>,
    /// Width and height of its sprite in cells.
    pub scale: f64,
    /// Where the line was written (1-based line, column).
    pub at: (usize, usize),
}

impl ItemDef {
    /// Whether it counts as a treasure (an item that is not a key).
    #[must_use]
    pub fn is_treasure(&self) -> bool {
        self.key.is_none()
    }
}

/// A door that opens only for a player holding a key.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DoorLock {
    /// The door's grid cell.
    pub cell: (i64, i64),
    /// The key's name (as in `ITEM … key=NAME`).
    pub key: String,
    /// Where the line was written.
    pub at: (usize, usize),
}

/// A cell whose entering ends the level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExitDef {
    /// The exit's grid cell.
    pub cell: (i64, i64),
    /// Where the line was written.
    pub at: (usize, usize),
}

/// How a creature picks its way when it sees nobody.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Behaviour {
    /// Random turns at cell centres.
    #[default]
    Wander,
    /// Back and forth along the longer open line through its start.
    Patrol,
    /// Always heads for the nearest player it sees (and searches where it saw one last).
    Chase,
}

impl Behaviour {
    /// The word a map line uses.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Behaviour::Wander => "wander",
            Behaviour::Patrol => "patrol",
            Behaviour::Chase => "chase",
        }
    }
}

/// A moving creature as the map places it.
#[derive(Debug, Clone, PartialEq)]
pub struct CreatureDef {
    /// Where it starts, in cells.
    pub pos: Vec2,
    /// Its 8-view sprite sheet (views left to right, walking frames top to bottom).
    pub texture: TextureRef,
    /// Walking speed in cells per second.
    pub speed: f64,
    /// What it does when it sees nobody.
    pub behaviour: Behaviour,
    /// Width and height of its sprite in cells.
    pub scale: f64,
    /// Walking frames in its sheet (top to bottom).
    pub frames: u16,
    /// Where the line was written.
    pub at: (usize, usize),
}

/// Which game line a header word starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum GameLine {
    Item,
    DoorLock,
    Exit,
    Creature,
}

impl GameLine {
    /// The line's identifier, if `word` is one.
    pub(super) fn classify(word: &str) -> Option<Self> {
        Some(match word {
            "ITEM" => GameLine::Item,
            "DOORLOCK" => GameLine::DoorLock,
            "EXIT" => GameLine::Exit,
            "CREATURE" => GameLine::Creature,
            _ => return None,
        })
    }

    fn id(self) -> &'static str {
        match self {
            GameLine::Item => "ITEM",
            GameLine::DoorLock => "DOORLOCK",
            GameLine::Exit => "EXIT",
            GameLine::Creature => "CREATURE",
        }
    }

    fn usage(self) -> &'static str {
        match self {
            GameLine::Item => "ITEM x,y texture [points=N] [key=NAME] [scale=S]",
            GameLine::DoorLock => "DOORLOCK x,y NAME",
            GameLine::Exit => "EXIT x,y",
            GameLine::Creature => {
                "CREATURE x,y texture [speed=S] [behaviour=wander|patrol|chase] [scale=S] [frames=N]"
            }
        }
    }
}

/// An error at a 1-based (line, column).
type LineError = ((usize, usize), MapErrorKind);

/// Every game line of a header, in file order.
#[derive(Debug, Clone, Default)]
pub(super) struct GameLines {
    pub(super) items: Vec<ItemDef>,
    pub(super) locks: Vec<DoorLock>,
    pub(super) exits: Vec<ExitDef>,
    pub(super) creatures: Vec<CreatureDef>,
}

/// Whether `name` may name a key: letters, digits, `-` and `_` (it is shown in messages).
fn valid_key_name(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= 32
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
}

/// One game line being read: its kind and where it is, to word its errors.
struct LineAt {
    kind: GameLine,
    line: usize,
    word_col: usize,
}

impl LineAt {
    /// The line's `BadValue` error at `col`.
    fn bad(&self, col: usize, why: String) -> LineError {
        let id = self.kind.id().to_owned();
        ((self.line, col), MapErrorKind::BadValue { id, why })
    }

    /// The error that shows how the line is written.
    fn usage(&self) -> LineError {
        self.bad(self.word_col, format!("write '{}'", self.kind.usage()))
    }

    /// `s` as a finite number, or the error naming `what` at `col`.
    fn number(&self, what: &str, s: &str, col: usize) -> Result<f64, LineError> {
        s.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| self.bad(col, format!("{what} needs a number, got '{s}'")))
    }

    /// `v` as a number above 0 and at most `max` (`unit` follows the limit in the error).
    fn above_zero(
        &self,
        what: &str,
        v: &str,
        col: usize,
        max: f64,
        unit: &str,
    ) -> Result<f64, LineError> {
        let s = self.number(what, v, col)?;
        if s > 0.0 && s <= max {
            Ok(s)
        } else {
            let why = format!("{what} must be above 0 and at most {max}{unit}, got '{v}'");
            Err(self.bad(col, why))
        }
    }
}

/// The `key=value` options of an `ITEM` or `CREATURE` line, each kind reading only its own
/// (`scale` is both's), with the defaults for what the line leaves out.
struct ThingOptions {
    is_item: bool,
    points: Option<i64>,
    key: Option<String>,
    speed: f64,
    behaviour: Behaviour,
    scale: f64,
    frames: u16,
}

impl ThingOptions {
    fn new(is_item: bool) -> Self {
        Self {
            is_item,
            points: None,
            key: None,
            speed: DEFAULT_CREATURE_SPEED,
            behaviour: Behaviour::default(),
            scale: if is_item { 0.5 } else { 0.7 },
            frames: 4,
        }
    }

    /// Reads the option `word` at `col`, refusing one the line's kind has not.
    fn read(&mut self, at: &LineAt, word: &str, col: usize) -> Result<(), LineError> {
        let unknown = || at.bad(col, format!("unknown option '{word}'"));
        let Some((k, v)) = word.split_once('=') else {
            return Err(unknown());
        };
        match (k, self.is_item) {
            ("points", true) => {
                let n = v
                    .parse::<i64>()
                    .ok()
                    .filter(|n| (0..=MAX_ITEM_POINTS).contains(n));
                let why = format!("points must be a whole number 0-{MAX_ITEM_POINTS}, got '{v}'");
                self.points = Some(n.ok_or_else(|| at.bad(col, why))?);
            }
            ("key", true) => {
                if !valid_key_name(v) {
                    return Err(at.bad(col, key_name_rule(v)));
                }
                self.key = Some(v.to_owned());
            }
            ("scale", _) => self.scale = at.above_zero("scale", v, col, 4.0, "")?,
            ("speed", false) => {
                let unit = " (cells per second)";
                self.speed = at.above_zero("speed", v, col, MAX_CREATURE_SPEED, unit)?;
            }
            ("behaviour" | "behavior", false) => {
                self.behaviour = match v {
                    "wander" => Behaviour::Wander,
                    "patrol" => Behaviour::Patrol,
                    "chase" => Behaviour::Chase,
                    _ => {
                        let why = format!("behaviour must be wander, patrol or chase, got '{v}'");
                        return Err(at.bad(col, why));
                    }
                };
            }
            ("frames", false) => {
                self.frames = v.parse::<u16>().ok().filter(|&n| n >= 1).ok_or_else(|| {
                    at.bad(
                        col,
                        format!("frames must be a whole number 1-65535, got '{v}'"),
                    )
                })?;
            }
            _ => return Err(unknown()),
        }
        Ok(())
    }
}

impl GameLines {
    /// Reads one game line; errors point at the word that broke the rule.
    pub(super) fn line(
        &mut self,
        kind: GameLine,
        rest: &str,
        line: usize,
        word_col: usize,
        rest_col: usize,
    ) -> Result<(), LineError> {
        let at = LineAt {
            kind,
            line,
            word_col,
        };
        let words = words(rest, rest_col);
        let Some((pos_word, pos_col)) = words.first() else {
            return Err(at.usage());
        };
        let (xs, ys) = pos_word
            .split_once(',')
            .ok_or_else(|| at.bad(*pos_col, format!("position must be x,y, got '{pos_word}'")))?;
        let pos = Vec2::new(at.number("x", xs, *pos_col)?, at.number("y", ys, *pos_col)?);
        let place = (line, word_col);
        match kind {
            GameLine::Exit => {
                if words.len() != 1 {
                    return Err(at.usage());
                }
                let cell = (pos.x.floor() as i64, pos.y.floor() as i64);
                self.exits.push(ExitDef { cell, at: place });
                Ok(())
            }
            GameLine::DoorLock => self.lock(&at, pos, &words),
            GameLine::Item | GameLine::Creature => self.thing(&at, pos, &words),
        }
    }

    /// A `DOORLOCK` line at `pos`: a whole cell, a key name, one lock per door.
    fn lock(&mut self, at: &LineAt, pos: Vec2, words: &[(String, usize)]) -> Result<(), LineError> {
        let [(pos_word, pos_col), (name, name_col)] = words else {
            return Err(at.usage());
        };
        if pos.x.fract() != 0.0 || pos.y.fract() != 0.0 {
            return Err(at.bad(
                *pos_col,
                format!("the door's cell must be whole numbers x,y, got '{pos_word}'"),
            ));
        }
        if !valid_key_name(name) {
            return Err(at.bad(*name_col, key_name_rule(name)));
        }
        let place = (at.line, at.word_col);
        let cell = (pos.x as i64, pos.y as i64);
        if let Some(first) = self.locks.iter().find(|l| l.cell == cell) {
            return Err((
                place,
                MapErrorKind::LockedTwice {
                    cell: format!("{},{}", cell.0, cell.1),
                    first_line: first.at.0,
                },
            ));
        }
        self.locks.push(DoorLock {
            cell,
            key: name.clone(),
            at: place,
        });
        Ok(())
    }

    /// An `ITEM` or `CREATURE` line at `pos`: a texture, then its options.
    fn thing(
        &mut self,
        at: &LineAt,
        pos: Vec2,
        words: &[(String, usize)],
    ) -> Result<(), LineError> {
        let Some((path, path_col)) = words.get(1) else {
            return Err(at.usage());
        };
        let texture = TextureRef {
            path: path.clone(),
            line: at.line,
            col: *path_col,
        };
        let is_item = at.kind == GameLine::Item;
        let mut o = ThingOptions::new(is_item);
        for (word, col) in &words[2..] {
            o.read(at, word, *col)?;
        }
        let place = (at.line, at.word_col);
        let too_many =
            |what: &'static str, limit: usize| (place, MapErrorKind::TooMany { what, limit });
        if is_item {
            if self.items.len() >= MAX_ITEMS {
                return Err(too_many("ITEM lines", MAX_ITEMS));
            }
            let treasure = if o.key.is_some() {
                0
            } else {
                DEFAULT_TREASURE_POINTS
            };
            self.items.push(ItemDef {
                pos,
                texture,
                points: o.points.unwrap_or(treasure),
                key: o.key,
                scale: o.scale,
                at: place,
            });
        } else {
            if self.creatures.len() >= MAX_CREATURES {
                return Err(too_many("CREATURE lines", MAX_CREATURES));
            }
            self.creatures.push(CreatureDef {
                pos,
                texture,
                speed: o.speed,
                behaviour: o.behaviour,
                scale: o.scale,
                frames: o.frames,
                at: place,
            });
        }
        Ok(())
    }

    /// The checks that need the grid (`cell` reads it): items, creatures and exits over floor,
    /// locks on doors, and an `ITEM` giving every key a lock needs.
    pub(super) fn check(&self, cell: impl Fn(i64, i64) -> Cell) -> Result<(), LineError> {
        let floor = |p: Vec2| {
            matches!(
                cell(p.x.floor() as i64, p.y.floor() as i64),
                Cell::Floor { .. }
            )
        };
        let place = |p: Vec2| format!("{},{}", p.x, p.y);
        for item in &self.items {
            if !floor(item.pos) {
                return Err((item.at, MapErrorKind::ItemOffFloor(place(item.pos))));
            }
        }
        for c in &self.creatures {
            if !floor(c.pos) {
                return Err((c.at, MapErrorKind::CreatureOffFloor(place(c.pos))));
            }
        }
        for e in &self.exits {
            if !matches!(cell(e.cell.0, e.cell.1), Cell::Floor { .. }) {
                let at = format!("{},{}", e.cell.0, e.cell.1);
                return Err((e.at, MapErrorKind::ExitOffFloor(at)));
            }
        }
        let keys: BTreeMap<&str, ()> = self
            .items
            .iter()
            .filter_map(|i| i.key.as_deref().map(|k| (k, ())))
            .collect();
        for lock in &self.locks {
            if !matches!(cell(lock.cell.0, lock.cell.1), Cell::Door(_)) {
                let at = format!("{},{}", lock.cell.0, lock.cell.1);
                return Err((lock.at, MapErrorKind::LockNotOnDoor(at)));
            }
            if !keys.contains_key(lock.key.as_str()) {
                return Err((lock.at, MapErrorKind::LockWithoutKey(lock.key.clone())));
            }
        }
        Ok(())
    }
}

fn key_name_rule(got: &str) -> String {
    format!("a key name is 1-32 letters, digits, '-' or '_', got '{got}'")
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn item_and_creature_lines_read_back_what_was_written(
            x in -50.0f64..50.0, y in -50.0f64..50.0,
            points in 0i64..=MAX_ITEM_POINTS,
            key in "[a-z0-9_-]{1,12}",
            scale in 0.01f64..4.0,
            speed in 0.01f64..MAX_CREATURE_SPEED,
            behaviour in 0usize..3,
        ) {
            let g = read(GameLine::Item, &format!(" {x},{y} tex points={points} key={key} scale={scale}")).unwrap();
            let i = &g.items[0];
            prop_assert_eq!((i.pos, i.points, i.key.as_deref(), i.scale), (Vec2::new(x, y), points, Some(key.as_str()), scale));
            let b = [Behaviour::Wander, Behaviour::Patrol, Behaviour::Chase][behaviour];
            let g = read(GameLine::Creature, &format!("\t{x},{y}\tc  speed={speed} behaviour={}", b.name())).unwrap();
            let c = &g.creatures[0];
            prop_assert_eq!((c.pos, c.speed, c.behaviour), (Vec2::new(x, y), speed, b));
        }

        #[test]
        fn any_text_after_a_game_word_is_read_or_refused_without_panicking(rest in "\\PC{0,40}") {
            for kind in [GameLine::Item, GameLine::DoorLock, GameLine::Exit, GameLine::Creature] {
                let _ = read(kind, &format!(" {rest}"));
            }
        }
    }

    fn read(kind: GameLine, rest: &str) -> Result<GameLines, String> {
        let mut g = GameLines::default();
        g.line(kind, rest, 3, 1, 5)
            .map_err(|((l, c), k)| format!("{l}:{c}: {k}"))?;
        Ok(g)
    }

    #[test]
    fn items_default_to_ten_point_treasures_and_keys_to_nothing() {
        let g = read(GameLine::Item, " 2.5,3.25 coin").unwrap();
        let i = &g.items[0];
        assert_eq!(
            (i.pos, i.points, i.key.as_deref()),
            (Vec2::new(2.5, 3.25), 10, None)
        );
        assert_eq!((i.texture.path.as_str(), i.texture.col), ("coin", 15));
        assert!(i.is_treasure());
        let g = read(GameLine::Item, " 1,1 k key=red").unwrap();
        assert_eq!(
            (g.items[0].points, g.items[0].key.as_deref()),
            (0, Some("red"))
        );
        let g = read(GameLine::Item, " 1,1 k key=red points=5 scale=0.25").unwrap();
        assert_eq!((g.items[0].points, g.items[0].scale), (5, 0.25));
    }

    #[test]
    fn creatures_locks_and_exits() {
        let g = read(GameLine::Creature, " 4.5,2.5 creature").unwrap();
        let c = &g.creatures[0];
        assert_eq!(
            (c.speed, c.behaviour, c.frames),
            (1.5, Behaviour::Wander, 4)
        );
        let g = read(
            GameLine::Creature,
            " 4.5,2.5 c speed=3 behaviour=patrol frames=2",
        )
        .unwrap();
        let c = &g.creatures[0];
        assert_eq!(
            (c.speed, c.behaviour, c.frames),
            (3.0, Behaviour::Patrol, 2)
        );
        let g = read(GameLine::DoorLock, " 3,1 blue").unwrap();
        assert_eq!((g.locks[0].cell, g.locks[0].key.as_str()), ((3, 1), "blue"));
        let g = read(GameLine::Exit, " 7.5,2.5").unwrap();
        assert_eq!(g.exits[0].cell, (7, 2));
    }

    #[test]
    fn bad_lines_name_the_word_and_the_rule() {
        let msg = |k, s: &str| read(k, s).unwrap_err();
        assert_eq!(
            msg(GameLine::Item, " 1,2"),
            "3:1: bad value for ITEM: write 'ITEM x,y texture [points=N] [key=NAME] [scale=S]'"
        );
        assert_eq!(
            msg(GameLine::Item, " 1,2 t points=-3"),
            "3:12: bad value for ITEM: points must be a whole number 0-1000000, got '-3'"
        );
        assert_eq!(
            msg(GameLine::Item, " 1,2 t key=a.b"),
            "3:12: bad value for ITEM: a key name is 1-32 letters, digits, '-' or '_', got 'a.b'"
        );
        assert_eq!(
            msg(GameLine::Item, " 1,2 t speed=2"),
            "3:12: bad value for ITEM: unknown option 'speed=2'"
        );
        assert_eq!(
            msg(GameLine::Creature, " 1,2 t behaviour=fly"),
            "3:12: bad value for CREATURE: behaviour must be wander, patrol or chase, got 'fly'"
        );
        assert_eq!(
            msg(GameLine::Creature, " 1,2 t speed=0"),
            "3:12: bad value for CREATURE: speed must be above 0 and at most 10 (cells per second), got '0'"
        );
        assert_eq!(
            msg(GameLine::DoorLock, " 1.5,2 red"),
            "3:6: bad value for DOORLOCK: the door's cell must be whole numbers x,y, got '1.5,2'"
        );
        assert_eq!(
            msg(GameLine::DoorLock, " 1,2"),
            "3:1: bad value for DOORLOCK: write 'DOORLOCK x,y NAME'"
        );
        assert_eq!(
            msg(GameLine::Exit, " 1;2"),
            "3:6: bad value for EXIT: position must be x,y, got '1;2'"
        );
        assert_eq!(
            msg(GameLine::Exit, " 1,nan"),
            "3:6: bad value for EXIT: y needs a number, got 'nan'"
        );
    }
}
