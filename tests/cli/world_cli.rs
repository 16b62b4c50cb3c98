//! `halfcast render` with the world options: flags, errors, and the JSON `sprites` array.

use crate::world_common;

use serde_json::Value;
use world_common::{halfcast, map_file, ROOM};

fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn json_reports_each_sprites_projection_and_fate() {
    // Facing east from (1.5, 3.5): ahead, behind, far off to the side, hidden behind the block.
    let (_d, path) = map_file(
        "SPRITE 3.5,3.5 textures/sprites/barrel.png\nSPRITE 1.2,3.5 textures/sprites/barrel.png\nSPRITE 2.0,1.2 textures/sprites/plant.png\nSPRITE 8.0,3.5 textures/sprites/pillar.png scale=0.5\n",
        ROOM,
    );
    let out = halfcast(&[
        "render",
        path.to_str().unwrap(),
        "--pos",
        "1.5,3.5",
        "--angle",
        "0",
        "--fov",
        "90",
        "--size",
        "80x30",
        "--format",
        "json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let s = v["sprites"].as_array().unwrap();
    assert_eq!(s.len(), 4);
    // Ahead at depth 2: |plane| = 1, focal = 40, so 20 columns wide centred on 40.
    assert_eq!(s[0]["index"], 0);
    assert_eq!(s[0]["pos"], serde_json::json!([3.5, 3.5]));
    assert_eq!(s[0]["distance"].as_f64(), Some(2.0));
    assert_eq!(s[0]["screen_x"], serde_json::json!([30.0, 50.0]));
    assert_eq!(s[0]["columns"], serde_json::json!([30, 50]));
    assert_eq!(
        (s[0]["drawn"].as_bool(), s[0]["culled"].is_null()),
        (Some(true), true)
    );
    assert_eq!(s[1]["culled"], "behind");
    assert!(s[1]["screen_x"].is_null() && s[1]["distance"].as_f64().unwrap() < 0.0);
    assert_eq!(s[2]["culled"], "offscreen");
    assert_eq!(s[2]["drawn"], false);
    assert!(s[2]["screen_x"][1].as_f64().unwrap() <= 0.0);
    assert!(
        s[3]["culled"].is_null() && s[3]["drawn"] == false,
        "{}",
        s[3]
    );
}

#[test]
fn maps_without_sprites_report_an_empty_array_and_doors_do_not_matter() {
    let (_d, path) = map_file("", ROOM);
    let run = |extra: &[&str]| {
        let mut args = vec![
            "render",
            path.to_str().unwrap(),
            "--format",
            "json",
            "--size",
            "40x10",
        ];
        args.extend_from_slice(extra);
        halfcast(&args).stdout
    };
    let plain = run(&[]);
    let v: Value = serde_json::from_slice(&plain).unwrap();
    assert_eq!(v["sprites"], serde_json::json!([]));
    // Light, time and doors do not move rays; pitch and eye height do not either.
    assert_eq!(
        run(&[
            "--door-open",
            "1",
            "--night",
            "--time",
            "3",
            "--pitch",
            "10",
            "--z",
            "0.3"
        ]),
        plain
    );
}

#[test]
fn light_view_and_time_flags_change_the_picture() {
    let (_d, path) = map_file(
        "SPRITE 4.5,3.5 textures/sprites/creature.png views=8 frames=4 fps=4\n",
        ROOM,
    );
    let png = |extra: &[&str]| {
        let mut args = vec!["render", path.to_str().unwrap(), "--size", "60x20"];
        args.extend_from_slice(extra);
        let out = halfcast(&args);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        out.stdout
    };
    let plain = png(&[]);
    for flags in [
        &["--night"][..],
        &["--fog", "200,200,210,0.3"],
        &["--pitch", "-10"],
        &["--z", "0.3"],
        &["--time", "0.3"],
    ] {
        assert_ne!(png(flags), plain, "{flags:?}");
    }
    assert_eq!(
        png(&["--time", "1.0"]),
        plain,
        "4 frames at 4 fps wrap after a second"
    );
}

#[test]
fn bad_world_flags_are_refused_with_exit_2() {
    let cases: [(&[&str], &str); 6] = [
        (
            &["--pitch", "60"],
            "pitch 60 must be between -45 and 45 degrees",
        ),
        (
            &["--z", "1.5"],
            "eye height 1.5 must be between 0.05 and 0.95",
        ),
        (&["--fog", "1,2,3"], "'1,2,3' is not R,G,B,DENSITY"),
        (&["--fog", "1,2,300,0.1"], "is not R,G,B,DENSITY"),
        (&["--door-open", "2"], "2 must be between 0 and 1"),
        (&["--time", "nan"], "'nan' is not a finite number"),
    ];
    for (flags, msg) in cases {
        let mut args = vec!["render", "--format", "json"];
        args.extend_from_slice(flags);
        let out = halfcast(&args);
        assert_eq!(out.status.code(), Some(2), "{flags:?}");
        assert!(stderr(&out).contains(msg), "{flags:?}: {}", stderr(&out));
    }
}

#[test]
fn bad_sprite_fog_and_shade_lines_are_map_errors() {
    let cases = [
        (
            "SPRITE 2.5,2.5 textures/sprites/barrel.png glow\n",
            "test.cub:9:1: bad value for SPRITE: unknown option 'glow'",
        ),
        (
            "SPRITE 6.5,3.5 textures/sprites/barrel.png\n",
            "test.cub:9:1: sprite at 6.5,3.5 is not over a floor cell",
        ),
        (
            "FOG 1,2,3\n",
            "test.cub:9:1: bad value for FOG: expected 'r,g,b density', got '1,2,3'",
        ),
        (
            "SHADE -1\n",
            "test.cub:9:1: bad value for SHADE: expected a falloff number >= 0, got '-1'",
        ),
        (
            "TD a b\n",
            "test.cub:9:1: TD needs exactly one texture path",
        ),
    ];
    for (line, msg) in cases {
        let (_d, path) = map_file(line, ROOM);
        let out = halfcast(&["render", path.to_str().unwrap(), "--format", "json"]);
        assert_eq!(out.status.code(), Some(2), "{line}");
        let err = stderr(&out);
        assert!(err.contains(msg), "{line}: {err}");
    }
}

#[test]
fn a_missing_sprite_texture_falls_back_with_a_warning_or_fails_under_strict() {
    let (_d, path) = map_file("SPRITE 2.5,2.5 nowhere/ghost.png\n", ROOM);
    let out = halfcast(&["render", path.to_str().unwrap(), "--format", "json"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(
        stderr(&out).contains("using the built-in 'barrel' sprite"),
        "{}",
        stderr(&out)
    );
    let out = halfcast(&[
        "render",
        path.to_str().unwrap(),
        "--strict",
        "--format",
        "json",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("cannot load texture 'nowhere/ghost.png'"));
}

#[test]
fn the_default_map_has_sprites_doors_and_fog() {
    let out = halfcast(&["render", "--format", "json", "--size", "60x20"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["sprites"].as_array().unwrap().len() >= 30);
    let w = halfcast::world::World::default_world();
    assert_eq!(w.map.door_cells().len(), 3);
    assert!(w.map.fog.is_some());
}
