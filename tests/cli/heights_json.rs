//! `render --format json` on maps with `Hz` heights: each column adds `spans`, every vertical face
//! drawn in it (issue 14's contract); on flat maps the field is absent.

use crate::common;

use common::halfcast_ok;
use serde_json::Value;

fn json(args: &[&str]) -> Value {
    let mut all = vec!["render", "--format", "json"];
    all.extend_from_slice(args);
    serde_json::from_slice(&halfcast_ok(&all).stdout).unwrap()
}

#[test]
fn the_window_column_lists_its_lintel_step_and_what_lies_beyond() {
    // From the start, the centre ray goes through the window cell (11,5): floor 0.4, ceiling 0.8.
    let v = json(&["maps/heights.cub", "--size", "120x40"]);
    let col = &v["columns"][60];
    let spans = col["spans"].as_array().unwrap();
    let first: Vec<(&str, i64, i64)> = spans
        .iter()
        .take(2)
        .map(|s| {
            (
                s["kind"].as_str().unwrap(),
                s["cell"][0].as_i64().unwrap(),
                s["cell"][1].as_i64().unwrap(),
            )
        })
        .collect();
    assert_eq!(first, [("lintel", 11, 5), ("step", 11, 5)]);
    assert_eq!(spans[0]["z"], serde_json::json!([0.8, 1.0]));
    assert_eq!(spans[1]["z"], serde_json::json!([0.0, 0.4]));
    assert_eq!(spans[0]["perp_dist"], 1.5);
    // Focal 120 / (2 tan 33°) at distance 1.5, eye 0.5: z = 1 at row 9.2, z = 0.8 at 21.5.
    assert_eq!(spans[0]["rows"], serde_json::json!([9, 22]));
    // The ray ends on the hall's far wall, which is what the column's hit reports.
    let last = spans.last().unwrap();
    assert_eq!(last["kind"], "wall");
    assert_eq!(col["cell"], last["cell"]);
    assert_eq!(col["perp_dist"], last["perp_dist"]);
}

#[test]
fn spans_are_front_to_back_disjoint_and_on_screen() {
    for pose in [
        ["--pos", "2.0,8.6", "--angle", "90", "--pitch", "8"],
        ["--pos", "15.5,5.0", "--angle", "0", "--pitch", "-35"],
        ["--pos", "5.6,2.4", "--angle", "200", "--pitch", "-10"],
    ] {
        let mut args = vec!["maps/heights.cub", "--size", "80x30"];
        args.extend_from_slice(&pose);
        let v = json(&args);
        let columns = v["columns"].as_array().unwrap();
        assert_eq!(columns.len(), 80);
        for col in columns {
            let spans = col["spans"].as_array().unwrap();
            let mut last_dist = 0.0;
            let mut rows_seen = [false; 60];
            for s in spans {
                let kind = s["kind"].as_str().unwrap();
                assert!(["wall", "step", "lintel"].contains(&kind), "{s}");
                assert!(["x", "y"].contains(&s["side"].as_str().unwrap()));
                let d = s["perp_dist"].as_f64().unwrap();
                assert!(d >= last_dist, "{pose:?}: not front to back: {spans:?}");
                last_dist = d;
                let (z0, z1) = (s["z"][0].as_f64().unwrap(), s["z"][1].as_f64().unwrap());
                assert!(z0 < z1, "{s}");
                let (top, bottom) = (
                    s["rows"][0].as_u64().unwrap() as usize,
                    s["rows"][1].as_u64().unwrap() as usize,
                );
                assert!(top < bottom && bottom <= 60, "{s}");
                for r in &mut rows_seen[top..bottom] {
                    assert!(!*r, "{pose:?}: row drawn twice: {spans:?}");
                    *r = true;
                }
            }
        }
    }
}

#[test]
fn flat_maps_have_no_spans_field() {
    let v = json(&["--size", "40x12"]);
    for col in v["columns"].as_array().unwrap() {
        assert!(col.get("spans").is_none(), "{col}");
        assert_eq!(col.as_object().unwrap().len(), 4);
    }
}

#[test]
fn the_eye_stands_on_the_floor_of_the_cameras_cell() {
    // On the balcony (floor 1) looking at the north wall: `--z` (0.5) is above that floor, so
    // the eye is at 1.5 and the wall's part from the balcony floor (1) to its ceiling (2) sits
    // symmetric about the horizon, as a unit wall does on flat ground.
    let v = json(&[
        "maps/heights.cub",
        "--pos",
        "3.5,2.5",
        "--angle",
        "90",
        "--size",
        "90x30",
    ]);
    let col = &v["columns"][45];
    let wall = col["spans"].as_array().unwrap().last().unwrap().clone();
    assert_eq!(wall["kind"], "wall");
    assert_eq!(wall["z"], serde_json::json!([1.0, 2.0]));
    let t = wall["perp_dist"].as_f64().unwrap();
    assert_eq!(t, 1.5);
    let focal = 90.0 / (2.0 * 33f64.to_radians().tan());
    let rows = [
        wall["rows"][0].as_f64().unwrap(),
        wall["rows"][1].as_f64().unwrap(),
    ];
    // z = 2 and z = 1 are 0.5 above and below the eye at 1.5.
    assert_eq!(rows[0], (30.0 - 0.5 * focal / t - 0.5).ceil());
    assert_eq!(rows[1], (30.0 + 0.5 * focal / t - 0.5).ceil());
}
