//! One map a server plays in its rotation: the loaded world and the content hash its
//! leaderboard is kept under.

use std::path::{Path, PathBuf};

use super::leaderboard::content_hash;
use crate::world::{TextureSource, Warnings, World};

/// A map as served.
#[derive(Debug, Clone)]
pub struct ServedMap {
    /// The loaded level.
    pub world: World,
    /// Its identity on the leaderboard ([`content_hash`] of the map file's bytes).
    pub hash: String,
}

impl ServedMap {
    /// Reads, checks and loads the map file at `path` (errors at file:line:col).
    ///
    /// # Errors
    /// The map's or its textures' error message.
    pub fn from_file(path: &Path, strict: bool) -> Result<(Self, Warnings), String> {
        let name = path.display().to_string();
        let bytes = crate::map::read_map_file(path).map_err(|e| e.to_string())?;
        let map = crate::map::parse_map(&name, &bytes).map_err(|e| e.to_string())?;
        let dir = path
            .parent()
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let (world, warnings) =
            World::load(map, &TextureSource::Dir(dir), strict).map_err(|e| e.to_string())?;
        Ok((
            Self {
                world,
                hash: content_hash(&bytes),
            },
            warnings,
        ))
    }

    /// The embedded default map.
    #[must_use]
    pub fn embedded() -> Self {
        Self {
            world: World::default_world(),
            hash: content_hash(crate::world::DEFAULT_MAP.as_bytes()),
        }
    }

    /// A world built in memory (tests, embedders): hashed by its parsed map, so the same map
    /// text keeps the same board within one build of halfcast.
    #[must_use]
    pub fn from_world(world: World) -> Self {
        let hash = content_hash(format!("{:?}", world.map).as_bytes());
        Self { world, hash }
    }
}
