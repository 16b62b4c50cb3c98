//! `halfcast render --format json` agrees with the independent DDA walk (`tests/oracle`) on random closed maps and poses.

use crate::common;
use crate::oracle;

use common::halfcast;
use oracle::{close, close_fraction, walk, walled_grid};
use proptest::prelude::*;
use serde_json::Value;

/// A closed random map as text, and a pose strictly inside the player's cell.
fn arb_case() -> impl Strategy<Value = (Vec<Vec<u8>>, (f64, f64))> {
    (4usize..16, 4usize..16).prop_flat_map(|(w, h)| {
        (
            prop::collection::vec(prop::bool::weighted(0.25), w * h),
            (1..w - 1, 1..h - 1),
            (0.01f64..0.99, 0.01f64..0.99),
        )
            .prop_map(move |(walls, (pi, pj), (fx, fy))| {
                let grid = walled_grid(w, h, &walls, (pi, pj), b'S');
                (grid, (pi as f64 + fx, pj as f64 + fy))
            })
    })
}

fn f(v: &Value) -> f64 {
    v.as_f64().expect("number")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    #[test]
    fn json_matches_independent_dda((grid, pos) in arb_case(), angle in -180.0f64..180.0, fov in 30.0f64..120.0, cols in 8usize..240, rows in 1usize..60) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.cub");
        let body: Vec<String> = grid.iter().map(|r| String::from_utf8(r.clone()).unwrap()).collect();
        std::fs::write(&path, format!("NO n\nSO s\nWE w\nEA e\nF 1,2,3\nC 4,5,6\n\n{}\n", body.join("\n"))).unwrap();
        let out = halfcast(&[
            "render", path.to_str().unwrap(), "--pos", &format!("{},{}", pos.0, pos.1), "--angle", &angle.to_string(),
            "--fov", &fov.to_string(), "--size", &format!("{cols}x{rows}"), "--format", "json",
        ]);
        prop_assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
        let v: Value = serde_json::from_slice(&out.stdout).unwrap();

        let a = angle.to_radians();
        let d = (a.cos(), -a.sin());
        let half = (fov.to_radians() / 2.0).tan();
        let plane = (-d.1 * half, d.0 * half);
        prop_assert!(close(f(&v["pos"][0]), pos.0) && close(f(&v["pos"][1]), pos.1));
        prop_assert!(close(f(&v["dir"][0]), d.0) && close(f(&v["dir"][1]), d.1));
        prop_assert!(close(f(&v["plane"][0]), plane.0) && close(f(&v["plane"][1]), plane.1));
        let columns = v["columns"].as_array().unwrap();
        prop_assert_eq!(columns.len(), cols);
        let ray = |x: usize| {
            let cx = 2.0 * x as f64 / cols as f64 - 1.0;
            (d.0 + plane.0 * cx, d.1 + plane.1 * cx)
        };
        for (x, col) in columns.iter().enumerate() {
            let hit = walk(&grid, pos, ray(x), true).hit;
            prop_assert_eq!(col["cell"][0].as_i64(), Some(hit.cell.0));
            prop_assert_eq!(col["cell"][1].as_i64(), Some(hit.cell.1));
            prop_assert_eq!(col["side"].as_str(), Some(hit.side));
            prop_assert!(close(f(&col["perp_dist"]), hit.perp), "column {}", x);
            prop_assert!(close_fraction(f(&col["wall_x"]), hit.wall_x), "column {} wall_x", x);
        }
        let trace = v["centre_trace"].as_array().unwrap();
        let expect = walk(&grid, pos, ray(cols / 2), true).steps;
        prop_assert_eq!(trace.len(), expect.len());
        for (s, step) in trace.iter().zip(expect) {
            prop_assert_eq!(s["cell"][0].as_i64(), Some(step.cell.0));
            prop_assert_eq!(s["cell"][1].as_i64(), Some(step.cell.1));
            prop_assert_eq!(s["side"].as_str(), Some(step.side));
            prop_assert!(close(f(&s["side_dist"][0]), step.side_dist.0) && close(f(&s["side_dist"][1]), step.side_dist.1));
        }
    }
}

#[test]
fn negative_angles_work_with_and_without_equals() {
    let a = halfcast(&[
        "render", "--angle", "-45", "--format", "json", "--size", "8x4",
    ]);
    let b = halfcast(&["render", "--angle=-45", "--format", "json", "--size", "8x4"]);
    assert_eq!(
        a.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&a.stderr)
    );
    assert_eq!(a.stdout, b.stdout);
    let v: Value = serde_json::from_slice(&a.stdout).unwrap();
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!(close(f(&v["dir"][0]), h) && close(f(&v["dir"][1]), h));
}
