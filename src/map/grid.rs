//! The map's grid as the reader builds it: the cells read from the grid lines, then the checks
//! that need neighbours (closed walls, framed doors) and the things placed on the grid.

use super::{Cell, DoorPlane, LightDef, MapErrorKind, SpriteDef, Start, Zone};
use crate::vec2::Vec2;

/// An error at a 1-based (line, column), or for the whole map.
pub(super) type GridError = (Option<(usize, usize)>, MapErrorKind);

/// The cells, row by row, with the grid lines they were read from (1-based line, text).
pub(super) struct Grid<'a> {
    pub(super) width: usize,
    pub(super) height: usize,
    pub(super) cells: Vec<Cell>,
    lines: &'a [(usize, &'a str)],
}

/// What the grid's characters place besides cells: the player and the legacy `2` sprites.
pub(super) struct Placed {
    pub(super) start: Start,
    pub(super) sprites: Vec<Vec2>,
}

/// What the header says that reading the grid's characters needs.
pub(super) struct GridRules<'a> {
    /// `T2` is given: `2` is a wall, not a sprite.
    pub(super) sprite_is_wall: bool,
    /// Sprites that may still be placed by `2` cells.
    pub(super) sprites_left: usize,
    pub(super) zones: &'a [Zone],
    pub(super) too_many_sprites: MapErrorKind,
}

impl<'a> Grid<'a> {
    /// An empty (void) grid as wide as the longest line.
    pub(super) fn sized(lines: &'a [(usize, &'a str)]) -> Self {
        let width = lines
            .iter()
            .map(|(_, l)| l.chars().count())
            .max()
            .unwrap_or(0);
        let height = lines.len();
        Self {
            width,
            height,
            cells: Vec::new(),
            lines,
        }
    }

    /// The cell at (`i`, `j`); outside the grid is void.
    pub(super) fn at(&self, i: i64, j: i64) -> Cell {
        if i < 0 || j < 0 || i as usize >= self.width || j as usize >= self.height {
            Cell::Void
        } else {
            self.cells[j as usize * self.width + i as usize]
        }
    }

    /// Every character of the grid lines with its cell position and 1-based line.
    fn chars(&self) -> impl Iterator<Item = (usize, usize, usize, char)> + 'a {
        let lines = self.lines;
        lines.iter().enumerate().flat_map(|(j, &(line_no, line))| {
            line.chars()
                .enumerate()
                .map(move |(i, ch)| (i, j, line_no, ch))
        })
    }

    /// Reads the characters into cells (doors get their plane later, in [`Grid::door_planes`]);
    /// one player, known zones, and the sprite limit.
    pub(super) fn read(&mut self, rules: &GridRules) -> Result<Placed, GridError> {
        self.cells = vec![Cell::Void; self.width * self.height];
        let mut start: Option<(Start, usize, usize)> = None;
        let mut sprites = Vec::new();
        for (i, j, line_no, ch) in self.chars() {
            let at = Some((line_no, i + 1));
            self.cells[j * self.width + i] = match ch {
                ' ' => Cell::Void,
                '0' => Cell::Floor { zone: 0 },
                '2' if !rules.sprite_is_wall => {
                    if sprites.len() >= rules.sprites_left {
                        return Err((at, rules.too_many_sprites.clone()));
                    }
                    sprites.push(Vec2::new(i as f64 + 0.5, j as f64 + 0.5));
                    Cell::Floor { zone: 0 }
                }
                '1'..='9' => Cell::Wall(ch as u8 - b'0'),
                // The plane is fixed later, once the neighbours are known.
                'D' => Cell::Door(DoorPlane::X),
                'N' | 'S' | 'E' | 'W' => {
                    if let Some((_, l, c)) = start {
                        let kind = MapErrorKind::SecondPlayer {
                            first_line: l,
                            first_col: c,
                        };
                        return Err((at, kind));
                    }
                    let here = Start {
                        cell: (i, j),
                        facing: ch,
                    };
                    start = Some((here, line_no, i + 1));
                    Cell::Floor { zone: 0 }
                }
                'a'..='z' => {
                    let z = usize::from(ch as u8 - b'a');
                    if rules.zones.get(z).is_none_or(|zone| {
                        zone.floor.is_none()
                            && zone.ceiling.is_none()
                            && zone.heights.is_none()
                            && zone.wall.is_none()
                    }) {
                        return Err((at, MapErrorKind::UndefinedZone(ch)));
                    }
                    Cell::Floor { zone: z as u8 + 1 }
                }
                _ => return Err((at, MapErrorKind::BadMapChar(ch))),
            };
        }
        let Some((start, _, _)) = start else {
            return Err((None, MapErrorKind::NoPlayer));
        };
        Ok(Placed { start, sprites })
    }

    /// Every floor and door has no void beside it (diagonals do not count).
    pub(super) fn check_closed(&self) -> Result<(), GridError> {
        for (i, j, line_no, ch) in self.chars() {
            if !matches!(
                self.cells[j * self.width + i],
                Cell::Floor { .. } | Cell::Door(_)
            ) {
                continue;
            }
            let (x, y) = (i as i64, j as i64);
            let open = [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)]
                .iter()
                .any(|&(a, b)| self.at(a, b) == Cell::Void);
            if open {
                let what = match ch {
                    'N' | 'S' | 'E' | 'W' => "player",
                    '2' => "sprite",
                    'D' => "door",
                    'a'..='z' => "zone floor",
                    _ => "floor",
                };
                let kind = MapErrorKind::NotClosed {
                    what,
                    line: line_no,
                    col: i + 1,
                };
                return Err((Some((line_no, i + 1)), kind));
            }
        }
        Ok(())
    }

    /// Each door's plane, from the walls that frame it (west and east, or north and south), as
    /// (cell index, plane); set them with [`Grid::set_doors`] once every check has passed.
    pub(super) fn door_planes(&self) -> Result<Vec<(usize, DoorPlane)>, GridError> {
        let mut planes = Vec::new();
        for (i, j, line_no, ch) in self.chars() {
            if ch != 'D' {
                continue;
            }
            let (x, y) = (i as i64, j as i64);
            let wall = |a: i64, b: i64| matches!(self.at(a, b), Cell::Wall(_));
            let plane = if wall(x - 1, y) && wall(x + 1, y) {
                DoorPlane::Y
            } else if wall(x, y - 1) && wall(x, y + 1) {
                DoorPlane::X
            } else {
                let kind = MapErrorKind::DoorNotFramed {
                    line: line_no,
                    col: i + 1,
                };
                return Err((Some((line_no, i + 1)), kind));
            };
            planes.push((j * self.width + i, plane));
        }
        Ok(planes)
    }

    /// Gives the doors their planes.
    pub(super) fn set_doors(&mut self, planes: Vec<(usize, DoorPlane)>) {
        for (k, plane) in planes {
            self.cells[k] = Cell::Door(plane);
        }
    }

    /// Sprites stand on floor, lights on floor or doors.
    pub(super) fn check_placed(
        &self,
        sprites: &[SpriteDef],
        lights: &[LightDef],
    ) -> Result<(), GridError> {
        let cell_of = |p: Vec2| self.at(p.x.floor() as i64, p.y.floor() as i64);
        for def in sprites {
            if !matches!(cell_of(def.pos), Cell::Floor { .. }) {
                let kind = MapErrorKind::SpriteOffFloor(format!("{},{}", def.pos.x, def.pos.y));
                return Err((Some(def.at), kind));
            }
        }
        for def in lights {
            if !matches!(cell_of(def.pos), Cell::Floor { .. } | Cell::Door(_)) {
                let kind = MapErrorKind::LightOffFloor(format!("{},{}", def.pos.x, def.pos.y));
                return Err((Some(def.at), kind));
            }
        }
        Ok(())
    }
}
