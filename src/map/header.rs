//! A `.cub` file's header: its identifiers (wall faces, colours, zones, sprites, lights, fog, the
//! game lines), each read and checked on its own line, before the grid.

use std::collections::HashMap;

use super::game_objects::{GameLine, GameLines};
use super::lamp::parse_light;
use super::sprite::parse_sprite;
use super::words::words;
use super::{LightDef, MapErrorKind, Span, SpriteDef, Surface, TextureRef, Zone};
use crate::color::Rgb;
use crate::map::Fog;

/// Most `LIGHT` lines: each is baked over up to 128×128 samples, one ray cast per sample, so
/// the count multiplies load time (10 000 lights took over a minute).
pub const MAX_LIGHTS: usize = 256;

/// Most sprites, `SPRITE` lines and legacy `2` cells together: every frame sorts and draws them.
pub const MAX_SPRITES: usize = 4096;

/// Header keys that must appear, in the order a missing one is reported.
const REQUIRED: [(&str, &str); 6] = [
    ("NO", "north wall texture"),
    ("SO", "south wall texture"),
    ("WE", "west wall texture"),
    ("EA", "east wall texture"),
    ("F", "floor colour"),
    ("C", "ceiling colour"),
];

/// A blank between words: a space or a tab.
pub(super) fn is_blank_char(c: char) -> bool {
    c == ' ' || c == '\t'
}

/// The header identifiers seen so far, each with the line that gave it.
#[derive(Default)]
pub(super) struct Header {
    seen: HashMap<String, usize>,
    pub(super) faces: [Option<TextureRef>; 4],
    pub(super) wall_types: [Option<TextureRef>; 10],
    pub(super) floor: Option<Surface>,
    pub(super) ceiling: Option<Surface>,
    pub(super) floor_texture: Option<TextureRef>,
    pub(super) ceiling_texture: Option<TextureRef>,
    pub(super) zones: Vec<Zone>,
    pub(super) sprite_texture: Option<TextureRef>,
    pub(super) resolution: Option<(u32, u32)>,
    pub(super) sprite_defs: Vec<SpriteDef>,
    pub(super) lights: Vec<LightDef>,
    pub(super) door_texture: Option<TextureRef>,
    pub(super) fog: Option<Fog>,
    pub(super) shade: Option<f64>,
    pub(super) game: GameLines,
}

/// An error at a 1-based (line, column).
type LineError = ((usize, usize), MapErrorKind);

impl Header {
    fn has(&self, id: &str) -> bool {
        self.seen.contains_key(id)
    }

    /// Whether every required identifier was given (`FT` and `CT` stand in for `F` and `C`).
    pub(super) fn check_complete(&self) -> Result<(), MapErrorKind> {
        for (id, what) in REQUIRED {
            let satisfied =
                self.has(id) || (id == "F" && self.has("FT")) || (id == "C" && self.has("CT"));
            if !satisfied {
                return Err(MapErrorKind::Missing(id, what));
            }
        }
        Ok(())
    }

    /// Reads one header line: its identifier, then what that identifier takes.
    pub(super) fn line(&mut self, line_no: usize, line: &str) -> Result<(), LineError> {
        let start = line.find(|c: char| !is_blank_char(c)).unwrap_or(0);
        let word_col = line[..start].chars().count() + 1;
        let rest_at = line[start..]
            .find(is_blank_char)
            .map_or(line.len(), |p| start + p);
        let word = &line[start..rest_at];
        let rest = &line[rest_at..];
        let rest_col = line[..rest_at].chars().count() + 1;
        let at = (line_no, word_col);
        let kind = classify(word).ok_or_else(|| {
            let mut chars = word.chars();
            match (chars.next(), chars.next()) {
                (Some(c @ ('F' | 'C')), Some(d)) if d.is_ascii_digit() || d == ',' => {
                    (at, MapErrorKind::NoSpaceAfter(c.to_string()))
                }
                _ => (at, MapErrorKind::UnknownIdentifier(word.to_owned())),
            }
        })?;
        if let Ident::Game(line) = kind {
            return self.game.line(line, rest, line_no, word_col, rest_col);
        }
        if let Ident::Light = kind {
            if self.lights.len() >= MAX_LIGHTS {
                let what = "LIGHT lines";
                return Err((
                    at,
                    MapErrorKind::TooMany {
                        what,
                        limit: MAX_LIGHTS,
                    },
                ));
            }
            let def = parse_light(rest, at).map_err(|k| (at, k))?;
            self.lights.push(def);
            return Ok(());
        }
        if let Ident::SpriteEntry = kind {
            if self.sprite_defs.len() >= MAX_SPRITES {
                return Err((at, too_many_sprites()));
            }
            let def = parse_sprite(rest, line_no, word_col, rest_col).map_err(|k| (at, k))?;
            self.sprite_defs.push(def);
            return Ok(());
        }
        if let Some(&first_line) = self.seen.get(word) {
            return Err((
                at,
                MapErrorKind::Duplicate {
                    id: word.to_owned(),
                    first_line,
                },
            ));
        }
        self.seen.insert(word.to_owned(), line_no);
        let value = Value {
            word,
            rest,
            line_no,
            rest_col,
            at,
        };
        self.set(kind, &value)
    }

    /// Sets what identifier `kind` (given once) says.
    fn set(&mut self, kind: Ident, v: &Value) -> Result<(), LineError> {
        let Value {
            word,
            rest,
            line_no,
            rest_col,
            at,
        } = *v;
        match kind {
            Ident::Face(i) => self.faces[i] = Some(one_path(word, rest, line_no, rest_col, at)?),
            Ident::WallType(d) => {
                self.wall_types[d] = Some(one_path(word, rest, line_no, rest_col, at)?)
            }
            Ident::Sprite => {
                self.sprite_texture = Some(one_path(word, rest, line_no, rest_col, at)?)
            }
            Ident::FloorTexture => {
                self.floor_texture = Some(one_path(word, rest, line_no, rest_col, at)?)
            }
            Ident::CeilingTexture => {
                self.ceiling_texture = Some(one_path(word, rest, line_no, rest_col, at)?);
            }
            Ident::Floor | Ident::Ceiling => {
                if rest.trim_matches(is_blank_char).is_empty() {
                    return Err((at, MapErrorKind::NoSpaceAfter(word.to_owned())));
                }
                let c = Surface::Colour(colour(word, rest).map_err(|k| (at, k))?);
                if matches!(kind, Ident::Floor) {
                    self.floor = Some(c);
                } else {
                    self.ceiling = Some(c);
                }
            }
            Ident::Zone { part, zone } => {
                if self.zones.len() <= zone {
                    self.zones.resize(zone + 1, Zone::default());
                }
                if let ZonePart::Heights = part {
                    let span = heights(word, rest, line_no, rest_col, at)?;
                    self.zones[zone].heights = Some(span);
                    return Ok(());
                }
                let value = rest.trim_matches(is_blank_char);
                let surface = if value.contains(',') {
                    Surface::Colour(colour(word, rest).map_err(|k| (at, k))?)
                } else {
                    Surface::Texture(one_path(word, rest, line_no, rest_col, at)?)
                };
                let z = &mut self.zones[zone];
                match part {
                    ZonePart::Floor => z.floor = Some(surface),
                    ZonePart::Ceiling => z.ceiling = Some(surface),
                    ZonePart::Wall => z.wall = Some(surface),
                    ZonePart::Heights => unreachable!("returned above"),
                }
            }
            Ident::DoorTexture => {
                self.door_texture = Some(one_path(word, rest, line_no, rest_col, at)?);
            }
            Ident::Fog => self.fog = Some(fog(rest).map_err(|k| (at, k))?),
            Ident::Shade => {
                let v = rest.trim_matches(is_blank_char);
                let k = v.parse::<f64>().ok().filter(|k| k.is_finite() && *k >= 0.0);
                let why = format!("expected a falloff number >= 0, got '{v}'");
                self.shade = Some(k.ok_or((
                    at,
                    MapErrorKind::BadValue {
                        id: "SHADE".to_owned(),
                        why,
                    },
                ))?);
            }
            Ident::SpriteEntry | Ident::Light | Ident::Game(_) => {
                unreachable!("handled before the duplicate check")
            }
            Ident::Resolution => {
                let nums: Vec<u32> = rest
                    .split_whitespace()
                    .filter_map(|w| w.parse().ok())
                    .collect();
                if let [w, h] = nums[..] {
                    self.resolution = Some((w, h));
                }
            }
        }
        Ok(())
    }
}

/// An identifier's line: the identifier, the rest of the line and where they are.
#[derive(Clone, Copy)]
struct Value<'a> {
    word: &'a str,
    rest: &'a str,
    line_no: usize,
    rest_col: usize,
    at: (usize, usize),
}

/// What a header identifier sets.
#[derive(Clone, Copy)]
enum Ident {
    Face(usize),
    WallType(usize),
    Sprite,
    Floor,
    Ceiling,
    FloorTexture,
    CeilingTexture,
    Zone { part: ZonePart, zone: usize },
    Resolution,
    SpriteEntry,
    DoorTexture,
    Fog,
    Shade,
    Light,
    Game(GameLine),
}

/// Which line of a zone letter: `Fz`, `Cz`, `Hz` or `Wz`.
#[derive(Clone, Copy)]
enum ZonePart {
    Floor,
    Ceiling,
    Heights,
    Wall,
}

fn classify(word: &str) -> Option<Ident> {
    Some(match word {
        "NO" => Ident::Face(0),
        "SO" => Ident::Face(1),
        "WE" => Ident::Face(2),
        "EA" => Ident::Face(3),
        "S" => Ident::Sprite,
        "F" => Ident::Floor,
        "C" => Ident::Ceiling,
        "FT" => Ident::FloorTexture,
        "CT" => Ident::CeilingTexture,
        "R" => Ident::Resolution,
        "SPRITE" => Ident::SpriteEntry,
        "TD" => Ident::DoorTexture,
        "FOG" => Ident::Fog,
        "SHADE" => Ident::Shade,
        "LIGHT" => Ident::Light,
        _ if GameLine::classify(word).is_some() => Ident::Game(GameLine::classify(word)?),
        _ => {
            let b = word.as_bytes();
            match b {
                [b'T', d @ b'1'..=b'9'] => Ident::WallType(usize::from(d - b'0')),
                [p @ (b'F' | b'C' | b'H' | b'W'), z @ b'a'..=b'z'] => Ident::Zone {
                    part: match p {
                        b'F' => ZonePart::Floor,
                        b'C' => ZonePart::Ceiling,
                        b'H' => ZonePart::Heights,
                        _ => ZonePart::Wall,
                    },
                    zone: usize::from(z - b'a'),
                },
                _ => return None,
            }
        }
    })
}

fn one_path(
    id: &str,
    rest: &str,
    line: usize,
    rest_col: usize,
    at: (usize, usize),
) -> Result<TextureRef, LineError> {
    let mut words = rest.split(is_blank_char).filter(|w| !w.is_empty());
    match (words.next(), words.next()) {
        (Some(path), None) => {
            let lead = rest.chars().take_while(|&c| is_blank_char(c)).count();
            Ok(TextureRef {
                path: path.to_owned(),
                line,
                col: rest_col + lead,
            })
        }
        _ => Err((at, MapErrorKind::NeedsOnePath(id.to_owned()))),
    }
}

/// Parses `r,g,b` (integers 0–255; blanks around numbers tolerated).
fn colour(id: &str, rest: &str) -> Result<Rgb, MapErrorKind> {
    let bad = || MapErrorKind::BadColour {
        id: id.to_owned(),
        got: rest.trim_matches(is_blank_char).to_owned(),
    };
    let parts: Vec<&str> = rest
        .split(',')
        .map(|p| p.trim_matches(is_blank_char))
        .collect();
    let [r, g, b] = parts[..] else {
        return Err(bad());
    };
    let channel = |s: &str| -> Option<u8> {
        if s.is_empty() || s.len() > 3 || !s.bytes().all(|c| c.is_ascii_digit()) {
            return None;
        }
        s.parse::<u16>().ok().and_then(|v| u8::try_from(v).ok())
    };
    match (channel(r), channel(g), channel(b)) {
        (Some(r), Some(g), Some(b)) => Ok(Rgb::new(r, g, b)),
        _ => Err(bad()),
    }
}

/// Parses `FLOOR CEIL` of an `Hz` line: two numbers with MIN_FLOOR <= FLOOR < CEIL <= MAX_CEIL;
/// a bad one is reported at its own column.
fn heights(
    id: &str,
    rest: &str,
    line: usize,
    rest_col: usize,
    at: (usize, usize),
) -> Result<Span, LineError> {
    let bad = |col: usize, why: String| {
        (
            (line, col),
            MapErrorKind::BadValue {
                id: id.to_owned(),
                why,
            },
        )
    };
    let words = words(rest, rest_col);
    let [(f, fcol), (c, ccol)] = &words[..] else {
        let got = rest.trim_matches(is_blank_char);
        return Err(bad(
            if words.len() > 2 { words[2].1 } else { at.1 },
            format!("expected 'FLOOR CEIL' (two heights in wall units), got '{got}'"),
        ));
    };
    let number = |col: usize, w: &str, what: &str| -> Result<f64, LineError> {
        w.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| bad(col, format!("{what} height '{w}' is not a number")))
    };
    let floor = number(*fcol, f, "floor")?;
    let ceil = number(*ccol, c, "ceiling")?;
    if floor < Span::MIN_FLOOR {
        return Err(bad(
            *fcol,
            format!("floor height {f} is below {}", Span::MIN_FLOOR),
        ));
    }
    if ceil > Span::MAX_CEIL {
        return Err(bad(
            *ccol,
            format!("ceiling height {c} is above {}", Span::MAX_CEIL),
        ));
    }
    if floor >= ceil {
        return Err(bad(
            *ccol,
            format!("ceiling height {c} must be above the floor height {f}"),
        ));
    }
    Ok(Span { floor, ceil })
}

/// Parses `r,g,b density` (density a number >= 0, fraction left per cell is e^-density).
fn fog(rest: &str) -> Result<Fog, MapErrorKind> {
    let v = rest.trim_matches(is_blank_char);
    let bad = || MapErrorKind::BadValue {
        id: "FOG".to_owned(),
        why: format!("expected 'r,g,b density', got '{v}'"),
    };
    let (rgb, density) = v.rsplit_once(is_blank_char).ok_or_else(bad)?;
    let colour = colour("FOG", rgb)?;
    let density = density
        .parse::<f64>()
        .ok()
        .filter(|d| d.is_finite() && *d >= 0.0)
        .ok_or_else(bad)?;
    Ok(Fog { colour, density })
}

/// The error for one sprite too many.
pub(super) fn too_many_sprites() -> MapErrorKind {
    MapErrorKind::TooMany {
        what: "sprites (SPRITE lines and '2' cells)",
        limit: MAX_SPRITES,
    }
}
