//! Moving lights handed to a frame (a projectile's glow): they brighten surfaces near them when
//! the world is dark, measured in 3-D from the surface point, with no shadows (they are small
//! and short-lived; a wall between one and a surface does not stop it).

use crate::vec2::Vec2;
use crate::world::lamp_falloff::{falloff, FULL};

/// A light that exists for one frame, placed by the game (not baked: it moves).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLight {
    /// Where it is on the map plane, in cells.
    pub pos: Vec2,
    /// Its height, in wall heights (0.5 = eye level on a plain floor).
    pub z: f64,
    /// Distance at which its light has fallen to nothing, in cells (keep it small: every
    /// pixel within it pays for it).
    pub radius: f64,
    /// Brightness at its centre, 0–1 (1 = full daylight).
    pub strength: f64,
}

/// The light of `lights` on the surface point at `p`, height `z`, in 256ths (0 when none is in
/// reach). The same falloff as the map's lamps.
#[must_use]
#[inline]
pub fn level(lights: &[PointLight], p: Vec2, z: f64) -> u16 {
    let mut sum = 0.0;
    for l in lights {
        let (dx, dy, dz) = (p.x - l.pos.x, p.y - l.pos.y, z - l.z);
        let r2 = l.radius * l.radius;
        // Cheap rejections first: most pixels are far from every light.
        if dx * dx >= r2 || dy * dy >= r2 {
            continue;
        }
        let d2 = dx * dx + dy * dy + dz * dz;
        if d2 < r2 {
            sum += l.strength * falloff(d2.sqrt(), l.radius);
        }
    }
    if sum <= 0.0 {
        return 0;
    }
    (sum.min(1.0) * f64::from(FULL)).round() as u16
}

/// Whether any of `lights` comes within reach of the vertical line through `p` (so a wall
/// column there needs per-row light).
#[must_use]
#[inline]
pub fn near(lights: &[PointLight], p: Vec2) -> bool {
    lights.iter().any(|l| {
        let (dx, dy) = (p.x - l.pos.x, p.y - l.pos.y);
        dx * dx + dy * dy < l.radius * l.radius
    })
}

/// Lamp and point light together, saturating at full.
#[must_use]
#[inline]
pub fn add(a: u16, b: u16) -> u16 {
    (a + b).min(FULL)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light(x: f64, y: f64, z: f64) -> PointLight {
        PointLight {
            pos: Vec2::new(x, y),
            z,
            radius: 1.5,
            strength: 1.0,
        }
    }

    #[test]
    fn full_at_the_light_fading_to_nothing_at_its_radius() {
        let l = [light(2.0, 2.0, 0.5)];
        assert_eq!(level(&l, Vec2::new(2.0, 2.0), 0.5), FULL);
        assert_eq!(level(&l, Vec2::new(3.5, 2.0), 0.5), 0);
        assert_eq!(level(&l, Vec2::new(9.0, 2.0), 0.5), 0);
        let mid = level(&l, Vec2::new(2.7, 2.0), 0.5);
        assert!(mid > 0 && mid < FULL, "{mid}");
        // Height counts: the floor under it is farther than the point beside it at its height.
        assert!(level(&l, Vec2::new(2.5, 2.0), 0.0) < level(&l, Vec2::new(2.5, 2.0), 0.5));
    }

    #[test]
    fn lights_add_and_saturate() {
        let two = [light(2.0, 2.0, 0.5), light(2.4, 2.0, 0.5)];
        let p = Vec2::new(2.2, 2.6);
        assert!(level(&two, p, 0.5) > level(&two[..1], p, 0.5));
        assert_eq!(add(200, 100), FULL);
        assert!(near(&two, Vec2::new(3.0, 2.0)) && !near(&two, Vec2::new(5.0, 2.0)));
    }
}
