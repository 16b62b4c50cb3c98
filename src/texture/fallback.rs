//! Which built-in stands in for an image file that cannot be loaded: the one the file is named
//! after (`stone.png` → the built-in stone, `treasure.png` → the treasure sprite), and only when
//! no built-in has its name, the one for its slot (the north wall's, an item's). The warning
//! says which, and why.

use std::path::Path;

use super::builtin::{EMBEDDED, EMBEDDED_SPRITES};

/// What kind of image a map line names: a wall, floor or ceiling texture, or a sprite sheet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageKind {
    /// A wall, door, floor or ceiling texture (the built-ins of `textures/`).
    Texture,
    /// A sprite, item or creature sheet (the built-ins of `textures/sprites/`).
    Sprite,
}

impl ImageKind {
    /// The word the warnings use.
    #[must_use]
    pub fn word(self) -> &'static str {
        match self {
            Self::Texture => "texture",
            Self::Sprite => "sprite",
        }
    }

    fn builtin_names(self) -> impl Iterator<Item = &'static str> {
        let names: &'static [(&'static str, &'static [u8])] = match self {
            Self::Texture => &EMBEDDED,
            Self::Sprite => &EMBEDDED_SPRITES,
        };
        names.iter().map(|(name, _)| *name)
    }
}

/// The built-in chosen for a file that could not be loaded.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Fallback<'s> {
    /// The built-in's stem (`stone`, `barrel`).
    pub stem: &'s str,
    /// Whether the file's name chose it (else its slot did).
    pub by_name: bool,
    kind: ImageKind,
}

impl<'s> Fallback<'s> {
    /// The stand-in for `path`: the built-in `kind` whose name is the file's stem (compared
    /// without regard to case), else `slot` (the slot's own stand-in, which must be built in).
    #[must_use]
    pub fn for_file(path: &str, kind: ImageKind, slot: &'s str) -> Self {
        let file_stem = Path::new(path)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or_default();
        let named = kind
            .builtin_names()
            .find(|name| name.eq_ignore_ascii_case(file_stem));
        Self {
            stem: named.unwrap_or(slot),
            by_name: named.is_some(),
            kind,
        }
    }

    /// The end of the warning after the reason the file failed: `using the built-in 'stone'
    /// texture, which has its name`, or, by slot, `using the built-in 'bricks' texture` (the
    /// words the slot's stand-in always had).
    #[must_use]
    pub fn says(&self) -> String {
        let kind = self.kind.word();
        if self.by_name {
            format!(
                "using the built-in '{}' {kind}, which has its name",
                self.stem
            )
        } else {
            format!("using the built-in '{}' {kind}", self.stem)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_named_like_a_builtin_gets_that_builtin_in_any_case() {
        for (name, _) in EMBEDDED {
            let f = Fallback::for_file(
                &format!("gone/{}.PNG", name.to_uppercase()),
                ImageKind::Texture,
                "bricks",
            );
            assert_eq!((f.stem, f.by_name), (name, true));
        }
        for (name, _) in EMBEDDED_SPRITES {
            let f = Fallback::for_file(&format!("./{name}.png"), ImageKind::Sprite, "barrel");
            assert_eq!((f.stem, f.by_name), (name, true));
        }
    }

    #[test]
    fn other_names_and_other_kinds_fall_back_by_slot() {
        let f = Fallback::for_file("./north.png", ImageKind::Texture, "wood");
        assert_eq!((f.stem, f.by_name), ("wood", false));
        assert_eq!(f.says(), "using the built-in 'wood' texture");
        // A sprite's name does not pick a wall texture, nor a texture's a sprite.
        let f = Fallback::for_file("treasure.png", ImageKind::Texture, "metal");
        assert_eq!((f.stem, f.by_name), ("metal", false));
        let f = Fallback::for_file("stone.png", ImageKind::Sprite, "barrel");
        assert_eq!((f.stem, f.by_name), ("barrel", false));
        let f = Fallback::for_file("lamp.png", ImageKind::Sprite, "barrel");
        assert_eq!(
            f.says(),
            "using the built-in 'lamp' sprite, which has its name"
        );
    }
}
