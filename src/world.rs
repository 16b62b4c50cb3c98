//! A map with its textures loaded: everything the rasterizer needs to paint.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use crate::color::Rgb;
use crate::map::{Cell, Map, Surface, TextureRef};
use crate::texture::{builtin, Texture};

/// The default map, compiled in so the binary needs no files.
pub const DEFAULT_MAP: &str = include_str!("../maps/default.cub");

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
    pub file: String,
    pub line: usize,
    pub col: usize,
    pub path: String,
    pub reason: String,
}

/// How a floor or ceiling pixel is painted once textures are loaded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Paint {
    Colour(Rgb),
    Texture(usize),
}

/// A map plus its decoded textures, indexed for the per-pixel loops.
#[derive(Debug, Clone)]
pub struct World {
    pub map: Map,
    pub textures: Vec<Texture>,
    /// Texture index per wall type (0–9) and face seen (looking N, S, W, E).
    wall_tex: [[usize; 4]; 10],
    /// Floor paint per zone (0 = default, 1–26 = a–z).
    floor: Vec<Paint>,
    /// Ceiling paint per zone.
    ceiling: Vec<Paint>,
}

/// The warnings printed while loading (one line per texture that fell back).
pub type Warnings = Vec<String>;

impl World {
    /// The embedded default map with its embedded textures.
    #[must_use]
    pub fn default_world() -> Self {
        let map = crate::map::parse_map(DEFAULT_MAP_NAME, DEFAULT_MAP.as_bytes())
            .expect("the default map is valid");
        let (world, warnings) =
            Self::load(map, &TextureSource::Embedded, true).expect("default textures are embedded");
        debug_assert!(warnings.is_empty());
        world
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
        for zone in &map.zones {
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
        let Loader {
            textures, warnings, ..
        } = loader;
        Ok((
            Self {
                map,
                textures,
                wall_tex,
                floor,
                ceiling,
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
            _ => 0,
        };
        &self.textures[self.wall_tex[kind][heading]]
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

    /// Ceiling paint of a zone.
    #[must_use]
    #[inline]
    pub fn ceiling_paint(&self, zone: u8) -> Paint {
        self.ceiling
            .get(usize::from(zone))
            .copied()
            .unwrap_or(self.ceiling[0])
    }
}

/// Loads textures once each, remembering warnings.
struct Loader<'a> {
    map_file: &'a str,
    source: &'a TextureSource,
    strict: bool,
    textures: Vec<Texture>,
    warnings: Warnings,
    warned: HashSet<String>,
}

impl Loader<'_> {
    fn push(&mut self, t: Texture) -> usize {
        if let Some(i) = self.textures.iter().position(|e| *e == t) {
            return i;
        }
        self.textures.push(t);
        self.textures.len() - 1
    }

    fn builtin(&mut self, stem: &str) -> usize {
        let t = builtin::by_name(stem).expect("fallback stems are embedded");
        self.push(t)
    }

    fn surface(&mut self, s: &Surface, fallback: &str) -> Result<Paint, TextureError> {
        Ok(match s {
            Surface::Colour(c) => Paint::Colour(*c),
            Surface::Texture(r) => Paint::Texture(self.load(r, fallback)?),
        })
    }

    fn load(&mut self, r: &TextureRef, fallback: &str) -> Result<usize, TextureError> {
        match read_texture(self.source, &r.path) {
            Ok(t) => Ok(self.push(t)),
            Err(reason) => {
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
                    self.warnings.push(format!(
                        "warning: {err}; using the built-in '{fallback}' texture"
                    ));
                }
                Ok(self.builtin(fallback))
            }
        }
    }
}

fn read_texture(source: &TextureSource, path: &str) -> Result<Texture, String> {
    match source {
        TextureSource::Embedded => {
            let stem = Path::new(path)
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or_default();
            builtin::by_name(stem).ok_or_else(|| "no embedded texture of that name".to_owned())
        }
        TextureSource::Dir(dir) => {
            let full = dir.join(path);
            let bytes = std::fs::read(&full).map_err(|e| e.to_string())?;
            Texture::decode(&bytes)
        }
    }
}

/// Why a map file could not become a world.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LoadError {
    #[error(transparent)]
    Map(#[from] crate::map::MapError),
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
        let bytes = std::fs::read(path).map_err(|e| crate::map::MapError {
            file: name.clone(),
            at: None,
            kind: crate::map::MapErrorKind::Io(e.to_string()),
        })?;
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
