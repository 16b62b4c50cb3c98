//! Sight and flight on maps with heights, against an independent walk: on random grids of
//! random floors and ceilings, the game's DDA-based `first_block_at` is blocked exactly when a
//! walk over every grid crossing of the segment (found analytically and sorted, not stepped)
//! meets a wall or a height outside the open air of the cell it is in.

use crate::game::sight::first_block_at;
use crate::map::{parse_map, Map};
use crate::vec2::Vec2;
use crate::world::door::DoorState;
use proptest::prelude::*;

const SIZE: usize = 9;

/// A bordered SIZE×SIZE grid: `cells` picks each inner cell (0 floor, 1 wall, 2–5 zones a–d),
/// `zones` their (floor, height of the open air).
fn height_map(cells: &[u8], zones: &[(f64, f64)]) -> Map {
    let mut text =
        String::from("NO ./a.png\nSO ./a.png\nWE ./a.png\nEA ./a.png\nF 1,1,1\nC 2,2,2\n");
    for (k, (floor, tall)) in zones.iter().enumerate() {
        let letter = char::from(b'a' + k as u8);
        text += &format!("H{letter} {floor:.3} {:.3}\n", floor + tall);
    }
    text.push('\n');
    for y in 0..SIZE {
        for x in 0..SIZE {
            let border = x == 0 || y == 0 || x == SIZE - 1 || y == SIZE - 1;
            let c = if border {
                '1'
            } else if (x, y) == (1, 1) {
                'N'
            } else {
                match cells[y * SIZE + x] {
                    0 => '0',
                    1 => '1',
                    z => char::from(b'a' + z - 2),
                }
            };
            text.push(c);
        }
        text.push('\n');
    }
    parse_map("random.cub", text.as_bytes()).expect("the random map parses")
}

/// Whether the segment is stopped, by the independent walk: every t where x or y crosses a
/// grid line, sorted; each piece between two lies in one cell, which must be open, with the
/// segment's height inside that cell's span at both ends of the piece.
fn blocked_by_walk(map: &Map, (a, za): (Vec2, f64), (b, zb): (Vec2, f64)) -> bool {
    let mut ts = vec![0.0, 1.0];
    for (p, q) in [(a.x, b.x), (a.y, b.y)] {
        if (q - p).abs() > 1e-12 {
            let (lo, hi) = (p.min(q).ceil() as i64, p.max(q).floor() as i64);
            for g in lo..=hi {
                let t = (g as f64 - p) / (q - p);
                if (0.0..=1.0).contains(&t) {
                    ts.push(t);
                }
            }
        }
    }
    ts.sort_by(f64::total_cmp);
    let z = |t: f64| za + (zb - za) * t;
    ts.windows(2).any(|w| {
        let mid = (w[0] + w[1]) / 2.0;
        let at = a + (b - a) * mid;
        match map.span(at.x.floor() as i64, at.y.floor() as i64) {
            None => true,
            Some(s) => [w[0], w[1]]
                .iter()
                .any(|&t| z(t) < s.floor - 1e-9 || z(t) > s.ceil + 1e-9),
        }
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn first_block_at_agrees_with_an_independent_walk(
        cells in prop::collection::vec(0u8..6, SIZE * SIZE),
        zones in prop::collection::vec((-1.0f64..1.0, 0.3f64..2.0), 4),
        ends in prop::collection::vec((1.0f64..8.0, 1.0f64..8.0, 0.05f64..0.95), 2),
    ) {
        let map = height_map(&cells, &zones);
        let doors = DoorState::none();
        // Each end inside an open cell, its height inside that cell's open air.
        let mut pts = Vec::new();
        for &(x, y, h) in &ends {
            let Some(s) = map.span(x.floor() as i64, y.floor() as i64) else {
                return Ok(());
            };
            pts.push((Vec2::new(x, y), s.floor + (s.ceil - s.floor) * h));
        }
        let (from, to) = (pts[0], pts[1]);
        let game = first_block_at(&map, &doors, from, to);
        prop_assert_eq!(
            game.is_some(),
            blocked_by_walk(&map, from, to),
            "{:?} -> {:?}: game says {:?}", from, to, game
        );
        // Where it stops, it stops in a solid cell or at a height outside the cell's air.
        if let Some((cell, t)) = game {
            let z = from.1 + (to.1 - from.1) * t;
            let solid = map.span(cell.0, cell.1).is_none_or(|s| z <= s.floor + 1e-6 || z >= s.ceil - 1e-6);
            prop_assert!(solid, "stopped at {:?}, t {}, z {}", cell, t, z);
        }
    }
}
