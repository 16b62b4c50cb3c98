//! A map with its textures loaded: everything the rasterizer needs to paint.

pub mod door;
pub(crate) mod lamp_falloff;
pub(crate) mod lamp_reach;
pub(crate) mod lightmap;
mod loader;
pub(crate) mod ray;
pub(crate) mod sprite;

use std::path::{Path, PathBuf};

use crate::color::Rgb;
use crate::map::{Cell, ColourKey, Map};
use crate::texture::key_tint::key_colour;
use crate::texture::sheet::SpriteSheet;
use crate::texture::Texture;
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::lightmap::LightMap;
use crate::world::sprite::Sprite;

/// Texel indices as the world's samplers make them, for the rasterizers' own texture reads
/// (they reach textures through the world).
pub use crate::texture::texel_index;

use loader::Loader;
pub use loader::MAX_MAP_TEXELS;

/// The default map, compiled in so the binary needs no files.
pub const DEFAULT_MAP: &str = include_str!("../../maps/default.cub");

/// The name the embedded default map goes by in messages.
pub const DEFAULT_MAP_NAME: &str = "maps/default.cub";

/// Where texture paths in a map are looked up.
#[derive(Debug, Clone)]
pub enum TextureSource {
    /// Paths relative to this directory (the map file's own).
    Dir(PathBuf),
    /// Paths name the embedded textures by file stem (`textures/bricks.png` → bricks).
    Embedded,
}

/// A texture that could not be loaded (an error only under `--strict`).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}:{col}: cannot load texture '{path}': {reason}")]
pub struct TextureError {
    /// The map file naming the texture.
    pub file: String,
    /// 1-based line of the texture line.
    pub line: usize,
    /// 1-based column of the path.
    pub col: usize,
    /// The path as written.
    pub path: String,
    /// Why it could not be loaded.
    pub reason: String,
}

/// How a floor or ceiling pixel is painted once textures are loaded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Paint {
    /// A flat colour.
    Colour(Rgb),
    /// A texture, by index into [`World::textures`].
    Texture(usize),
}

/// A [`Paint`] with its texture looked up: what a floor caster keeps while its row stays in one
/// map cell, so no pixel pays for the lookup.
#[derive(Debug, Clone, Copy)]
pub enum Fill<'a> {
    /// A flat colour.
    Colour(Rgb),
    /// A texture.
    Texture(&'a Texture),
}

impl Fill<'_> {
    /// The colour at (u, v), both in [0, 1).
    #[must_use]
    #[inline]
    pub fn at_unit(self, u: f64, v: f64) -> Rgb {
        match self {
            Fill::Colour(c) => c,
            Fill::Texture(t) => t.sample_unit(u, v),
        }
    }
}

/// A map plus its decoded textures, indexed for the per-pixel loops.
#[derive(Debug, Clone)]
pub struct World {
    /// The parsed map.
    pub map: Map,
    /// Every decoded texture.
    pub textures: Vec<Texture>,
    /// Texture index per wall type (0–9) and face seen (looking N, S, W, E).
    wall_tex: [[usize; 4]; 10],
    /// Floor paint per zone (0 = default, 1–26 = a–z).
    floor: Vec<Paint>,
    /// Ceiling paint per zone.
    ceiling: Vec<Paint>,
    /// `Wz` paint of each zone's step and lintel faces (index 0 and zones without `Wz`: none).
    faces: Vec<Option<Paint>>,
    /// Texture index of door panels.
    door_tex: usize,
    /// Decoded sprite sheets (with alpha), indexed by `Sprite::sheet`.
    pub sheets: Vec<SpriteSheet>,
    /// Every sprite: the legacy `2` cells first, then the `SPRITE` lines.
    pub sprites: Vec<Sprite>,
    /// The `LIGHT`s baked onto the floor plan (empty without lights).
    pub lightmap: LightMap,
    /// Sheet index per `ITEM` line (a key's sheet tinted with its key's colour).
    pub item_sheets: Vec<usize>,
    /// Sheet index per `CREATURE` line.
    pub creature_sheets: Vec<usize>,
    /// The sheet shots are drawn with (a soft glow).
    pub glow_sheet: usize,
    /// The sheet exits are drawn with (a glowing arch).
    pub exit_sheet: usize,
    /// Locked doors' cells (sorted) and their panel textures, tinted with their key's colour.
    door_tints: Vec<((i64, i64), usize)>,
}

/// A disc that blocks movement (a solid sprite).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolidDisc {
    /// The sprite's position on the map plane.
    pub centre: Vec2,
    /// Blocking radius in cells.
    pub radius: f64,
}

/// The warnings printed while loading (one line per texture that fell back).
pub type Warnings = Vec<String>;

impl World {
    /// The embedded default map with its embedded textures (decoded once per process).
    #[must_use]
    pub fn default_world() -> Self {
        static DEFAULT: std::sync::OnceLock<World> = std::sync::OnceLock::new();
        DEFAULT
            .get_or_init(|| {
                let map = crate::map::parse_map(DEFAULT_MAP_NAME, DEFAULT_MAP.as_bytes())
                    .expect("the default map is valid");
                let (world, warnings) = Self::load(map, &TextureSource::Embedded, true)
                    .expect("default textures are embedded");
                debug_assert!(warnings.is_empty());
                world
            })
            .clone()
    }

    /// Loads every texture the map names; a missing one falls back to a built-in with a warning,
    /// or is an error when `strict`.
    ///
    /// # Errors
    /// Under `strict`, the first texture that cannot be loaded.
    pub fn load(
        map: Map,
        source: &TextureSource,
        strict: bool,
    ) -> Result<(Self, Warnings), TextureError> {
        let mut loader = Loader::new(&map.file, source, strict);
        let wall_tex = loader.walls(&map)?;
        let zones = loader.zone_paints(&map)?;
        let door_tex = match &map.door_texture {
            Some(r) => loader.load(r, "door")?,
            None => loader.builtin("door"),
        };
        let sprites = loader.sprites(&map)?;
        let item_sheets = loader.item_sheets(&map)?;
        let creature_sheets = map
            .creatures
            .iter()
            .map(|c| loader.sheet(&c.texture, ColourKey::Auto, CREATURE_FALLBACK))
            .collect::<Result<Vec<_>, _>>()?;
        let glow_sheet = loader.builtin_sheet("orb");
        let exit_sheet = loader.builtin_sheet("exit");
        let mut door_tints: Vec<((i64, i64), usize)> = map
            .locks
            .iter()
            .map(|l| (l.cell, loader.tinted_texture(door_tex, key_colour(&l.key))))
            .collect();
        door_tints.sort_unstable();
        let Loader {
            textures,
            warnings,
            sheets,
            ..
        } = loader;
        let lightmap = LightMap::build(&map);
        Ok((
            Self {
                lightmap,
                map,
                textures,
                wall_tex,
                floor: zones.floor,
                ceiling: zones.ceiling,
                faces: zones.faces,
                door_tex,
                sheets,
                sprites,
                item_sheets,
                creature_sheets,
                glow_sheet,
                exit_sheet,
                door_tints,
            },
            warnings,
        ))
    }

    /// The texture for a wall cell, by the compass direction the ray travels (N, S, W, E = 0..4).
    #[must_use]
    #[inline]
    pub fn wall_texture(&self, what: Cell, heading: usize) -> &Texture {
        let kind = match what {
            Cell::Wall(d) => usize::from(d),
            Cell::Door(_) => return &self.textures[self.door_tex],
            _ => 0,
        };
        &self.textures[self.wall_tex[kind][heading]]
    }

    /// [`World::wall_texture`] for the face of cell `cell`: a locked door's panel shows its
    /// key's colour.
    #[must_use]
    #[inline]
    pub fn wall_texture_at(&self, what: Cell, cell: (i64, i64), heading: usize) -> &Texture {
        match self.door_tint(what, cell) {
            Some(t) => &self.textures[t],
            None => self.wall_texture(what, heading),
        }
    }

    /// [`World::face_paint`] for the face of cell `cell` (a locked door's panel is tinted).
    #[must_use]
    #[inline]
    pub fn face_paint_at(&self, what: Cell, cell: (i64, i64), heading: usize) -> Paint {
        match self.door_tint(what, cell) {
            Some(t) => Paint::Texture(t),
            None => self.face_paint(what, heading),
        }
    }

    /// The tinted panel texture of a locked door at `cell`, if `what` is one.
    #[inline]
    fn door_tint(&self, what: Cell, cell: (i64, i64)) -> Option<usize> {
        if self.door_tints.is_empty() || !matches!(what, Cell::Door(_)) {
            return None;
        }
        self.door_tints
            .binary_search_by(|(c, _)| c.cmp(&cell))
            .ok()
            .map(|k| self.door_tints[k].1)
    }

    /// The paint of a vertical face of `what` (the cell whose solid part it is) seen heading
    /// N, S, W, E (0..4): a wall's or door's texture; for a walkable cell's step or lintel its
    /// zone's `Wz`, or else the `NO`/`SO`/`WE`/`EA` textures as walls.
    #[must_use]
    #[inline]
    pub fn face_paint(&self, what: Cell, heading: usize) -> Paint {
        match what {
            Cell::Wall(d) => Paint::Texture(self.wall_tex[usize::from(d)][heading]),
            Cell::Door(_) => Paint::Texture(self.door_tex),
            Cell::Floor { zone } => self
                .faces
                .get(usize::from(zone))
                .copied()
                .flatten()
                .unwrap_or(Paint::Texture(self.wall_tex[0][heading])),
            Cell::Void => Paint::Texture(self.wall_tex[0][heading]),
        }
    }

    /// Floor paint of a zone.
    #[must_use]
    #[inline]
    pub fn floor_paint(&self, zone: u8) -> Paint {
        self.floor
            .get(usize::from(zone))
            .copied()
            .unwrap_or(self.floor[0])
    }

    /// `paint` with its texture looked up.
    #[must_use]
    #[inline]
    pub fn fill(&self, paint: Paint) -> Fill<'_> {
        match paint {
            Paint::Colour(c) => Fill::Colour(c),
            Paint::Texture(i) => Fill::Texture(&self.textures[i]),
        }
    }

    /// Ceiling paint of a zone.
    #[must_use]
    #[inline]
    pub fn ceiling_paint(&self, zone: u8) -> Paint {
        self.ceiling
            .get(usize::from(zone))
            .copied()
            .unwrap_or(self.ceiling[0])
    }

    /// What the floor (or the ceiling) over map cell (`i`, `j`) shows, texture looked up: the
    /// cell's zone's paint, the default zone's for walls and off the map. The flat floor casters
    /// read it once per run of pixels in one cell.
    #[must_use]
    #[inline]
    pub fn surface_fill(&self, i: i64, j: i64, is_floor: bool) -> Fill<'_> {
        let zone = match self.map.cell(i, j) {
            Cell::Floor { zone } => zone,
            _ => 0,
        };
        self.fill(if is_floor {
            self.floor_paint(zone)
        } else {
            self.ceiling_paint(zone)
        })
    }
}

/// The built-in sheet a sprite falls back to when its texture cannot be loaded.
pub const LEGACY_SPRITE_FALLBACK: &str = "barrel";

/// The built-in sheet a `CREATURE` falls back to when its texture cannot be loaded.
pub const CREATURE_FALLBACK: &str = "creature";

impl World {
    /// The discs of every solid sprite, for movement code that wants them directly.
    #[must_use]
    pub fn solid_discs(&self) -> Vec<SolidDisc> {
        self.sprites
            .iter()
            .filter_map(|s| {
                s.def.solid.map(|radius| SolidDisc {
                    centre: s.def.pos,
                    radius,
                })
            })
            .collect()
    }

    /// Whether a body of `radius` centred at `pos` would overlap a wall, void, a door that is
    /// not open far enough (its whole cell blocks), or a solid sprite. Pure: the game step asks.
    #[must_use]
    pub fn is_blocked(&self, pos: Vec2, radius: f64, doors: &DoorState) -> bool {
        let r = radius.max(0.0);
        let (x0, x1) = ((pos.x - r).floor() as i64, (pos.x + r).floor() as i64);
        let (y0, y1) = ((pos.y - r).floor() as i64, (pos.y + r).floor() as i64);
        for j in y0..=y1 {
            for i in x0..=x1 {
                let blocking = match self.map.cell(i, j) {
                    Cell::Floor { .. } => false,
                    Cell::Door(_) => doors.blocks((i, j)),
                    _ => true,
                };
                if !blocking {
                    continue;
                }
                // Distance from the centre to the cell's square; touching is allowed.
                let dx = pos.x - pos.x.clamp(i as f64, i as f64 + 1.0);
                let dy = pos.y - pos.y.clamp(j as f64, j as f64 + 1.0);
                if dx * dx + dy * dy < r * r || (r == 0.0 && dx == 0.0 && dy == 0.0) {
                    return true;
                }
            }
        }
        self.sprites.iter().any(|s| {
            s.def.solid.is_some_and(|sr| {
                let d = s.def.pos - pos;
                d.dot(d) < (sr + r) * (sr + r)
            })
        })
    }
}

/// Why a map file could not become a world.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LoadError {
    /// The map file itself is invalid.
    #[error(transparent)]
    Map(#[from] crate::map::MapError),
    /// A texture could not be loaded (under `strict`).
    #[error(transparent)]
    Texture(#[from] TextureError),
}

impl World {
    /// Reads and parses a map file, loading textures relative to its folder.
    ///
    /// # Errors
    /// An unreadable file or a broken rule ([`LoadError::Map`]), or under `strict` a texture.
    pub fn from_file(path: &Path, strict: bool) -> Result<(Self, Warnings), LoadError> {
        let name = path.display().to_string();
        let bytes = crate::map::read_map_file(path)?;
        let map = crate::map::parse_map(&name, &bytes)?;
        let dir = path
            .parent()
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        Ok(Self::load(map, &TextureSource::Dir(dir), strict)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::parse_map;
    use crate::texture::builtin;

    fn world(extra: &str) -> World {
        let text = format!("{extra}NO a/bricks.png\nSO a/stone.png\nWE a/wood.png\nEA a/metal.png\nF 1,2,3\nC 4,5,6\n111\n1N1\n131\n111\n");
        World::load(
            parse_map("w.cub", text.as_bytes()).unwrap(),
            &TextureSource::Embedded,
            true,
        )
        .unwrap()
        .0
    }

    #[test]
    fn type_1_walls_use_the_four_faces_and_t1_overrides_them() {
        let w = world("");
        let bricks = builtin::by_name("bricks").unwrap();
        let stone = builtin::by_name("stone").unwrap();
        assert_eq!(w.wall_texture(Cell::Wall(1), 0), &bricks);
        assert_eq!(w.wall_texture(Cell::Wall(1), 1), &stone);
        let w = world("T1 x/mossy.png\n");
        let mossy = builtin::by_name("mossy").unwrap();
        assert!((0..4).all(|h| w.wall_texture(Cell::Wall(1), h) == &mossy));
    }

    #[test]
    fn wall_types_without_a_texture_line_get_a_builtin() {
        let w = world("");
        assert_eq!(
            w.wall_texture(Cell::Wall(3), 2),
            &builtin::by_name(builtin::fallback_stem(3)).unwrap()
        );
    }

    #[test]
    fn the_default_world_loads_without_warnings() {
        let map = parse_map(DEFAULT_MAP_NAME, DEFAULT_MAP.as_bytes()).unwrap();
        let (_, warnings) = World::load(map, &TextureSource::Embedded, true).unwrap();
        assert!(warnings.is_empty());
    }
}
