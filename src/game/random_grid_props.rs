//! Properties of the game's rules on random small maps: creatures never end up inside walls or
//! shut doors, and a creature's line of sight is exactly the renderer's DDA.

use crate::game::collision::{overlaps_wall, Obstacles};
use crate::game::creature::CREATURE_RADIUS;
use crate::game::sight::line_of_sight;
use crate::game::{Level, Player, Score};
use crate::map::{parse_map, Cell, Map};
use crate::render::cast::cast_ray_doors;
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use proptest::prelude::*;

/// Map header: any texture paths (only the grid is used here).
const HEADER: &str = "NO a.png\nSO a.png\nWE a.png\nEA a.png\nF 96,88,80\nC 150,146,136\n";

/// A closed random grid: border walls, `walls` inside, and every floor cell framed by walls on
/// two opposite sides turned into a door where `doors` says so; the start is the first floor.
fn random_map(w: usize, h: usize, walls: &[bool], doors: &[bool], creatures: &str) -> Option<Map> {
    let wall =
        |i: usize, j: usize| i == 0 || j == 0 || i == w - 1 || j == h - 1 || walls[j * w + i];
    let mut rows: Vec<Vec<u8>> = (0..h)
        .map(|j| {
            (0..w)
                .map(|i| if wall(i, j) { b'1' } else { b'0' })
                .collect()
        })
        .collect();
    for j in 1..h - 1 {
        for i in 1..w - 1 {
            let framed = (wall(i - 1, j) && wall(i + 1, j)) || (wall(i, j - 1) && wall(i, j + 1));
            if !wall(i, j) && framed && doors[j * w + i] {
                rows[j][i] = b'D';
            }
        }
    }
    let start = (0..h * w).find(|&k| rows[k / w][k % w] == b'0')?;
    rows[start / w][start % w] = b'E';
    let grid: Vec<String> = rows
        .into_iter()
        .map(|r| String::from_utf8(r).unwrap())
        .collect();
    let text = format!("{HEADER}{creatures}\n{}\n", grid.join("\n"));
    parse_map("random.cub", text.as_bytes()).ok()
}

fn floor_points(map: &Map, picks: &[(u16, f64, f64)]) -> Vec<Vec2> {
    let floors: Vec<(i64, i64)> = (0..map.height as i64)
        .flat_map(|j| (0..map.width as i64).map(move |i| (i, j)))
        .filter(|&(i, j)| matches!(map.cell(i, j), Cell::Floor { .. }))
        .collect();
    picks
        .iter()
        .map(|&(k, fx, fy)| {
            let (i, j) = floors[usize::from(k) % floors.len()];
            Vec2::new(i as f64 + fx, j as f64 + fy)
        })
        .collect()
}

fn doors_as(map: &Map, open: &[bool]) -> DoorState {
    let mut doors = DoorState::new(map);
    for (k, &cell) in map.door_cells().iter().enumerate() {
        doors.set_open(cell, if open[k % open.len()] { 1.0 } else { 0.0 });
    }
    doors
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn creatures_never_walk_into_walls_or_shut_doors(
        (w, h) in (5usize..11, 5usize..10),
        walls in prop::collection::vec(prop::bool::weighted(0.3), 110),
        door_cells in prop::collection::vec(prop::bool::weighted(0.4), 110),
        open in prop::collection::vec(any::<bool>(), 1..6),
        picks in prop::collection::vec((any::<u16>(), 0.05f64..0.95, 0.05f64..0.95), 3..6),
        behaviours in prop::collection::vec(0usize..3, 3),
        seed in any::<u64>(),
    ) {
        let Some(plain) = random_map(w, h, &walls, &door_cells, "") else { return Ok(()) };
        let points = floor_points(&plain, &picks);
        let names = ["wander", "patrol", "chase"];
        let lines: String = points[1..]
            .iter()
            .zip(behaviours.iter().cycle())
            .map(|(p, &b)| format!("CREATURE {},{} creature speed=4 behaviour={}\n", p.x, p.y, names[b]))
            .collect();
        let map = random_map(w, h, &walls, &door_cells, &lines).expect("same grid parses");
        let doors = doors_as(&map, &open);
        let mut level = Level::new(&map, seed);
        let mut score = Score::default();
        let obstacles = Obstacles { map: &map, doors: Some(&doors), discs: &[], body: None };
        let cell = |p: Vec2| (p.x.floor() as i64, p.y.floor() as i64);
        let mut before: Vec<(i64, i64)> = level.creatures().iter().map(|c| cell(c.pos)).collect();
        for _ in 0..240 {
            let mut players = [Player {
                pos: points[0],
                eye: 0.5,
                score: &mut score,
            }];
            level.tick(&map, &doors, &mut players, 1.0 / 30.0);
            for (c, was) in level.creatures().iter().zip(&mut before) {
                prop_assert!(
                    !overlaps_wall(&obstacles, c.pos, CREATURE_RADIUS - 1e-6),
                    "creature at {:?} overlaps a wall or shut door", c.pos
                );
                let now = cell(c.pos);
                prop_assert!(
                    (now.0 - was.0).abs() + (now.1 - was.1).abs() <= 1,
                    "jumped from {:?} to {:?}", was, now
                );
                *was = now;
            }
        }
    }

    #[test]
    fn sight_agrees_with_the_renderers_dda(
        (w, h) in (5usize..12, 5usize..12),
        walls in prop::collection::vec(prop::bool::weighted(0.25), 144),
        door_cells in prop::collection::vec(prop::bool::weighted(0.5), 144),
        open in prop::collection::vec(any::<bool>(), 1..6),
        picks in prop::collection::vec((any::<u16>(), 0.0f64..1.0, 0.0f64..1.0), 2),
    ) {
        let Some(map) = random_map(w, h, &walls, &door_cells, "") else { return Ok(()) };
        let doors = doors_as(&map, &open);
        let pts = floor_points(&map, &picks);
        let (a, b) = (pts[0], pts[1]);
        let target = (b.x.floor() as i64, b.y.floor() as i64);
        // The renderer's ray from A toward B: does it enter B's cell before it stops?
        let mut cells = Vec::new();
        let hit = cast_ray_doors(&map, &doors, a, b - a, |s| cells.push(s.cell));
        let start = (a.x.floor() as i64, a.y.floor() as i64);
        let reached = start == target || cells.iter().take_while(|&&c| c != hit.cell).any(|&c| c == target);
        prop_assert_eq!(line_of_sight(&map, &doors, a, b), reached, "{:?} -> {:?}", a, b);
    }
}
