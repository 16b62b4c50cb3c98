//! A map with its textures loaded: everything the rasterizer needs to paint.

pub mod door;
pub(crate) mod lamp_falloff;
pub(crate) mod lamp_reach;
pub(crate) mod lightmap;
pub(crate) mod ray;
pub(crate) mod sprite;

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use crate::color::Rgb;
use crate::input_file::read_regular_capped;
use crate::map::{Cell, ColourKey, Map, SpriteDef, Surface, TextureRef};
use crate::texture::decode::{
    check_size, image_dimensions, MAX_IMAGE_FILE_BYTES, MAX_TEXTURE_SIDE,
};
use crate::texture::fallback::{Fallback, ImageKind};
use crate::texture::key_tint::{key_colour, tinted};
use crate::texture::sheet::SpriteSheet;
use crate::texture::{builtin, Texture};
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use crate::world::lightmap::LightMap;
use crate::world::sprite::Sprite;

/// Texel indices as the world's samplers make them, for the rasterizers' own texture reads
/// (they reach textures through the world).
pub use crate::texture::texel_index;

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
        let mut loader = Loader {
            map_file: &map.file,
            source,
            strict,
            textures: Vec::new(),
            warnings: Vec::new(),
            warned: HashSet::new(),
            sheets: Vec::new(),
            loaded: HashMap::new(),
            budget: MAX_MAP_TEXELS,
        };
        let faces: Vec<usize> = map
            .faces
            .iter()
            .enumerate()
            .map(|(i, r)| loader.load(r, builtin::fallback_stem(i)))
            .collect::<Result<_, _>>()?;
        let mut wall_tex = [[0; 4]; 10];
        wall_tex[0] = [faces[0], faces[1], faces[2], faces[3]];
        for (d, (slot, given)) in wall_tex.iter_mut().zip(&map.wall_types).enumerate().skip(1) {
            *slot = match given {
                Some(r) => [loader.load(r, builtin::fallback_stem(d))?; 4],
                None if d == 1 => [faces[0], faces[1], faces[2], faces[3]],
                None => [loader.builtin(builtin::fallback_stem(d)); 4],
            };
        }
        let floor_default = loader.surface(&map.floor, "floor")?;
        let ceiling_default = loader.surface(&map.ceiling, "ceiling")?;
        let mut floor = vec![floor_default];
        let mut ceiling = vec![ceiling_default];
        let mut faces = vec![None];
        for zone in &map.zones {
            faces.push(
                zone.wall
                    .as_ref()
                    .map(|s| loader.surface(s, builtin::fallback_stem(0)))
                    .transpose()?,
            );
            floor.push(
                zone.floor
                    .as_ref()
                    .map_or(Ok(floor_default), |s| loader.surface(s, "floor"))?,
            );
            ceiling.push(
                zone.ceiling
                    .as_ref()
                    .map_or(Ok(ceiling_default), |s| loader.surface(s, "ceiling"))?,
            );
        }
        let door_tex = match &map.door_texture {
            Some(r) => loader.load(r, "door")?,
            None => loader.builtin("door"),
        };
        let mut sprites = Vec::new();
        if !map.sprites.is_empty() {
            // Legacy `2` cells: the `S` texture, loaded only when something uses it.
            let sheet = match &map.sprite_texture {
                Some(r) => loader.sheet(r, ColourKey::Auto, LEGACY_SPRITE_FALLBACK)?,
                None => loader.builtin_sheet(LEGACY_SPRITE_FALLBACK),
            };
            let texture = map.sprite_texture.clone().unwrap_or(TextureRef {
                path: LEGACY_SPRITE_FALLBACK.to_owned(),
                line: 0,
                col: 0,
            });
            for &pos in &map.sprites {
                let def = SpriteDef::legacy(pos, texture.clone());
                sprites.push(Sprite { def, sheet });
            }
        }
        for def in &map.sprite_defs {
            let sheet = loader.sheet(&def.texture, def.key, LEGACY_SPRITE_FALLBACK)?;
            sprites.push(Sprite {
                def: def.clone(),
                sheet,
            });
        }
        let mut item_sheets = Vec::with_capacity(map.items.len());
        for item in &map.items {
            let sheet = loader.sheet(&item.texture, ColourKey::Auto, LEGACY_SPRITE_FALLBACK)?;
            item_sheets.push(match &item.key {
                Some(key) => loader.tinted_sheet(sheet, key_colour(key)),
                None => sheet,
            });
        }
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
                floor,
                ceiling,
                faces,
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

/// The index of `t` in `items`, added at the end if no equal one is there (one decoded copy per
/// image, however many map lines name it).
fn intern<T: PartialEq>(items: &mut Vec<T>, t: T) -> usize {
    if let Some(i) = items.iter().position(|e| *e == t) {
        return i;
    }
    items.push(t);
    items.len() - 1
}

/// Loads textures once each, remembering warnings.
struct Loader<'a> {
    map_file: &'a str,
    source: &'a TextureSource,
    strict: bool,
    textures: Vec<Texture>,
    warnings: Warnings,
    warned: HashSet<String>,
    sheets: Vec<SpriteSheet>,
    /// Each file's outcome, so a file named by many lines is read and decoded once: keyed by
    /// path and, for a sprite sheet, its colour key (part of the result); `None` for a texture.
    loaded: HashMap<(String, Option<ColourKey>), Result<usize, String>>,
    /// Texels the map's own image files may still add (see [`MAX_MAP_TEXELS`]).
    budget: usize,
}

impl Loader<'_> {
    fn push(&mut self, t: Texture) -> usize {
        intern(&mut self.textures, t)
    }

    fn builtin(&mut self, stem: &str) -> usize {
        let t = builtin::by_name(stem).expect("fallback stems are embedded");
        self.push(t)
    }

    fn push_sheet(&mut self, t: SpriteSheet) -> usize {
        intern(&mut self.sheets, t)
    }

    /// A copy of sheet `k` recoloured toward `tint` (a key's sprite).
    fn tinted_sheet(&mut self, k: usize, tint: Rgb) -> usize {
        let s = &self.sheets[k];
        let t = SpriteSheet::from_fn(s.width(), s.height(), |x, y| {
            let (c, a) = s.texel(x, y);
            (tinted(c, tint), a)
        });
        self.push_sheet(t)
    }

    /// A copy of texture `k` recoloured toward `tint` (a locked door's panel).
    fn tinted_texture(&mut self, k: usize, tint: Rgb) -> usize {
        let s = &self.textures[k];
        let t = Texture::from_fn(s.width(), s.height(), |x, y| tinted(s.texel(x, y), tint));
        self.push(t)
    }

    fn builtin_sheet(&mut self, stem: &str) -> usize {
        let t = builtin::sheet_by_name(stem).expect("fallback sprite stems are embedded");
        self.push_sheet(t)
    }

    fn sheet(
        &mut self,
        r: &TextureRef,
        key: ColourKey,
        fallback: &str,
    ) -> Result<usize, TextureError> {
        let outcome = self.cached((r.path.clone(), Some(key)), |l| {
            read_sheet(l.source, &r.path, key, &mut l.budget).map(|t| l.push_sheet(t))
        });
        match outcome {
            Ok(i) => Ok(i),
            Err(reason) => {
                let fallback = Fallback::for_file(&r.path, ImageKind::Sprite, fallback);
                self.fall_back(r, reason, &fallback)?;
                Ok(self.builtin_sheet(fallback.stem))
            }
        }
    }

    fn surface(&mut self, s: &Surface, fallback: &str) -> Result<Paint, TextureError> {
        Ok(match s {
            Surface::Colour(c) => Paint::Colour(*c),
            Surface::Texture(r) => Paint::Texture(self.load(r, fallback)?),
        })
    }

    fn load(&mut self, r: &TextureRef, fallback: &str) -> Result<usize, TextureError> {
        let outcome = self.cached((r.path.clone(), None), |l| {
            read_texture(l.source, &r.path, &mut l.budget).map(|t| l.push(t))
        });
        match outcome {
            Ok(i) => Ok(i),
            Err(reason) => {
                let fallback = Fallback::for_file(&r.path, ImageKind::Texture, fallback);
                self.fall_back(r, reason, &fallback)?;
                Ok(self.builtin(fallback.stem))
            }
        }
    }

    /// The outcome of reading the file `key` names: remembered from the first time, else `read`.
    fn cached(
        &mut self,
        key: (String, Option<ColourKey>),
        read: impl FnOnce(&mut Self) -> Result<usize, String>,
    ) -> Result<usize, String> {
        if let Some(known) = self.loaded.get(&key) {
            return known.clone();
        }
        let outcome = read(self);
        self.loaded.insert(key, outcome.clone());
        outcome
    }

    /// A file that could not be read: the error under `strict`, else one warning per path (the
    /// caller then uses the built-in `fallback`, named by the file or chosen by its slot).
    fn fall_back(
        &mut self,
        r: &TextureRef,
        reason: String,
        fallback: &Fallback,
    ) -> Result<(), TextureError> {
        let err = TextureError {
            file: self.map_file.to_owned(),
            line: r.line,
            col: r.col,
            path: r.path.clone(),
            reason,
        };
        if self.strict {
            return Err(err);
        }
        if self.warned.insert(r.path.clone()) {
            self.warnings
                .push(format!("warning: {err}; {}", fallback.says()));
        }
        Ok(())
    }
}

/// Most texels all of a map's own image files may add up to (two images of the largest size):
/// each distinct file is decoded once, but a map can name dozens of texture slots and thousands
/// of sprites, each a different 4096×4096 file. Past it, a texture falls back like a missing one.
pub const MAX_MAP_TEXELS: usize = 1 << 25;

/// An image file within the map's remaining texel `budget`: its header is read, its size
/// checked, and only then is it decoded (the budget is then spent).
fn read_budgeted<T>(
    path: &Path,
    budget: &mut usize,
    decode: impl FnOnce(&[u8]) -> Result<T, String>,
) -> Result<T, String> {
    let bytes = read_image_file(path)?;
    let (w, h) = image_dimensions(&bytes)?;
    check_size((w, h), (MAX_TEXTURE_SIDE, MAX_TEXTURE_SIDE))?;
    let texels = w as usize * h as usize;
    if texels > *budget {
        return Err(format!(
            "the map's images together would exceed {MAX_MAP_TEXELS} pixels (the limit)"
        ));
    }
    let decoded = decode(&bytes)?;
    *budget -= texels;
    Ok(decoded)
}

fn read_texture(source: &TextureSource, path: &str, budget: &mut usize) -> Result<Texture, String> {
    match source {
        TextureSource::Embedded => {
            let stem = Path::new(path)
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or_default();
            builtin::by_name(stem).ok_or_else(|| "no embedded texture of that name".to_owned())
        }
        TextureSource::Dir(dir) => read_budgeted(&dir.join(path), budget, Texture::decode),
    }
}

/// An image file's bytes: only a regular file is read (a FIFO would block the load, a device
/// would read forever), and at most [`MAX_IMAGE_FILE_BYTES`] of it.
fn read_image_file(path: &Path) -> Result<Vec<u8>, String> {
    read_regular_capped(path, MAX_IMAGE_FILE_BYTES).map_err(|e| e.to_string())
}

fn read_sheet(
    source: &TextureSource,
    path: &str,
    key: ColourKey,
    budget: &mut usize,
) -> Result<SpriteSheet, String> {
    match source {
        TextureSource::Embedded => {
            let stem = Path::new(path)
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or_default();
            builtin::sheet_by_name(stem).ok_or_else(|| "no embedded sprite of that name".to_owned())
        }
        TextureSource::Dir(dir) => {
            read_budgeted(&dir.join(path), budget, |b| SpriteSheet::decode(b, key))
        }
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
