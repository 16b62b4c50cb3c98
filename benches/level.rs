//! One `Level::tick` on the default map with 10 creatures (wander, patrol and chase mixed),
//! for 1 player and for 32 players spread over the map: the game logic a server runs per tick,
//! beside the render budget.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use halfcast::game::{Level, Player, Score};
use halfcast::map::{parse_map, Cell, Map};
use halfcast::world::door::DoorState;
use halfcast::world::{DEFAULT_MAP, DEFAULT_MAP_NAME};
use halfcast::Vec2;

/// Every `stride`-th floor cell's centre, `n` of them.
fn spread(map: &Map, n: usize, offset: usize) -> Vec<Vec2> {
    let floors: Vec<Vec2> = (0..map.height as i64)
        .flat_map(|j| (0..map.width as i64).map(move |i| (i, j)))
        .filter(|&(i, j)| matches!(map.cell(i, j), Cell::Floor { .. }))
        .map(|(i, j)| Vec2::new(i as f64 + 0.5, j as f64 + 0.5))
        .collect();
    let stride = (floors.len() / n).max(1);
    (0..n)
        .map(|k| floors[(offset + k * stride) % floors.len()])
        .collect()
}

fn level_tick(c: &mut Criterion) {
    let plain = parse_map(DEFAULT_MAP_NAME, DEFAULT_MAP.as_bytes()).expect("default map");
    let behaviours = ["wander", "patrol", "chase"];
    let lines: String = spread(&plain, 10, 3)
        .iter()
        .enumerate()
        .map(|(k, p)| {
            format!(
                "CREATURE {},{} creature behaviour={}\n",
                p.x,
                p.y,
                behaviours[k % 3]
            )
        })
        .collect();
    let map = parse_map(DEFAULT_MAP_NAME, format!("{lines}{DEFAULT_MAP}").as_bytes())
        .expect("default map with creatures");
    assert_eq!(map.creatures.len(), 10);
    let doors = DoorState::new(&map);
    let mut group = c.benchmark_group("level tick, 10 creatures");
    group.sample_size(30);
    group.measurement_time(std::time::Duration::from_secs(3));
    for players in [1usize, 32] {
        let spots = spread(&map, players, 7);
        let mut level = Level::new(&map, 1);
        let mut scores = vec![Score::default(); players];
        // Warm up: creatures spread out, some see players and chase.
        let tick = |level: &mut Level, scores: &mut [Score]| {
            let mut ps: Vec<Player> = spots
                .iter()
                .zip(scores.iter_mut())
                .map(|(&pos, score)| Player {
                    pos,
                    eye: 0.5,
                    score,
                })
                .collect();
            level.tick(&map, &doors, &mut ps, 1.0 / 30.0)
        };
        for _ in 0..300 {
            tick(&mut level, &mut scores);
        }
        group.bench_with_input(BenchmarkId::from_parameter(players), &(), |b, ()| {
            b.iter(|| tick(&mut level, &mut scores));
        });
    }
    group.finish();
}

criterion_group!(benches, level_tick);
criterion_main!(benches);
