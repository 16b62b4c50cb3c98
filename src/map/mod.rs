//! The world's grid and header, as parsed from a `.cub` file (no textures loaded yet).

mod error;
mod fog;
mod game_objects;
mod grid;
mod header;
mod lamp;
mod parse;
mod read;
mod sprite;
mod words;

pub use error::{MapError, MapErrorKind};
pub use fog::Fog;
pub use game_objects::{
    Behaviour, CreatureDef, DoorLock, ExitDef, ItemDef, DEFAULT_CREATURE_SPEED,
    DEFAULT_TREASURE_POINTS, MAX_CREATURES, MAX_CREATURE_SPEED, MAX_ITEMS, MAX_ITEM_POINTS,
};
pub use header::{MAX_LIGHTS, MAX_SPRITES};
pub use lamp::{LightDef, MAX_LIGHT_RADIUS};
pub use parse::{parse_map, MAX_CELLS, MAX_LIT_CELLS};
pub use read::{read_map_file, MAX_MAP_BYTES};
pub use sprite::{Blend, ColourKey, SpriteDef, DEFAULT_SOLID_RADIUS};

use crate::color::Rgb;

use crate::vec2::Vec2;

/// What one grid cell holds; walls carry their digit (1–9), floors their zone (0 = default).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cell {
    /// Outside the map (a space in the file, or beyond a short row).
    Void,
    /// Walkable; `zone` 0 is the default floor, 1–26 the zone letters `a`–`z`.
    Floor {
        /// 0 for plain floor, 1–26 for `a`–`z`.
        zone: u8,
    },
    /// Solid wall of type 1–9 (each type has its own texture).
    Wall(u8),
    /// A sliding door (`D`), drawn as a thin panel across the middle of its cell.
    Door(DoorPlane),
}

/// Which way a door panel lies, fixed by the walls that frame it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DoorPlane {
    /// The panel is the line x = i + 0.5 (walls north and south; the passage runs east–west).
    X,
    /// The panel is the line y = j + 0.5 (walls east and west; the passage runs north–south).
    Y,
}

impl Cell {
    /// Whether a ray stops on entering: walls, and void (never reached from inside a closed map).
    /// Doors do not: the caster tests their inset panel separately.
    #[must_use]
    #[inline]
    pub fn blocks_ray(self) -> bool {
        !matches!(self, Cell::Floor { .. } | Cell::Door(_))
    }
}

/// A texture path as written in the map, with where it was written (for warnings).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TextureRef {
    /// The path as written (relative paths are resolved against the map's folder).
    pub path: String,
    /// 1-based line of the path in the map file.
    pub line: usize,
    /// 1-based column of the path.
    pub col: usize,
}

/// How a floor or ceiling is painted: a flat colour or a texture.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Surface {
    /// One flat colour (`r,g,b`).
    Colour(Rgb),
    /// A texture file, world-anchored.
    Texture(TextureRef),
}

/// Floor and ceiling overrides for cells marked with one zone letter.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Zone {
    /// `Fz`: the zone's floor paint.
    pub floor: Option<Surface>,
    /// `Cz`: the zone's ceiling paint.
    pub ceiling: Option<Surface>,
    /// `Hz FLOOR CEIL`: the open span of the zone's cells, in wall heights.
    pub heights: Option<Span>,
    /// `Wz VALUE`: the paint of the zone's step and lintel faces (otherwise the NO/SO/WE/EA walls').
    pub wall: Option<Surface>,
}

/// Highest rise of the floor walked onto without jumping, in wall heights: a step. The game's
/// bodies climb it and the minimap draws heights in it, so both read one constant.
pub const STEP_UP: f64 = 0.25;

/// The open air of a walkable cell, between its floor and its ceiling, in wall heights (a plain
/// cell is 0 to 1); everything above and below it is solid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    /// Height of the floor (solid below).
    pub floor: f64,
    /// Height of the ceiling (solid above).
    pub ceil: f64,
}

impl Span {
    /// What every cell outside an `Hz` zone has: Wolfenstein's floor at 0 and ceiling at 1.
    pub const FLAT: Span = Span {
        floor: 0.0,
        ceil: 1.0,
    };

    /// Lowest floor height an `Hz` line may give.
    pub const MIN_FLOOR: f64 = -4.0;

    /// Highest ceiling height an `Hz` line may give.
    pub const MAX_CEIL: f64 = 8.0;

    /// Open height between floor and ceiling.
    #[must_use]
    pub fn height(self) -> f64 {
        self.ceil - self.floor
    }
}

/// The player's start: a cell centre and a facing, from the N/S/E/W letter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Start {
    /// The cell (column, row) holding the letter.
    pub cell: (usize, usize),
    /// The letter: `N`, `S`, `E` or `W`.
    pub facing: char,
}

impl Start {
    /// The cell centre, where the player stands at start.
    #[must_use]
    pub fn pos(&self) -> Vec2 {
        Vec2::new(self.cell.0 as f64 + 0.5, self.cell.1 as f64 + 0.5)
    }

    /// The facing in CLI degrees: E = 0, N = 90, W = 180, S = 270.
    #[must_use]
    pub fn angle_deg(&self) -> f64 {
        match self.facing {
            'N' => 90.0,
            'W' => 180.0,
            'S' => 270.0,
            _ => 0.0,
        }
    }
}

/// A parsed map: grid, start, colours and the texture paths it names.
#[derive(Debug, Clone, PartialEq)]
pub struct Map {
    /// The path it was read from, as given (for messages).
    pub file: String,
    /// Its file name alone (for the status line).
    pub name: String,
    /// Cells per row (the longest row of the grid; short rows end in void).
    pub width: usize,
    /// Rows of the grid.
    pub height: usize,
    cells: Vec<Cell>,
    /// Where the player starts and which way it faces.
    pub start: Start,
    /// Wall textures for type-1 walls, by the face the ray sees: NO, SO, WE, EA.
    pub faces: [TextureRef; 4],
    /// Textures for wall types 2–9 given by `T2`…`T9` (index = digit).
    pub wall_types: [Option<TextureRef>; 10],
    /// `F`/`FT`: the floor of plain cells.
    pub floor: Surface,
    /// `C`/`CT`: the ceiling of plain cells.
    pub ceiling: Surface,
    /// Zone letters `a`–`z` (index 0 = `a`).
    pub zones: Vec<Zone>,
    /// The legacy `S` sprite texture.
    pub sprite_texture: Option<TextureRef>,
    /// Legacy `2` cells: sprite positions (cell centres), kept for the sprite renderer.
    pub sprites: Vec<Vec2>,
    /// The legacy `R w h` line, accepted and otherwise ignored.
    pub resolution: Option<(u32, u32)>,
    /// halfcast's own `SPRITE` lines, in file order (drawn after the legacy ones).
    pub sprite_defs: Vec<SpriteDef>,
    /// The `TD` door texture, if given (otherwise the built-in door).
    pub door_texture: Option<TextureRef>,
    /// The `FOG r,g,b density` line.
    pub fog: Option<Fog>,
    /// The `SHADE falloff` line: distance darkening strength (see [`crate::render::light::Lighting`]).
    pub shade: Option<f64>,
    /// halfcast's `LIGHT` lines, in file order.
    pub lights: Vec<LightDef>,
    /// `ITEM` lines: treasures and keys to pick up, in file order.
    pub items: Vec<ItemDef>,
    /// `DOORLOCK` lines: doors that need a key.
    pub locks: Vec<DoorLock>,
    /// `EXIT` lines: cells that end the level.
    pub exits: Vec<ExitDef>,
    /// `CREATURE` lines, in file order.
    pub creatures: Vec<CreatureDef>,
}

impl Map {
    /// The cell at column `i`, row `j`; anything outside the grid is void.
    #[must_use]
    #[inline]
    pub fn cell(&self, i: i64, j: i64) -> Cell {
        if i < 0 || j < 0 || i as usize >= self.width || j as usize >= self.height {
            Cell::Void
        } else {
            self.cells[j as usize * self.width + i as usize]
        }
    }

    /// The open span of the cell at (`i`, `j`): its zone's `Hz` heights, [`Span::FLAT`] for other
    /// floors and doors (a door spans its cell's floor to ceiling), `None` where it is solid at
    /// every height (walls and void).
    #[must_use]
    #[inline]
    pub fn span(&self, i: i64, j: i64) -> Option<Span> {
        match self.cell(i, j) {
            Cell::Floor { zone } if zone > 0 => Some(
                self.zones
                    .get(usize::from(zone - 1))
                    .and_then(|z| z.heights)
                    .unwrap_or(Span::FLAT),
            ),
            Cell::Floor { .. } | Cell::Door(_) => Some(Span::FLAT),
            Cell::Wall(_) | Cell::Void => None,
        }
    }

    /// The height of the floor in cell (`i`, `j`): what a body there stands on (its span's floor;
    /// 0 for walls and the void, and on flat maps).
    #[must_use]
    #[inline]
    pub fn floor_height(&self, i: i64, j: i64) -> f64 {
        self.span(i, j).map_or(0.0, |s| s.floor)
    }

    /// Whether any zone has an `Hz` line: without one the world is flat and renders exactly as
    /// Wolfenstein-style maps always have (renderers take the flat path).
    #[must_use]
    pub fn has_heights(&self) -> bool {
        self.zones.iter().any(|z| z.heights.is_some())
    }

    /// Whether the map is a game level (something to pick up or an exit to reach): the HUD and
    /// the SSH scoreboard show only then.
    #[must_use]
    pub fn has_game(&self) -> bool {
        !self.items.is_empty() || !self.exits.is_empty()
    }

    /// Whether a point stands in a walkable cell (used by collision and pose checks).
    /// Door cells are not walkable here; whether one is open is dynamic (see [`crate::world::door`]).
    #[must_use]
    pub fn is_walkable(&self, p: Vec2) -> bool {
        matches!(
            self.cell(p.x.floor() as i64, p.y.floor() as i64),
            Cell::Floor { .. }
        )
    }
}

impl Map {
    /// Every door cell, in row-major order (the index a [`crate::world::door::DoorState`] uses).
    #[must_use]
    pub fn door_cells(&self) -> Vec<(i64, i64)> {
        let w = self.width.max(1);
        self.cells
            .iter()
            .enumerate()
            .filter(|(_, c)| matches!(c, Cell::Door(_)))
            .map(|(k, _)| ((k % w) as i64, (k / w) as i64))
            .collect()
    }
}

/// A map from just a grid (minimal header, no textures on disk): unit tests of the maths on maps.
#[cfg(test)]
pub(crate) fn grid_map(grid: &str) -> Map {
    const HEADER: &str = "NO n\nSO s\nWE w\nEA e\nF 1,2,3\nC 4,5,6\n";
    parse_map("t.cub", format!("{HEADER}{grid}").as_bytes()).expect("test grid parses")
}
