//! Property tests: the DDA against an independent traversal, and the parser on arbitrary input.

use halfcast::camera::Camera;
use halfcast::map::{parse_map, Cell, Map, MapErrorKind};
use halfcast::render::cast::{cast, trace_column, Side};
use halfcast::Vec2;
use proptest::prelude::*;

/// A closed map: a border of walls around random interior walls (types 1, 3–5), one player.
fn map_text(w: usize, h: usize, walls: &[bool], kinds: &[u8], player: (usize, usize)) -> String {
    let mut s = String::from("NO n\nSO s\nWE w\nEA e\nF 1,2,3\nC 4,5,6\n\n");
    for j in 0..h {
        for i in 0..w {
            let border = i == 0 || j == 0 || i == w - 1 || j == h - 1;
            let k = j * w + i;
            s.push(if (i, j) == player {
                'E'
            } else if border || walls[k] {
                char::from(b'0' + kinds[k])
            } else {
                '0'
            });
        }
        s.push('\n');
    }
    s
}

fn arb_world() -> impl Strategy<Value = (String, Vec2)> {
    (4usize..20, 4usize..20).prop_flat_map(|(w, h)| {
        (
            Just((w, h)),
            prop::collection::vec(prop::bool::weighted(0.2), w * h),
            prop::collection::vec(prop::sample::select(vec![1u8, 3, 4, 5]), w * h),
            (1..w - 1, 1..h - 1),
            (0.001f64..0.999, 0.001f64..0.999),
        )
            .prop_map(|((w, h), walls, kinds, p, f)| {
                (
                    map_text(w, h, &walls, &kinds, p),
                    Vec2::new(p.0 as f64 + f.0, p.1 as f64 + f.1),
                )
            })
    })
}

/// An independent traversal: crossing times along the ray parameter t, written from scratch.
/// Returns (cells entered with the axis crossed, t at the hit = perpendicular distance).
/// Cells entered, each with the axis crossed ('x' or 'y').
type Path = Vec<((i64, i64), char)>;

fn reference_walk(map: &Map, pos: Vec2, ray: Vec2) -> (Path, f64) {
    let mut cell = (pos.x.floor() as i64, pos.y.floor() as i64);
    let next_t = |p: f64, d: f64, c: i64| -> (f64, f64, i64) {
        if d > 0.0 {
            ((c as f64 + 1.0 - p) / d, 1.0 / d, 1)
        } else if d < 0.0 {
            ((p - c as f64) / -d, -1.0 / d, -1)
        } else {
            (f64::INFINITY, f64::INFINITY, 0)
        }
    };
    let (mut tx, dtx, sx) = next_t(pos.x, ray.x, cell.0);
    let (mut ty, dty, sy) = next_t(pos.y, ray.y, cell.1);
    let mut path = Vec::new();
    loop {
        let t;
        if tx < ty {
            t = tx;
            tx += dtx;
            cell.0 += sx;
            path.push((cell, 'x'));
        } else {
            t = ty;
            ty += dty;
            cell.1 += sy;
            path.push((cell, 'y'));
        }
        if !matches!(map.cell(cell.0, cell.1), Cell::Floor { .. }) {
            return (path, t);
        }
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn dda_agrees_with_an_independent_walk((text, pos) in arb_world(), angle in -360.0f64..360.0, fov in 30.0f64..120.0, width in 8usize..240) {
        let map = parse_map("p.cub", text.as_bytes()).unwrap();
        let cam = Camera::from_angle(pos, angle, fov);
        let c = cast(&map, &cam, width, None);
        for (x, hit) in c.columns.iter().enumerate() {
            let (path, t) = reference_walk(&map, pos, cam.ray_dir(x, width));
            let (cell, axis) = *path.last().unwrap();
            prop_assert_eq!(hit.cell, cell);
            prop_assert_eq!(hit.side.as_str(), axis.to_string());
            prop_assert!(close(hit.perp_dist, t), "column {}: {} vs {}", x, hit.perp_dist, t);
            prop_assert!(hit.perp_dist > 0.0);
            prop_assert!(matches!(map.cell(hit.cell.0, hit.cell.1), Cell::Wall(_)));
            prop_assert!((0.0..1.0).contains(&hit.wall_x));
        }
    }

    #[test]
    fn traces_are_four_connected_and_end_at_the_hit((text, pos) in arb_world(), angle in -180.0f64..180.0, width in 8usize..64, pick in 0.0f64..1.0) {
        let map = parse_map("p.cub", text.as_bytes()).unwrap();
        let cam = Camera::from_angle(pos, angle, 66.0);
        let x = ((width as f64 * pick) as usize).min(width - 1);
        let t = trace_column(&map, &cam, x, width);
        let mut prev = t.start_cell;
        for s in &t.steps {
            let (dx, dy) = (s.cell.0 - prev.0, s.cell.1 - prev.1);
            prop_assert_eq!(dx.abs() + dy.abs(), 1, "{:?} -> {:?}", prev, s.cell);
            prop_assert_eq!(s.side == Side::X, dx != 0);
            prev = s.cell;
        }
        prop_assert_eq!(prev, t.hit.cell);
        let walls = t.steps.iter().filter(|s| !matches!(map.cell(s.cell.0, s.cell.1), Cell::Floor { .. })).count();
        prop_assert_eq!(walls, 1, "only the last cell is a wall");
    }

    #[test]
    fn arbitrary_bytes_never_panic_the_parser(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        let lines = bytes.iter().filter(|&&b| b == b'\n').count() + 1;
        if let Err(e) = parse_map("r.cub", &bytes) {
            if let Some((line, col)) = e.at {
                prop_assert!(line >= 1 && line <= lines && col >= 1, "{}", e);
            }
            prop_assert!(e.to_string().starts_with("r.cub:"));
        }
    }

    #[test]
    fn arbitrary_map_like_text_never_panics(body in "[012NSEW \n\t3a-cFCNOSWEA,.0-9]{0,300}") {
        let _ = parse_map("r.cub", format!("NO n\nSO s\nWE w\nEA e\nF 1,2,3\nC 4,5,6\n{body}").as_bytes());
    }

    #[test]
    fn opening_any_border_wall_breaks_closure((text, _pos) in arb_world(), pick in any::<prop::sample::Index>()) {
        let lines: Vec<&str> = text.lines().collect();
        let grid = &lines[7..];
        let (w, h) = (grid[0].len(), grid.len());
        let border: Vec<(usize, usize)> = (0..h).flat_map(|j| (0..w).map(move |i| (i, j)))
            .filter(|&(i, j)| (i == 0 || j == 0 || i == w - 1 || j == h - 1) && grid[j].as_bytes()[i] != b'E')
            .collect();
        let (i, j) = border[pick.index(border.len())];
        let mut rows: Vec<String> = grid.iter().map(|r| (*r).to_owned()).collect();
        rows[j].replace_range(i..=i, "0");
        let broken = format!("{}\n{}\n", lines[..7].join("\n"), rows.join("\n"));
        let e = parse_map("b.cub", broken.as_bytes()).unwrap_err();
        let not_closed = matches!(e.kind, MapErrorKind::NotClosed { .. });
        prop_assert!(not_closed, "{}", e);
    }
}
