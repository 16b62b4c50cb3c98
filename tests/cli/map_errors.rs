//! Every `tests/fixtures/invalid_*.cub` is refused with exit code 2 and its exact message.

use crate::common;

use common::{halfcast, root};

const CASES: &[(&str, &str)] = &[
    ("invalid_bad_character", "9:3: bad map character 'X'"),
    (
        "invalid_blank_line_in_map",
        "11:1: content after the blank line at 10 that ended the map (the grid must be contiguous and come last)",
    ),
    (
        "invalid_colour_out_of_range",
        "5:1: bad colour for F: expected r,g,b with integers 0-255, got '220,256,0'",
    ),
    ("invalid_colour_two_numbers", "5:1: bad colour for F: expected r,g,b with integers 0-255, got '220,100'"),
    (
        "invalid_content_after_map",
        "13:1: content after the blank line at 12 that ended the map (the grid must be contiguous and come last)",
    ),
    ("invalid_duplicate_texture", "7:1: duplicate identifier 'NO' (first given at line 1)"),
    (
        "invalid_game_creature_behaviour",
        "7:35: bad value for CREATURE: behaviour must be wander, patrol or chase, got 'fly'",
    ),
    ("invalid_game_exit_in_wall", "7:1: exit at 6,1 is not a floor cell"),
    ("invalid_game_item_in_wall", "7:1: item at 0.5,1.5 is not over a floor cell"),
    (
        "invalid_game_item_points",
        "7:21: bad value for ITEM: points must be a whole number 0-1000000, got 'lots'",
    ),
    ("invalid_game_lock_not_door", "8:1: DOORLOCK at 3,1 is not on a door cell (D)"),
    ("invalid_game_lock_twice", "9:1: door at 4,1 is already locked (line 8)"),
    ("invalid_game_lock_without_key", "8:1: DOORLOCK needs the key 'blue' but no ITEM has key=blue"),
    ("invalid_heights_duplicate", "9:1: duplicate identifier 'Ha' (first given at line 7)"),
    (
        "invalid_heights_floor_not_below_ceiling",
        "7:8: bad value for Ha: ceiling height 1.5 must be above the floor height 1.5",
    ),
    ("invalid_heights_not_a_number", "7:8: bad value for Ha: ceiling height 'abc' is not a number"),
    (
        "invalid_heights_one_number",
        "7:1: bad value for Ha: expected 'FLOOR CEIL' (two heights in wall units), got '0.5'",
    ),
    ("invalid_heights_out_of_range", "7:4: bad value for Ha: floor height -5 is below -4"),
    (
        "invalid_light_in_wall",
        "8:1: light at 0.5,1.5 is not over a floor cell",
    ),
    (
        "invalid_light_radius",
        "7:1: bad value for LIGHT: radius must be above 0 and at most 16, got 40",
    ),
    ("invalid_missing_ea", " missing identifier 'EA' (east wall texture) before the map"),
    ("invalid_no_map", " no map grid after the header"),
    ("invalid_no_player", " no player start (N, S, E or W) in the map"),
    ("invalid_no_space_after_f", "5:1: no space after identifier 'F' (write 'F r,g,b')"),
    ("invalid_not_closed", "10:5: map is not closed: floor cell at 10:5 touches void"),
    ("invalid_not_utf8", "2:7: file is not valid UTF-8 text"),
    ("invalid_serve_rotation", "7:1: unknown identifier 'Q'"),
    ("invalid_tab_in_map", "9:1: bad map character '\\t'"),
    ("invalid_too_many_lights", "263:1: too many LIGHT lines; the limit is 256"),
    (
        "invalid_too_many_sprites",
        "71:3: too many sprites (SPRITE lines and '2' cells); the limit is 4096",
    ),
    ("invalid_two_players", "10:3: second player start (first at 9:3); a map has exactly one"),
    ("invalid_two_texture_paths", "1:1: NO needs exactly one texture path"),
    ("invalid_undefined_zone", "9:3: zone letter 'a' is used in the map but has no Fa, Ca, Ha or Wa line"),
    ("invalid_unknown_identifier", "8:1: unknown identifier 'XX'"),
    ("invalid_void_inside", "9:5: map is not closed: floor cell at 9:5 touches void"),
];

#[test]
fn each_invalid_fixture_gives_its_exact_message_and_exit_2() {
    for (name, tail) in CASES {
        let path = format!("tests/fixtures/{name}.cub");
        let out = halfcast(&["render", &path, "--format", "txt"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
        assert_eq!(stderr, format!("error: {path}:{tail}\n"), "{name}");
        assert!(out.stdout.is_empty(), "{name} wrote a frame");
    }
}

#[test]
fn every_invalid_fixture_is_listed() {
    let mut on_disk: Vec<String> = std::fs::read_dir(root().join("tests/fixtures"))
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.starts_with("invalid_") && n.ends_with(".cub"))
        .map(|n| n.trim_end_matches(".cub").to_owned())
        .collect();
    on_disk.sort();
    let listed: Vec<String> = CASES.iter().map(|(n, _)| (*n).to_owned()).collect();
    assert_eq!(on_disk, listed);
}

#[test]
fn missing_textures_warn_once_each_and_still_render() {
    let out = halfcast(&[
        "render",
        "tests/fixtures/valid_missing_textures.cub",
        "--format",
        "txt",
        "--size",
        "20x5",
    ]);
    assert_eq!(out.status.code(), Some(0));
    let stderr = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 4, "{stderr}");
    assert!(lines[0].starts_with(
        "warning: tests/fixtures/valid_missing_textures.cub:1:4: cannot load texture './north.png': "
    ));
    assert!(lines[0].ends_with("; using the built-in 'bricks' texture"));
    assert_eq!(String::from_utf8_lossy(&out.stdout).lines().count(), 5);
}

#[test]
fn strict_makes_a_missing_texture_an_error() {
    let out = halfcast(&[
        "render",
        "tests/fixtures/valid_missing_textures.cub",
        "--strict",
        "--format",
        "txt",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with("error: tests/fixtures/valid_missing_textures.cub:1:4: cannot load texture './north.png': "),
        "{stderr}"
    );
}

#[test]
fn a_missing_map_file_is_a_clear_error() {
    let out = halfcast(&["render", "tests/fixtures/no_such_map.cub"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with("error: tests/fixtures/no_such_map.cub: cannot read the file: "),
        "{stderr}"
    );
}

#[test]
fn absurd_sizes_and_fovs_are_refused() {
    for args in [
        ["--size", "0x10"],
        ["--size", "5000x10"],
        ["--size", "axb"],
        ["--fov", "180"],
        ["--fov", "-5"],
    ] {
        let out = halfcast(&["render", args[0], args[1], "--format", "txt"]);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(!out.stderr.is_empty());
    }
}
