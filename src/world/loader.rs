//! Loading a map's images once each: textures and sprite sheets by path (and colour key),
//! within the map's texel budget, with a built-in stand-in and one warning for a file that
//! cannot be read (or the error, when strict).

use std::collections::{HashMap, HashSet};
use std::path::Path;

use super::sprite::Sprite;
use super::{Paint, TextureError, TextureSource, Warnings, LEGACY_SPRITE_FALLBACK};
use crate::color::Rgb;
use crate::input_file::read_regular_capped;
use crate::map::{ColourKey, Map, SpriteDef, Surface, TextureRef};
use crate::texture::decode::{
    check_size, image_dimensions, MAX_IMAGE_FILE_BYTES, MAX_TEXTURE_SIDE,
};
use crate::texture::fallback::{Fallback, ImageKind};
use crate::texture::key_tint::{key_colour, tinted};
use crate::texture::sheet::SpriteSheet;
use crate::texture::{builtin, Texture};

/// The paints of zone 0 (the map's own floor and ceiling) and of each zone letter after it.
pub(super) struct ZonePaints {
    pub(super) floor: Vec<Paint>,
    pub(super) ceiling: Vec<Paint>,
    /// A zone's wall paint, if its `Wz` line gives one (zone 0 has none).
    pub(super) faces: Vec<Option<Paint>>,
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
pub(super) struct Loader<'a> {
    map_file: &'a str,
    source: &'a TextureSource,
    strict: bool,
    pub(super) textures: Vec<Texture>,
    pub(super) warnings: Warnings,
    warned: HashSet<String>,
    pub(super) sheets: Vec<SpriteSheet>,
    /// Each file's outcome, so a file named by many lines is read and decoded once: keyed by
    /// path and, for a sprite sheet, its colour key (part of the result); `None` for a texture.
    loaded: HashMap<(String, Option<ColourKey>), Result<usize, String>>,
    /// Texels the map's own image files may still add (see [`MAX_MAP_TEXELS`]).
    budget: usize,
}

impl<'a> Loader<'a> {
    /// A loader for the map read from `map_file`, its images from `source`; `strict` makes a
    /// missing image an error instead of a warning and a built-in stand-in.
    pub(super) fn new(map_file: &'a str, source: &'a TextureSource, strict: bool) -> Self {
        Self {
            map_file,
            source,
            strict,
            textures: Vec::new(),
            warnings: Vec::new(),
            warned: HashSet::new(),
            sheets: Vec::new(),
            loaded: HashMap::new(),
            budget: MAX_MAP_TEXELS,
        }
    }

    /// The wall textures by wall type (`1`-`9`; 0 is the four faces) and heading: type 1 is
    /// the faces unless `T1` says otherwise, a type without a line gets a built-in.
    pub(super) fn walls(&mut self, map: &Map) -> Result<[[usize; 4]; 10], TextureError> {
        let faces: Vec<usize> = map
            .faces
            .iter()
            .enumerate()
            .map(|(i, r)| self.load(r, builtin::fallback_stem(i)))
            .collect::<Result<_, _>>()?;
        let mut wall_tex = [[0; 4]; 10];
        wall_tex[0] = [faces[0], faces[1], faces[2], faces[3]];
        for (d, (slot, given)) in wall_tex.iter_mut().zip(&map.wall_types).enumerate().skip(1) {
            *slot = match given {
                Some(r) => [self.load(r, builtin::fallback_stem(d))?; 4],
                None if d == 1 => [faces[0], faces[1], faces[2], faces[3]],
                None => [self.builtin(builtin::fallback_stem(d)); 4],
            };
        }
        Ok(wall_tex)
    }

    /// The floor, ceiling and wall paint of zone 0 (the map's own) and of each zone letter.
    pub(super) fn zone_paints(&mut self, map: &Map) -> Result<ZonePaints, TextureError> {
        let floor_default = self.surface(&map.floor, "floor")?;
        let ceiling_default = self.surface(&map.ceiling, "ceiling")?;
        let mut z = ZonePaints {
            floor: vec![floor_default],
            ceiling: vec![ceiling_default],
            faces: vec![None],
        };
        for zone in &map.zones {
            z.faces.push(
                zone.wall
                    .as_ref()
                    .map(|s| self.surface(s, builtin::fallback_stem(0)))
                    .transpose()?,
            );
            z.floor.push(
                zone.floor
                    .as_ref()
                    .map_or(Ok(floor_default), |s| self.surface(s, "floor"))?,
            );
            z.ceiling.push(
                zone.ceiling
                    .as_ref()
                    .map_or(Ok(ceiling_default), |s| self.surface(s, "ceiling"))?,
            );
        }
        Ok(z)
    }

    /// The map's sprites: legacy `2` cells (with the `S` texture, loaded only when one is
    /// there), then the `SPRITE` lines.
    pub(super) fn sprites(&mut self, map: &Map) -> Result<Vec<Sprite>, TextureError> {
        let mut sprites = Vec::new();
        if !map.sprites.is_empty() {
            let sheet = match &map.sprite_texture {
                Some(r) => self.sheet(r, ColourKey::Auto, LEGACY_SPRITE_FALLBACK)?,
                None => self.builtin_sheet(LEGACY_SPRITE_FALLBACK),
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
            let sheet = self.sheet(&def.texture, def.key, LEGACY_SPRITE_FALLBACK)?;
            sprites.push(Sprite {
                def: def.clone(),
                sheet,
            });
        }
        Ok(sprites)
    }

    /// Each item's sheet, a key's tinted in the key's colour.
    pub(super) fn item_sheets(&mut self, map: &Map) -> Result<Vec<usize>, TextureError> {
        let mut item_sheets = Vec::with_capacity(map.items.len());
        for item in &map.items {
            let sheet = self.sheet(&item.texture, ColourKey::Auto, LEGACY_SPRITE_FALLBACK)?;
            item_sheets.push(match &item.key {
                Some(key) => self.tinted_sheet(sheet, key_colour(key)),
                None => sheet,
            });
        }
        Ok(item_sheets)
    }

    fn push(&mut self, t: Texture) -> usize {
        intern(&mut self.textures, t)
    }

    pub(super) fn builtin(&mut self, stem: &str) -> usize {
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
    pub(super) fn tinted_texture(&mut self, k: usize, tint: Rgb) -> usize {
        let s = &self.textures[k];
        let t = Texture::from_fn(s.width(), s.height(), |x, y| tinted(s.texel(x, y), tint));
        self.push(t)
    }

    pub(super) fn builtin_sheet(&mut self, stem: &str) -> usize {
        let t = builtin::sheet_by_name(stem).expect("fallback sprite stems are embedded");
        self.push_sheet(t)
    }

    pub(super) fn sheet(
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

    pub(super) fn load(&mut self, r: &TextureRef, fallback: &str) -> Result<usize, TextureError> {
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

/// The name an embedded image goes by for a map's `path` to it: the file's stem
/// (`textures/brick.png` is `brick`).
fn embedded_name(path: &str) -> &str {
    Path::new(path)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or_default()
}

fn read_texture(source: &TextureSource, path: &str, budget: &mut usize) -> Result<Texture, String> {
    match source {
        TextureSource::Embedded => builtin::by_name(embedded_name(path))
            .ok_or_else(|| "no embedded texture of that name".to_owned()),
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
        TextureSource::Embedded => builtin::sheet_by_name(embedded_name(path))
            .ok_or_else(|| "no embedded sprite of that name".to_owned()),
        TextureSource::Dir(dir) => {
            read_budgeted(&dir.join(path), budget, |b| SpriteSheet::decode(b, key))
        }
    }
}
