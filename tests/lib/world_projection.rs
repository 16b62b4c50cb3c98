//! Properties of the sprite maths: projection agrees with the rays the caster shoots, and the
//! draw order is far to near.

use halfcast::camera::Camera;
use halfcast::render::sprite_projection::{far_to_near, project, to_camera_space, Culled};
use halfcast::{Vec2, View};
use proptest::prelude::*;

proptest! {
    #[test]
    fn a_sprite_centre_lands_on_the_column_whose_ray_passes_through_it(
        px in 0.0f64..20.0, py in 0.0f64..20.0, angle in -180.0f64..180.0, fov in 30.0f64..120.0,
        sx in 0.0f64..20.0, sy in 0.0f64..20.0, w in 8usize..400,
    ) {
        let cam = Camera::from_angle(Vec2::new(px, py), angle, fov);
        let p = Vec2::new(sx, sy);
        let (lateral, depth) = to_camera_space(&cam, p);
        // p − pos = lateral·plane + depth·dir, exactly.
        let back = cam.pos + cam.plane * lateral + cam.dir * depth;
        prop_assert!((back.x - p.x).abs() < 1e-9 && (back.y - p.y).abs() < 1e-9);
        match project(&cam, &View::default(), p, (1.0, 1.0), 0.0, w, 60) {
            Ok(proj) => {
                let centre = (proj.left + proj.right) / 2.0;
                // The ray through fractional column `centre` points at p.
                let cx = 2.0 * centre / w as f64 - 1.0;
                let ray = cam.dir + cam.plane * cx;
                let rel = p - cam.pos;
                let cross = ray.x * rel.y - ray.y * rel.x;
                prop_assert!(cross.abs() < 1e-6 * (1.0 + rel.length() * ray.length()), "{cross}");
                prop_assert!(proj.depth > 0.0 && ray.dot(rel) > 0.0);
                // Width in columns = focal / depth for a one-cell sprite.
                let width = proj.right - proj.left;
                prop_assert!((width - cam.focal_length(w) / depth).abs() < 1e-6 * width.max(1.0));
                prop_assert!(proj.cols.0 < proj.cols.1 && proj.cols.1 <= w);
            }
            Err(Culled::Behind) => prop_assert!(depth <= 0.05),
            Err(Culled::Offscreen) => {
                // Entirely left, entirely right, or thinner than a column between two rays,
                // or shorter than a pixel row between two row centres.
                let centre = w as f64 / 2.0 * (1.0 + lateral / depth);
                let half = cam.focal_length(w) / depth / 2.0;
                let (left, right) = (centre - half, centre + half);
                let (top, bottom) = (30.0 - half, 30.0 + half);
                prop_assert!(
                    right <= 0.0
                        || left > (w - 1) as f64
                        || left.ceil() >= right.ceil()
                        || (top - 0.5).ceil() >= (bottom - 0.5).ceil()
                );
            }
        }
    }

    #[test]
    fn draw_order_is_far_to_near_and_a_permutation(depths in prop::collection::vec(-5.0f64..50.0, 0..40)) {
        let input: Vec<(usize, f64)> = depths.iter().copied().enumerate().collect();
        let order = far_to_near(&input);
        prop_assert_eq!(order.len(), depths.len());
        for pair in order.windows(2) {
            prop_assert!(depths[pair[0]] >= depths[pair[1]]);
        }
        let mut seen = order.clone();
        seen.sort_unstable();
        prop_assert_eq!(seen, (0..depths.len()).collect::<Vec<_>>());
    }
}
