//! halfcast's `SPRITE` header line: a billboard with sub-cell position and drawing options.
//!
//! ```text
//! SPRITE x,y texture [scale=S|W,H] [offset=Z|hang] [solid[=R]] [blend=normal|average|additive]
//!        [views=1|8] [facing=DEG] [frames=N] [fps=F] [key=r,g,b|none]
//! ```

use super::words::words;
use super::{MapErrorKind, TextureRef};
use crate::color::Rgb;
use crate::vec2::Vec2;

/// How a sprite's opaque texels combine with what is already drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Blend {
    /// Replace (partially transparent texels mix by their alpha).
    #[default]
    Normal,
    /// Half sprite, half background (Lode's translucency).
    Average,
    /// Background plus sprite, saturating: glows, flames, ghosts.
    Additive,
}

/// Which texels are see-through.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum ColourKey {
    /// The image's alpha channel; an image without one uses black as the key (Lode's rule).
    #[default]
    Auto,
    /// Nothing is transparent except by alpha.
    None,
    /// Texels of exactly this colour are transparent.
    Colour(Rgb),
}

/// One sprite as the map describes it (textures not loaded yet).
#[derive(Debug, Clone, PartialEq)]
pub struct SpriteDef {
    /// Centre on the map plane, in cells (sub-cell precision).
    pub pos: Vec2,
    /// The sprite sheet image (one picture, or views × frames).
    pub texture: TextureRef,
    /// Width and height in cells (Lode's 1/uDiv and 1/vDiv).
    pub scale: (f64, f64),
    /// Height of the sprite's bottom above the floor, in wall heights (Lode's vMove).
    pub offset: f64,
    /// Given as `hang`: its top is at its cell's ceiling (`offset` is then 1 − height, right for
    /// a flat cell; on `Hz` maps the renderer hangs it from the cell's own ceiling).
    pub hang: bool,
    /// Radius of the disc that blocks movement, when solid.
    pub solid: Option<f64>,
    /// How it mixes with what is behind it.
    pub blend: Blend,
    /// 1, or 8 direction-dependent views laid out left to right in the texture.
    pub views: u8,
    /// The way the sprite faces, in CLI degrees (0 = east, 90 = north); used by 8-view sprites.
    pub facing_deg: f64,
    /// Animation frames laid out top to bottom in the texture.
    pub frames: u16,
    /// Animation speed in frames per second.
    pub fps: f64,
    /// Which texels are transparent.
    pub key: ColourKey,
    /// Where the line was written (1-based line, column), for messages.
    pub at: (usize, usize),
}

/// Radius a legacy `2` sprite or a bare `solid` blocks with, in cells.
pub const DEFAULT_SOLID_RADIUS: f64 = 0.3;

impl SpriteDef {
    /// A full-size, floor-standing, solid sprite: what a cub3D `2` cell means.
    #[must_use]
    pub fn legacy(pos: Vec2, texture: TextureRef) -> Self {
        let at = (texture.line, texture.col);
        Self {
            pos,
            texture,
            scale: (1.0, 1.0),
            offset: 0.0,
            hang: false,
            solid: Some(DEFAULT_SOLID_RADIUS),
            blend: Blend::Normal,
            views: 1,
            facing_deg: 0.0,
            frames: 1,
            fps: 0.0,
            key: ColourKey::Auto,
            at,
        }
    }
}

fn bad(why: impl Into<String>) -> MapErrorKind {
    MapErrorKind::BadValue {
        id: "SPRITE".to_owned(),
        why: why.into(),
    }
}

fn number(key: &str, s: &str) -> Result<f64, MapErrorKind> {
    s.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| bad(format!("{key} needs a number, got '{s}'")))
}

fn positive(key: &str, s: &str) -> Result<f64, MapErrorKind> {
    let v = number(key, s)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(bad(format!("{key} must be greater than 0, got '{s}'")))
    }
}

/// Parses the words after `SPRITE`; `line` and `path_col` place the texture path for messages.
pub(super) fn parse_sprite(
    rest: &str,
    line: usize,
    word_col: usize,
    rest_col: usize,
) -> Result<SpriteDef, MapErrorKind> {
    let words = words(rest, rest_col);
    let [(pos, _), (path, path_col), options @ ..] = &words[..] else {
        return Err(bad("write 'SPRITE x,y texture [options]'"));
    };
    let (x, y) = pos
        .split_once(',')
        .ok_or_else(|| bad(format!("position must be x,y, got '{pos}'")))?;
    let pos = Vec2::new(number("x", x)?, number("y", y)?);
    let mut def = SpriteDef::legacy(
        pos,
        TextureRef {
            path: path.clone(),
            line,
            col: *path_col,
        },
    );
    def.solid = None;
    def.at = (line, word_col);
    let mut height = Height::default();
    for (word, _) in options {
        let (key, value) = match word.split_once('=') {
            Some((k, v)) => (k, Some(v)),
            None => (word.as_str(), None),
        };
        option(&mut def, &mut height, word, key, value)?;
    }
    if height.hang {
        if height.offset_given {
            return Err(bad("give either offset=... or hang, not both"));
        }
        def.offset = 1.0 - def.scale.1;
        def.hang = true;
    }
    Ok(def)
}

/// Where the line puts the sprite's foot: `offset=` and `hang` exclude each other, and `hang`
/// needs the height `scale=` gives, wherever it is written.
#[derive(Default)]
struct Height {
    hang: bool,
    offset_given: bool,
}

/// Reads one option `word` (`key`, with its `value` after `=` if any) into `def`.
fn option(
    def: &mut SpriteDef,
    height: &mut Height,
    word: &str,
    key: &str,
    value: Option<&str>,
) -> Result<(), MapErrorKind> {
    let need = || value.ok_or_else(|| bad(format!("{key} needs a value ({key}=...)")));
    match key {
        "scale" => {
            let v = need()?;
            def.scale = match v.split_once(',') {
                Some((w, h)) => (positive("scale", w)?, positive("scale", h)?),
                None => {
                    let s = positive("scale", v)?;
                    (s, s)
                }
            };
        }
        "offset" => {
            def.offset = number("offset", need()?)?;
            height.offset_given = true;
        }
        "hang" if value.is_none() => height.hang = true,
        "solid" => {
            def.solid = Some(match value {
                Some(v) => positive("solid", v)?,
                None => DEFAULT_SOLID_RADIUS,
            });
        }
        "blend" => {
            def.blend = match need()? {
                "normal" => Blend::Normal,
                "average" => Blend::Average,
                "additive" => Blend::Additive,
                other => {
                    return Err(bad(format!(
                        "blend must be normal, average or additive, got '{other}'"
                    )))
                }
            };
        }
        "views" => {
            def.views = match need()? {
                "1" => 1,
                "8" => 8,
                other => return Err(bad(format!("views must be 1 or 8, got '{other}'"))),
            };
        }
        "facing" => def.facing_deg = number("facing", need()?)?,
        "frames" => {
            let v = need()?;
            def.frames =
                v.parse::<u16>().ok().filter(|&n| n >= 1).ok_or_else(|| {
                    bad(format!("frames must be a whole number 1-65535, got '{v}'"))
                })?;
        }
        "fps" => {
            let v = need()?;
            let f = number("fps", v)?;
            if f < 0.0 {
                return Err(bad(format!("fps must not be negative, got '{v}'")));
            }
            def.fps = f;
        }
        "key" => def.key = colour_key(need()?)?,
        _ => return Err(bad(format!("unknown option '{word}'"))),
    }
    Ok(())
}

/// The `key=` option: `none`, or the `r,g,b` colour that is transparent.
fn colour_key(v: &str) -> Result<ColourKey, MapErrorKind> {
    if v == "none" {
        return Ok(ColourKey::None);
    }
    let parts: Vec<Option<u8>> = v.split(',').map(|p| p.trim().parse::<u8>().ok()).collect();
    match parts[..] {
        [Some(r), Some(g), Some(b)] => Ok(ColourKey::Colour(Rgb::new(r, g, b))),
        _ => Err(bad(format!("key must be r,g,b or none, got '{v}'"))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minimal_line_is_a_full_size_non_solid_billboard() {
        let d = parse_sprite(" 2.5,3.25 tex/barrel.png", 7, 1, 7).unwrap();
        assert_eq!(d.pos, Vec2::new(2.5, 3.25));
        assert_eq!(d.texture.path, "tex/barrel.png");
        assert_eq!((d.texture.line, d.texture.col), (7, 17));
        assert_eq!((d.scale, d.offset, d.solid), ((1.0, 1.0), 0.0, None));
        assert_eq!((d.views, d.frames, d.blend), (1, 1, Blend::Normal));
    }

    #[test]
    fn every_option() {
        let d = parse_sprite(
            " 1,2 t.png scale=0.5,0.25 hang solid=0.4 blend=additive views=8 facing=90 frames=4 fps=6 key=255,0,255",
            1,
            1,
            7,
        )
        .unwrap();
        assert_eq!(d.scale, (0.5, 0.25));
        assert_eq!(d.offset, 0.75);
        assert_eq!(d.solid, Some(0.4));
        assert_eq!(d.blend, Blend::Additive);
        assert_eq!((d.views, d.facing_deg, d.frames, d.fps), (8, 90.0, 4, 6.0));
        assert_eq!(d.key, ColourKey::Colour(Rgb::new(255, 0, 255)));
        let d = parse_sprite(" 1,2 t.png solid offset=-0.1 key=none", 1, 1, 7).unwrap();
        assert_eq!(
            (d.solid, d.offset, d.key),
            (Some(0.3), -0.1, ColourKey::None)
        );
    }

    #[test]
    fn bad_options_say_what_is_wrong() {
        let msg = |s: &str| parse_sprite(s, 1, 1, 7).unwrap_err().to_string();
        assert_eq!(
            msg(" 1,2"),
            "bad value for SPRITE: write 'SPRITE x,y texture [options]'"
        );
        assert_eq!(
            msg(" 1;2 t"),
            "bad value for SPRITE: position must be x,y, got '1;2'"
        );
        assert_eq!(
            msg(" 1,2 t views=4"),
            "bad value for SPRITE: views must be 1 or 8, got '4'"
        );
        assert_eq!(
            msg(" 1,2 t scale=0"),
            "bad value for SPRITE: scale must be greater than 0, got '0'"
        );
        assert_eq!(
            msg(" 1,2 t glow"),
            "bad value for SPRITE: unknown option 'glow'"
        );
        assert_eq!(
            msg(" 1,2 t blend=xor"),
            "bad value for SPRITE: blend must be normal, average or additive, got 'xor'"
        );
        assert_eq!(
            msg(" 1,2 t offset=0.2 hang"),
            "bad value for SPRITE: give either offset=... or hang, not both"
        );
        assert_eq!(
            msg(" 1,2 t frames=0"),
            "bad value for SPRITE: frames must be a whole number 1-65535, got '0'"
        );
        assert_eq!(
            msg(" 1,nan t"),
            "bad value for SPRITE: y needs a number, got 'nan'"
        );
    }
}
