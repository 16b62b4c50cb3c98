//! Doors: parsing, the inset panel seen by the caster (checked against an independent walk),
//! and the movement queries.

use crate::oracle;
use crate::world_common;

use halfcast::map::{parse_map, Cell, DoorPlane};
use halfcast::world::door::DoorState;
use halfcast::Vec2;
use oracle::{close, close_fraction, walk, walled_grid};
use proptest::prelude::*;
use serde_json::Value;
use world_common::{halfcast, map_file, world, HEADER};

fn parse_err(grid: &str) -> String {
    parse_map("t.cub", format!("{HEADER}\n{grid}").as_bytes())
        .unwrap_err()
        .to_string()
}

#[test]
fn door_planes_follow_their_frame() {
    let w = world("", "11111\n1E0D1\n11011\n11D11\n10001\n11111\n");
    assert_eq!(w.map.cell(3, 1), Cell::Door(DoorPlane::X));
    assert_eq!(w.map.cell(2, 3), Cell::Door(DoorPlane::Y));
    assert_eq!(w.map.door_cells(), [(3, 1), (2, 3)]);
}

#[test]
fn door_rule_breaks_are_reported_with_their_place() {
    assert_eq!(
        parse_err("11111\n1E001\n10D01\n10001\n11111\n"),
        "t.cub:12:3: door at 12:3 needs walls on two opposite sides (east and west, or north and south)"
    );
    assert_eq!(
        parse_err("1111\n1E0D\n1111\n"),
        "t.cub:11:4: map is not closed: door cell at 11:4 touches void"
    );
}

#[test]
fn blocking_walls_doors_and_solid_sprites() {
    let w = world(
        "SPRITE 2.5,3.5 textures/sprites/barrel.png solid=0.3\nSPRITE 3.5,3.5 textures/sprites/lamp.png\n",
        "111111\n1E0D01\n111101\n100001\n111111\n",
    );
    let mut doors = DoorState::new(&w.map);
    let r = 0.2;
    assert!(!w.is_blocked(Vec2::new(1.5, 1.5), r, &doors));
    assert!(
        w.is_blocked(Vec2::new(1.15, 1.5), r, &doors),
        "wall to the west"
    );
    assert!(w.is_blocked(Vec2::new(2.9, 1.5), r, &doors), "shut door");
    doors.set_open((3, 1), 1.0);
    assert!(!w.is_blocked(Vec2::new(2.9, 1.5), r, &doors), "open door");
    assert!(
        !w.is_blocked(Vec2::new(3.5, 1.5), r, &doors),
        "standing in the open door"
    );
    assert!(w.is_blocked(Vec2::new(2.5, 3.1), r, &doors), "solid barrel");
    assert!(
        !w.is_blocked(Vec2::new(3.5, 3.5), r, &doors),
        "lamps are not solid"
    );
    assert_eq!(w.solid_discs().len(), 1);
    assert_eq!(w.solid_discs()[0].radius, 0.3);
}

#[test]
fn legacy_two_cells_are_solid_sprites_with_the_s_texture() {
    let w = world("S textures/sprites/pillar.png\n", "11111\n1E021\n11111\n");
    assert_eq!(w.sprites.len(), 1);
    assert_eq!(w.sprites[0].def.pos, Vec2::new(3.5, 1.5));
    assert!(w.is_blocked(Vec2::new(3.1, 1.5), 0.2, &DoorState::none()));
}

#[test]
fn pressing_use_opens_the_door_in_front_over_a_second() {
    let w = world("", "1111111\n1E00D01\n1111111\n");
    let mut doors = DoorState::new(&w.map);
    let pos = Vec2::new(3.2, 1.5);
    assert_eq!(
        doors.toggle_facing(&w.map, pos, Vec2::new(1.0, 0.0)),
        Some((4, 1))
    );
    for _ in 0..10 {
        doors.update(0.05);
    }
    assert!((doors.open_amount((4, 1)) - 0.5).abs() < 1e-9);
    assert!(doors.blocks((4, 1)));
    doors.update(0.6);
    assert!(!doors.blocks((4, 1)));
}

/// A closed random map with some framed doors, and a pose inside a floor cell.
fn arb_door_case() -> impl Strategy<Value = (Vec<Vec<u8>>, (f64, f64))> {
    (5usize..14, 5usize..14).prop_flat_map(|(w, h)| {
        (
            prop::collection::vec(prop::bool::weighted(0.3), w * h),
            prop::collection::vec(prop::bool::weighted(0.6), w * h),
            (1..w - 1, 1..h - 1),
            (0.01f64..0.99, 0.01f64..0.99),
        )
            .prop_map(move |(walls, doors, (pi, pj), (fx, fy))| {
                let mut g = walled_grid(w, h, &walls, (pi, pj), b'E');
                for j in 1..h - 1 {
                    for i in 1..w - 1 {
                        let framed = (g[j][i - 1] == b'1' && g[j][i + 1] == b'1')
                            || (g[j - 1][i] == b'1' && g[j + 1][i] == b'1');
                        if g[j][i] == b'0' && framed && doors[j * w + i] {
                            g[j][i] = b'D';
                        }
                    }
                }
                (g, (pi as f64 + fx, pj as f64 + fy))
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn json_columns_match_an_independent_walk_with_doors_shut_and_open(
        (grid, pos) in arb_door_case(), angle in -180.0f64..180.0, cols in 8usize..120, open in any::<bool>()
    ) {
        let body: Vec<String> = grid.iter().map(|r| String::from_utf8(r.clone()).unwrap()).collect();
        let (_dir, path) = map_file("", &format!("{}\n", body.join("\n")));
        let out = halfcast(&[
            "render", path.to_str().unwrap(), "--pos", &format!("{},{}", pos.0, pos.1), "--angle", &angle.to_string(),
            "--size", &format!("{cols}x10"), "--format", "json", "--door-open", if open { "1" } else { "0" },
        ]);
        prop_assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
        let v: Value = serde_json::from_slice(&out.stdout).unwrap();
        let a = angle.to_radians();
        let d = (a.cos(), -a.sin());
        let half = 33f64.to_radians().tan();
        let plane = (-d.1 * half, d.0 * half);
        for (x, col) in v["columns"].as_array().unwrap().iter().enumerate() {
            let cx = 2.0 * x as f64 / cols as f64 - 1.0;
            let r = (d.0 + plane.0 * cx, d.1 + plane.1 * cx);
            let hit = walk(&grid, pos, r, open).hit;
            prop_assert_eq!(col["cell"][0].as_i64(), Some(hit.cell.0), "column {}", x);
            prop_assert_eq!(col["cell"][1].as_i64(), Some(hit.cell.1), "column {}", x);
            prop_assert_eq!(col["side"].as_str(), Some(hit.side), "column {}", x);
            prop_assert!(close(col["perp_dist"].as_f64().unwrap(), hit.perp), "column {} perp", x);
            prop_assert!(close_fraction(col["wall_x"].as_f64().unwrap(), hit.wall_x), "column {} wall_x", x);
        }
    }
}
