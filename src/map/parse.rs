//! The `.cub` reader: header identifiers, then a closed grid with one player.

use std::collections::HashMap;

use super::game_objects::{GameLine, GameLines};
use super::lamp::parse_light;
use super::sprite::parse_sprite;
use super::{
    Cell, DoorPlane, LightDef, Map, MapError, MapErrorKind, Span, SpriteDef, Start, Surface,
    TextureRef, Zone,
};
use crate::color::Rgb;
use crate::map::Fog;
use crate::vec2::Vec2;

/// More cells than this is refused instead of allocating without bound.
pub const MAX_CELLS: usize = 1 << 24;

/// Most `LIGHT` lines: each is baked over up to 128×128 samples, one ray cast per sample, so
/// the count multiplies load time (10 000 lights took over a minute).
pub const MAX_LIGHTS: usize = 256;

/// Largest map (in cells) that may have lights: the light map holds 16 samples per cell.
pub const MAX_LIT_CELLS: usize = 1 << 20;

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

fn is_blank_char(c: char) -> bool {
    c == ' ' || c == '\t'
}

/// Whether a header-section line is the first line of the grid: it starts with a digit after
/// any blanks (a closed map's first row holds only walls and void, so "WE" or "N" never is).
fn starts_grid(line: &str) -> bool {
    line.chars()
        .find(|&c| !is_blank_char(c))
        .is_some_and(|c| c.is_ascii_digit())
}

/// Parses `bytes` read from `file` (the name used in messages) into a [`Map`].
///
/// # Errors
/// Any broken rule, as a [`MapError`] naming the file and, where there is one, line:col.
pub fn parse_map(file: &str, bytes: &[u8]) -> Result<Map, MapError> {
    let err = |at: Option<(usize, usize)>, kind| MapError {
        file: file.to_owned(),
        at,
        kind,
    };
    let text = match std::str::from_utf8(bytes) {
        Ok(t) => t,
        Err(e) => {
            let before = &bytes[..e.valid_up_to()];
            let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
            let line_start = before
                .iter()
                .rposition(|&b| b == b'\n')
                .map_or(0, |p| p + 1);
            let col = String::from_utf8_lossy(&before[line_start..])
                .chars()
                .count()
                + 1;
            return Err(err(Some((line, col)), MapErrorKind::NotUtf8));
        }
    };
    let mut header = Header::default();
    let mut grid: Vec<(usize, &str)> = Vec::new();
    let mut blank_after_grid = None;
    for (idx, raw) in text.split('\n').enumerate() {
        let line_no = idx + 1;
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        let blank = line.chars().all(is_blank_char);
        if grid.is_empty() {
            if blank {
                continue;
            }
            if starts_grid(line) {
                header.check_complete().map_err(|k| err(None, k))?;
                grid.push((line_no, line));
            } else {
                header
                    .line(line_no, line)
                    .map_err(|(at, k)| err(Some(at), k))?;
            }
        } else if blank {
            blank_after_grid = blank_after_grid.or(Some(line_no));
        } else if let Some(blank_line) = blank_after_grid {
            let col = line.chars().take_while(|&c| is_blank_char(c)).count() + 1;
            return Err(err(
                Some((line_no, col)),
                MapErrorKind::AfterMap { blank_line },
            ));
        } else {
            grid.push((line_no, line));
        }
    }
    if grid.is_empty() {
        header.check_complete().map_err(|k| err(None, k))?;
        return Err(err(None, MapErrorKind::NoMap));
    }
    build(file, header, &grid)
}

/// The header identifiers seen so far, each with the line that gave it.
#[derive(Default)]
struct Header {
    seen: HashMap<String, usize>,
    faces: [Option<TextureRef>; 4],
    wall_types: [Option<TextureRef>; 10],
    floor: Option<Surface>,
    ceiling: Option<Surface>,
    floor_texture: Option<TextureRef>,
    ceiling_texture: Option<TextureRef>,
    zones: Vec<Zone>,
    sprite_texture: Option<TextureRef>,
    resolution: Option<(u32, u32)>,
    sprite_defs: Vec<SpriteDef>,
    lights: Vec<LightDef>,
    door_texture: Option<TextureRef>,
    fog: Option<Fog>,
    shade: Option<f64>,
    game: GameLines,
}

type LineError = ((usize, usize), MapErrorKind);

impl Header {
    fn has(&self, id: &str) -> bool {
        self.seen.contains_key(id)
    }

    fn check_complete(&self) -> Result<(), MapErrorKind> {
        for (id, what) in REQUIRED {
            let satisfied =
                self.has(id) || (id == "F" && self.has("FT")) || (id == "C" && self.has("CT"));
            if !satisfied {
                return Err(MapErrorKind::Missing(id, what));
            }
        }
        Ok(())
    }

    fn line(&mut self, line_no: usize, line: &str) -> Result<(), LineError> {
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
    // Each word with its 1-based column.
    let mut words = Vec::new();
    let mut current: Option<(usize, String)> = None;
    for (col, c) in (rest_col..).zip(rest.chars()) {
        if is_blank_char(c) {
            words.extend(current.take());
        } else {
            current
                .get_or_insert_with(|| (col, String::new()))
                .1
                .push(c);
        }
    }
    words.extend(current);
    let [(fcol, f), (ccol, c)] = &words[..] else {
        let got = rest.trim_matches(is_blank_char);
        return Err(bad(
            if words.len() > 2 { words[2].0 } else { at.1 },
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

fn too_many_sprites() -> MapErrorKind {
    MapErrorKind::TooMany {
        what: "sprites (SPRITE lines and '2' cells)",
        limit: MAX_SPRITES,
    }
}

/// Turns the grid lines into cells, then checks players and closure.
fn build(file: &str, h: Header, grid: &[(usize, &str)]) -> Result<Map, MapError> {
    let err = |at: Option<(usize, usize)>, kind| MapError {
        file: file.to_owned(),
        at,
        kind,
    };
    let width = grid
        .iter()
        .map(|(_, l)| l.chars().count())
        .max()
        .unwrap_or(0);
    let height = grid.len();
    if width.saturating_mul(height) > MAX_CELLS {
        return Err(err(
            Some((grid[0].0, 1)),
            MapErrorKind::TooLarge(width * height, MAX_CELLS),
        ));
    }
    if let Some(first) = h.lights.first() {
        if width * height > MAX_LIT_CELLS {
            let kind = MapErrorKind::TooLargeToLight {
                cells: width * height,
                limit: MAX_LIT_CELLS,
            };
            return Err(err(Some(first.at), kind));
        }
    }
    let sprite_is_wall = h.wall_types[2].is_some();
    let mut cells = vec![Cell::Void; width * height];
    let mut start: Option<(Start, usize, usize)> = None;
    let mut sprites = Vec::new();
    for (j, &(line_no, line)) in grid.iter().enumerate() {
        for (i, ch) in line.chars().enumerate() {
            let at = Some((line_no, i + 1));
            cells[j * width + i] = match ch {
                ' ' => Cell::Void,
                '0' => Cell::Floor { zone: 0 },
                '2' if !sprite_is_wall => {
                    if sprites.len() + h.sprite_defs.len() >= MAX_SPRITES {
                        return Err(err(at, too_many_sprites()));
                    }
                    sprites.push(Vec2::new(i as f64 + 0.5, j as f64 + 0.5));
                    Cell::Floor { zone: 0 }
                }
                '1'..='9' => Cell::Wall(ch as u8 - b'0'),
                // The plane is fixed below, once the neighbours are known.
                'D' => Cell::Door(DoorPlane::X),
                'N' | 'S' | 'E' | 'W' => {
                    if let Some((_, l, c)) = start {
                        return Err(err(
                            at,
                            MapErrorKind::SecondPlayer {
                                first_line: l,
                                first_col: c,
                            },
                        ));
                    }
                    start = Some((
                        Start {
                            cell: (i, j),
                            facing: ch,
                        },
                        line_no,
                        i + 1,
                    ));
                    Cell::Floor { zone: 0 }
                }
                'a'..='z' => {
                    let z = usize::from(ch as u8 - b'a');
                    if h.zones.get(z).is_none_or(|zone| {
                        zone.floor.is_none()
                            && zone.ceiling.is_none()
                            && zone.heights.is_none()
                            && zone.wall.is_none()
                    }) {
                        return Err(err(at, MapErrorKind::UndefinedZone(ch)));
                    }
                    Cell::Floor { zone: z as u8 + 1 }
                }
                _ => return Err(err(at, MapErrorKind::BadMapChar(ch))),
            };
        }
    }
    let Some((start, _, _)) = start else {
        return Err(err(None, MapErrorKind::NoPlayer));
    };
    let at = |i: i64, j: i64| -> Cell {
        if i < 0 || j < 0 || i as usize >= width || j as usize >= height {
            Cell::Void
        } else {
            cells[j as usize * width + i as usize]
        }
    };
    for (j, &(line_no, line)) in grid.iter().enumerate() {
        for (i, ch) in line.chars().enumerate() {
            if !matches!(cells[j * width + i], Cell::Floor { .. } | Cell::Door(_)) {
                continue;
            }
            let (x, y) = (i as i64, j as i64);
            let open = [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)]
                .iter()
                .any(|&(a, b)| at(a, b) == Cell::Void);
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
                return Err(err(Some((line_no, i + 1)), kind));
            }
        }
    }
    let mut planes = Vec::new();
    for (j, &(line_no, line)) in grid.iter().enumerate() {
        for (i, ch) in line.chars().enumerate() {
            if ch != 'D' {
                continue;
            }
            let (x, y) = (i as i64, j as i64);
            let wall = |a: i64, b: i64| matches!(at(a, b), Cell::Wall(_));
            let plane = if wall(x - 1, y) && wall(x + 1, y) {
                DoorPlane::Y
            } else if wall(x, y - 1) && wall(x, y + 1) {
                DoorPlane::X
            } else {
                let kind = MapErrorKind::DoorNotFramed {
                    line: line_no,
                    col: i + 1,
                };
                return Err(err(Some((line_no, i + 1)), kind));
            };
            planes.push((j * width + i, plane));
        }
    }
    for def in &h.sprite_defs {
        let (x, y) = (def.pos.x.floor() as i64, def.pos.y.floor() as i64);
        if !matches!(at(x, y), Cell::Floor { .. }) {
            let kind = MapErrorKind::SpriteOffFloor(format!("{},{}", def.pos.x, def.pos.y));
            return Err(err(Some(def.at), kind));
        }
    }
    for def in &h.lights {
        let (x, y) = (def.pos.x.floor() as i64, def.pos.y.floor() as i64);
        if !matches!(at(x, y), Cell::Floor { .. } | Cell::Door(_)) {
            let kind = MapErrorKind::LightOffFloor(format!("{},{}", def.pos.x, def.pos.y));
            return Err(err(Some(def.at), kind));
        }
    }
    h.game
        .check(at)
        .map_err(|(place, kind)| err(Some(place), kind))?;
    for (k, plane) in planes {
        cells[k] = Cell::Door(plane);
    }
    let surface = |tex: Option<TextureRef>, colour: Option<Surface>| {
        tex.map(Surface::Texture)
            .or(colour)
            .unwrap_or(Surface::Colour(Rgb::default()))
    };
    let [no, so, we, ea] = h.faces;
    let name = std::path::Path::new(file)
        .file_name()
        .map_or_else(|| file.to_owned(), |n| n.to_string_lossy().into_owned());
    Ok(Map {
        file: file.to_owned(),
        name,
        width,
        height,
        cells,
        start,
        faces: [no, so, we, ea].map(|f| f.expect("checked by check_complete")),
        wall_types: h.wall_types,
        floor: surface(h.floor_texture, h.floor),
        ceiling: surface(h.ceiling_texture, h.ceiling),
        zones: h.zones,
        sprite_texture: h.sprite_texture,
        sprites,
        resolution: h.resolution,
        sprite_defs: h.sprite_defs,
        lights: h.lights,
        door_texture: h.door_texture,
        fog: h.fog,
        shade: h.shade,
        items: h.game.items,
        locks: h.game.locks,
        exits: h.game.exits,
        creatures: h.game.creatures,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str =
        "NO ./n.png\nSO ./s.png\nWE ./w.png\nEA ./e.png\nF 220,100,0\nC 225,30,0\n";
    const GRID: &str = "111111\n100001\n10N001\n111111\n";

    fn parse(text: &str) -> Result<Map, MapError> {
        parse_map("m.cub", text.as_bytes())
    }

    fn kind(text: &str) -> MapErrorKind {
        parse(text).unwrap_err().kind
    }

    #[test]
    fn minimal_map_loads_with_start_and_colours() {
        let m = parse(&format!("{HEADER}\n{GRID}")).unwrap();
        assert_eq!((m.width, m.height), (6, 4));
        assert_eq!(
            m.start,
            Start {
                cell: (2, 2),
                facing: 'N'
            }
        );
        assert_eq!(m.floor, Surface::Colour(Rgb::new(220, 100, 0)));
        assert_eq!(m.faces[3].path, "./e.png");
        assert_eq!((m.faces[3].line, m.faces[3].col), (4, 4));
        assert_eq!(m.cell(0, 0), Cell::Wall(1));
        assert_eq!(m.cell(2, 2), Cell::Floor { zone: 0 });
        assert_eq!(m.cell(-1, 0), Cell::Void);
    }

    #[test]
    fn header_in_any_order_with_blank_lines_and_crlf() {
        let text = "\r\nC 225,30,0\r\n\r\nEA ./e.png\r\nF 220,100,0\r\nWE ./w.png\r\n\r\nSO ./s.png\r\nNO ./n.png\r\n\r\n111111\r\n100001\r\n10N001\r\n111111\r\n\r\n";
        assert_eq!(parse(text).unwrap().width, 6);
    }

    #[test]
    fn blanks_around_colour_numbers_and_tabs_after_identifiers_are_tolerated() {
        let m = parse(&format!("NO\t./n.png\nSO ./s.png\nWE ./w.png\nEA ./e.png\nF   254, 100 ,    5\nC 225,30     ,0\n{GRID}")).unwrap();
        assert_eq!(m.floor, Surface::Colour(Rgb::new(254, 100, 5)));
        assert_eq!(m.ceiling, Surface::Colour(Rgb::new(225, 30, 0)));
    }

    #[test]
    fn bad_colours_are_refused() {
        for c in [
            "220,100",
            "220,100,0,0",
            "-1,0,0",
            "256,0,0",
            "220+,100,0",
            "a,b,c",
            "220,,0",
            "1,2,3 4",
        ] {
            let k = kind(&format!("NO n\nSO s\nWE w\nEA e\nF {c}\nC 1,2,3\n{GRID}"));
            assert!(matches!(k, MapErrorKind::BadColour { .. }), "{c}: {k:?}");
        }
    }

    #[test]
    fn legacy_resolution_sprite_texture_and_sprite_cells() {
        let m = parse(&format!(
            "R 1920 1080\nS ./sprite.xpm\n{HEADER}111111\n102001\n10N021\n111111\n"
        ))
        .unwrap();
        assert_eq!(m.resolution, Some((1920, 1080)));
        assert_eq!(m.sprite_texture.as_ref().unwrap().path, "./sprite.xpm");
        assert_eq!(m.sprites, vec![Vec2::new(2.5, 1.5), Vec2::new(4.5, 2.5)]);
        assert_eq!(m.cell(2, 1), Cell::Floor { zone: 0 });
    }

    #[test]
    fn wall_type_textures_and_t2_turns_2_into_a_wall() {
        let m = parse(&format!(
            "T3 ./wood.png\nT2 ./two.png\n{HEADER}111111\n102301\n10N001\n111111\n"
        ))
        .unwrap();
        assert_eq!(m.cell(2, 1), Cell::Wall(2));
        assert_eq!(m.cell(3, 1), Cell::Wall(3));
        assert!(m.sprites.is_empty());
        assert_eq!(m.wall_types[3].as_ref().unwrap().path, "./wood.png");
    }

    #[test]
    fn floor_and_ceiling_textures_and_zones() {
        let text = format!(
            "{HEADER}FT ./floor.png\nCa 10,20,30\nFb ./grass.png\n111111\n1ab001\n10N001\n111111\n"
        );
        let m = parse(&text).unwrap();
        assert!(matches!(m.floor, Surface::Texture(ref t) if t.path == "./floor.png"));
        assert_eq!(m.cell(1, 1), Cell::Floor { zone: 1 });
        assert_eq!(
            m.zones[0].ceiling,
            Some(Surface::Colour(Rgb::new(10, 20, 30)))
        );
        assert!(matches!(m.zones[1].floor, Some(Surface::Texture(_))));
    }

    #[test]
    fn height_zones_give_spans_and_wall_paints() {
        let text = format!(
            "{HEADER}Ha 0.25 1\nHb -1.5 2.75\nWb 1,2,3\nWc ./step.png\n1111111\n1abc101\n10N0D01\n1111111\n"
        );
        let m = parse(&text).unwrap();
        assert!(m.has_heights());
        assert_eq!(
            m.span(1, 1),
            Some(Span {
                floor: 0.25,
                ceil: 1.0
            })
        );
        assert_eq!(
            m.span(2, 1),
            Some(Span {
                floor: -1.5,
                ceil: 2.75
            })
        );
        // A zone with only Wz keeps the flat span, as do plain floors, the start and doors.
        assert_eq!(m.span(3, 1), Some(Span::FLAT));
        assert_eq!(m.span(1, 2), Some(Span::FLAT));
        assert_eq!(m.span(4, 2), Some(Span::FLAT));
        assert_eq!(m.span(0, 0), None, "walls are solid at every height");
        assert_eq!(m.span(-3, 9), None, "so is the void");
        assert_eq!(m.zones[1].wall, Some(Surface::Colour(Rgb::new(1, 2, 3))));
        assert!(matches!(m.zones[2].wall, Some(Surface::Texture(ref t)) if t.path == "./step.png"));
        assert!(!parse(&format!("{HEADER}{GRID}")).unwrap().has_heights());
    }

    #[test]
    fn heights_at_the_limits_are_accepted() {
        let m = parse(&format!("{HEADER}Ha -4 8\n111\n1a1\n1N1\n111\n")).unwrap();
        assert_eq!(
            m.span(1, 1),
            Some(Span {
                floor: -4.0,
                ceil: 8.0
            })
        );
        assert!(parse(&format!("{HEADER}Ha 0 8.01\n111\n1a1\n1N1\n111\n")).is_err());
        assert!(parse(&format!("{HEADER}Ha 1e400 2\n111\n1a1\n1N1\n111\n")).is_err());
        assert!(parse(&format!("{HEADER}Ha nan 2\n111\n1a1\n1N1\n111\n")).is_err());
        assert!(parse(&format!("{HEADER}Ha 0 1 2\n111\n1a1\n1N1\n111\n")).is_err());
    }

    #[test]
    fn floor_texture_alone_satisfies_f() {
        let text = "NO n\nSO s\nWE w\nEA e\nFT f.png\nCT c.png\n111\n1N1\n111\n";
        assert!(parse(text).is_ok());
    }

    #[test]
    fn diagonal_only_openings_are_closed_enough() {
        // The 0 at (1,1) touches void only diagonally.
        let m = parse(&format!("{HEADER} 1111\n1001\n1N11\n111\n"));
        assert!(m.is_ok(), "{m:?}");
    }

    #[test]
    fn player_on_the_grid_edge_is_not_closed() {
        let e = parse(&format!("{HEADER}1111\nN001\n1111\n")).unwrap_err();
        assert_eq!(
            e.kind,
            MapErrorKind::NotClosed {
                what: "player",
                line: 8,
                col: 1
            }
        );
        assert_eq!(
            e.to_string(),
            "m.cub:8:1: map is not closed: player cell at 8:1 touches void"
        );
    }

    #[test]
    fn short_rows_are_padded_with_void() {
        let e = parse(&format!("{HEADER}11111\n1N001\n100\n11111\n")).unwrap_err();
        assert!(
            matches!(
                e.kind,
                MapErrorKind::NotClosed {
                    line: 8,
                    col: 4,
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn missing_identifiers_are_reported_in_order() {
        assert_eq!(
            kind(GRID),
            MapErrorKind::Missing("NO", "north wall texture")
        );
        assert_eq!(kind(""), MapErrorKind::Missing("NO", "north wall texture"));
        assert_eq!(
            kind(&format!("NO n\nSO s\nEA e\nC 1,1,1\n{GRID}")),
            MapErrorKind::Missing("WE", "west wall texture")
        );
    }

    #[test]
    fn glued_texture_path_is_an_unknown_identifier() {
        assert_eq!(
            kind("NO./n.png\n"),
            MapErrorKind::UnknownIdentifier("NO./n.png".into())
        );
    }

    #[test]
    fn identifier_without_value_is_refused() {
        assert_eq!(kind("WE\n"), MapErrorKind::NeedsOnePath("WE".into()));
        assert_eq!(kind("F\n"), MapErrorKind::NoSpaceAfter("F".into()));
    }

    #[test]
    fn huge_maps_are_refused_before_allocating() {
        let wide = "1".repeat(5000);
        let text = format!("{HEADER}{}", format!("{wide}\n").repeat(3400));
        assert!(matches!(kind(&text), MapErrorKind::TooLarge(..)));
    }
}
