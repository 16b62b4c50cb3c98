//! The `.cub` reader: header identifiers, then a closed grid with one player.

use super::grid::{Grid, GridError, GridRules};
use super::header::{is_blank_char, too_many_sprites, Header, MAX_SPRITES};
use super::{Map, MapError, MapErrorKind, Surface, TextureRef};
use crate::color::Rgb;

/// More cells than this is refused instead of allocating without bound.
pub const MAX_CELLS: usize = 1 << 24;

/// Largest map (in cells) that may have lights: the light map holds 16 samples per cell.
pub const MAX_LIT_CELLS: usize = 1 << 20;

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

/// Turns the grid lines into cells, then checks players and closure.
fn build(file: &str, h: Header, lines: &[(usize, &str)]) -> Result<Map, MapError> {
    let err = |(at, kind): GridError| MapError {
        file: file.to_owned(),
        at,
        kind,
    };
    let mut grid = Grid::sized(lines);
    let cells = grid.width.saturating_mul(grid.height);
    if cells > MAX_CELLS {
        let kind = MapErrorKind::TooLarge(grid.width * grid.height, MAX_CELLS);
        return Err(err((Some((lines[0].0, 1)), kind)));
    }
    if let Some(first) = h.lights.first() {
        if cells > MAX_LIT_CELLS {
            let kind = MapErrorKind::TooLargeToLight {
                cells,
                limit: MAX_LIT_CELLS,
            };
            return Err(err((Some(first.at), kind)));
        }
    }
    let placed = grid
        .read(&GridRules {
            sprite_is_wall: h.wall_types[2].is_some(),
            sprites_left: MAX_SPRITES.saturating_sub(h.sprite_defs.len()),
            zones: &h.zones,
            too_many_sprites: too_many_sprites(),
        })
        .map_err(err)?;
    grid.check_closed().map_err(err)?;
    let planes = grid.door_planes().map_err(err)?;
    grid.check_placed(&h.sprite_defs, &h.lights).map_err(err)?;
    h.game
        .check(|i, j| grid.at(i, j))
        .map_err(|(place, kind)| err((Some(place), kind)))?;
    grid.set_doors(planes);
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
        width: grid.width,
        height: grid.height,
        cells: grid.cells,
        start: placed.start,
        faces: [no, so, we, ea].map(|f| f.expect("checked by check_complete")),
        wall_types: h.wall_types,
        floor: surface(h.floor_texture, h.floor),
        ceiling: surface(h.ceiling_texture, h.ceiling),
        zones: h.zones,
        sprite_texture: h.sprite_texture,
        sprites: placed.sprites,
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
    use super::super::{Cell, Span, Start};
    use super::*;
    use crate::vec2::Vec2;

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
