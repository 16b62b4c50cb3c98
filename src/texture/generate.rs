//! Procedural textures: the project's own art, made deterministically from integer hashes.

use super::Texture;
use crate::color::Rgb;

/// Edge length of every generated texture.
pub const SIZE: usize = 64;

/// A texture generator: no inputs, same texture every time.
pub type Generator = fn() -> Texture;

/// Every generated texture with the file stem it is saved under in `textures/`.
pub const ALL: [(&str, Generator); 8] = [
    ("bricks", bricks),
    ("stone", stone),
    ("wood", wood),
    ("metal", metal),
    ("mossy", mossy),
    ("floor", floor),
    ("ceiling", ceiling),
    ("door", door),
];

/// A well-mixed 32-bit hash of a lattice point, the root of all the noise here.
pub(super) fn hash(x: i64, y: i64, seed: u32) -> u32 {
    let mut h = (x as u32).wrapping_mul(0x9E37_79B1)
        ^ (y as u32).wrapping_mul(0x85EB_CA77)
        ^ seed.wrapping_mul(0xC2B2_AE3D);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2C1B_3C6D);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297A_2D39);
    h ^ (h >> 15)
}

/// Hash noise in [0, 1).
pub(super) fn white(x: i64, y: i64, seed: u32) -> f64 {
    f64::from(hash(x, y, seed) >> 8) / f64::from(1u32 << 24)
}

/// Smooth value noise in [0, 1) that tiles every `SIZE` pixels (lattice step `cell`).
pub(super) fn smooth(x: usize, y: usize, cell: usize, seed: u32) -> f64 {
    let n = (SIZE / cell) as i64;
    let (gx, gy) = ((x / cell) as i64, (y / cell) as i64);
    let (fx, fy) = (
        (x % cell) as f64 / cell as f64,
        (y % cell) as f64 / cell as f64,
    );
    let ease = |t: f64| t * t * (3.0 - 2.0 * t);
    let corner = |i: i64, j: i64| white(i.rem_euclid(n), j.rem_euclid(n), seed);
    let top = corner(gx, gy) + (corner(gx + 1, gy) - corner(gx, gy)) * ease(fx);
    let bottom = corner(gx, gy + 1) + (corner(gx + 1, gy + 1) - corner(gx, gy + 1)) * ease(fx);
    top + (bottom - top) * ease(fy)
}

/// Three octaves of tiling value noise in [0, 1).
pub(super) fn fbm(x: usize, y: usize, seed: u32) -> f64 {
    (smooth(x, y, 16, seed) * 4.0 + smooth(x, y, 8, seed + 1) * 2.0 + smooth(x, y, 4, seed + 2))
        / 7.0
}

/// Multiplies a base colour by `k` (around 1.0) and clamps.
pub(super) fn tint(base: (f64, f64, f64), k: f64) -> Rgb {
    let c = |v: f64| (v * k).round().clamp(0.0, 255.0) as u8;
    Rgb::new(c(base.0), c(base.1), c(base.2))
}

/// Running-bond red bricks with light mortar and a bevel on each brick.
#[must_use]
pub fn bricks() -> Texture {
    Texture::from_fn(SIZE, SIZE, |x, y| {
        let row = y / 16;
        let shifted = (x + if row % 2 == 1 { 16 } else { 0 }) % SIZE;
        let (bx, by) = (shifted % 32, y % 16);
        if bx < 2 || by < 2 {
            return tint(
                (182.0, 176.0, 164.0),
                0.85 + 0.25 * white(x as i64, y as i64, 3),
            );
        }
        let brick = hash((shifted / 32) as i64, row as i64, 7);
        let hue = f64::from(brick % 40) - 20.0;
        let base = (158.0 + hue, 66.0 + hue * 0.4, 48.0);
        let mut k = 0.8 + 0.3 * fbm(x, y, 11) + 0.12 * white(x as i64, y as i64, 5);
        if by == 2 || bx == 2 {
            k *= 1.18;
        } else if by == 15 || bx == 31 {
            k *= 0.72;
        }
        tint(base, k)
    })
}

/// Irregular grey stone blocks in two courses with dark joints.
#[must_use]
pub fn stone() -> Texture {
    Texture::from_fn(SIZE, SIZE, |x, y| {
        let course = y / 32;
        let offset = if course == 0 { 0 } else { 21 };
        let widths = [24usize, 18, 22];
        let mut px = (x + offset) % SIZE;
        let mut block = 0;
        while block < widths.len() - 1 && px >= widths[block] {
            px -= widths[block];
            block += 1;
        }
        let py = y % 32;
        let joint = px < 2 || py < 2;
        let n = fbm(x, y, 21);
        if joint {
            return tint((52.0, 50.0, 48.0), 0.8 + 0.4 * n);
        }
        let shade = f64::from(hash(block as i64, course as i64, 23) % 30) / 100.0;
        let bevel = if px == 2 || py == 2 { 1.15 } else { 1.0 };
        tint((128.0, 126.0, 120.0), (0.7 + shade + 0.35 * n) * bevel)
    })
}

/// Vertical planks with wavy grain, dark gaps and two nails each.
#[must_use]
pub fn wood() -> Texture {
    Texture::from_fn(SIZE, SIZE, |x, y| {
        let plank = x / 16;
        let px = x % 16;
        if px == 0 {
            return Rgb::new(40, 26, 16);
        }
        let phase = f64::from(hash(plank as i64, 0, 31) % 100) / 10.0;
        let grain =
            ((y as f64 * 0.18 + px as f64 * 1.3 + fbm(x, y, 33) * 5.0 + phase).sin() + 1.0) / 2.0;
        let nail = (px == 8) && (y % 32 == 4);
        if nail {
            return Rgb::new(60, 60, 64);
        }
        let tone = f64::from(hash(plank as i64, 1, 37) % 20) / 100.0;
        tint((150.0, 100.0, 58.0), 0.72 + tone + 0.28 * grain)
    })
}

/// Blue-grey brushed metal panels with a bevelled border and rivets.
#[must_use]
pub fn metal() -> Texture {
    Texture::from_fn(SIZE, SIZE, |x, y| {
        let (px, py) = (x % 32, y);
        let brushed =
            smooth(x, y / 4 * 4, 4, 41) * 0.08 + white(x as i64, (y / 2) as i64, 43) * 0.06;
        let mut k = 0.92 + brushed;
        if px == 0 || py == 0 {
            k = 1.3;
        } else if px == 31 || py == SIZE - 1 || py == 31 {
            k = 0.55;
        }
        let rivet = [4usize, 27].contains(&px) && [4usize, 27, 36, 59].contains(&py);
        if rivet {
            return Rgb::new(200, 205, 215);
        }
        tint((104.0, 116.0, 134.0), k)
    })
}

/// Stone blocks overgrown with moss, for a second kind of wall.
#[must_use]
pub fn mossy() -> Texture {
    let base = stone();
    Texture::from_fn(SIZE, SIZE, |x, y| {
        let c = base.texel(x, y);
        let moss = fbm(x, y, 51) + (y as f64 / SIZE as f64) * 0.35;
        if moss > 0.72 {
            let k = 0.7 + white(x as i64, y as i64, 53) * 0.4;
            tint((64.0, 110.0, 48.0), k)
        } else {
            c
        }
    })
}

/// Dark square floor tiles with grout, alternating in tone.
#[must_use]
pub fn floor() -> Texture {
    Texture::from_fn(SIZE, SIZE, |x, y| {
        let (tx, ty) = (x / 32, y / 32);
        let (px, py) = (x % 32, y % 32);
        if px < 1 || py < 1 {
            return Rgb::new(40, 38, 36);
        }
        let alt = if (tx + ty) % 2 == 0 { 1.0 } else { 0.82 };
        let n = fbm(x, y, 61);
        tint((120.0, 108.0, 94.0), alt * (0.75 + 0.4 * n))
    })
}

/// Pale plaster ceiling panels with faint seams.
#[must_use]
pub fn ceiling() -> Texture {
    Texture::from_fn(SIZE, SIZE, |x, y| {
        let seam = x % 32 == 0 || y % 32 == 0;
        let n = fbm(x, y, 71);
        let k = if seam { 0.7 } else { 0.85 + 0.2 * n };
        tint((150.0, 146.0, 136.0), k)
    })
}

/// A sliding steel door: two recessed panels, rivets, a handle slot and a warning stripe.
#[must_use]
pub fn door() -> Texture {
    Texture::from_fn(SIZE, SIZE, |x, y| {
        let brushed = smooth(x, y / 2 * 2, 4, 81) * 0.1 + white(x as i64, y as i64, 83) * 0.05;
        let frame = !(3..SIZE - 3).contains(&x) || !(3..SIZE - 3).contains(&y);
        if frame {
            return tint((70.0, 74.0, 82.0), 0.9 + brushed);
        }
        let in_panel = |y0: usize, y1: usize| (8..56).contains(&x) && (y0..y1).contains(&y);
        if (28..34).contains(&y) {
            // Hazard stripe across the middle.
            let band = (x + y) / 4 % 2 == 0;
            return if band {
                tint((210.0, 170.0, 40.0), 0.95 + brushed)
            } else {
                tint((40.0, 38.0, 36.0), 1.0 + brushed)
            };
        }
        if (50..54).contains(&x) && (38..48).contains(&y) {
            return Rgb::new(24, 24, 28);
        }
        let rivet = [5usize, 58].contains(&x) && [6usize, 20, 44, 58].contains(&y);
        if rivet {
            return Rgb::new(190, 196, 204);
        }
        let mut k = 0.95 + brushed;
        if in_panel(8, 24) || in_panel(38, 56) {
            k *= 0.82;
            if x == 8 || y == 8 || y == 38 {
                k *= 0.7;
            } else if x == 55 || y == 23 || y == 55 {
                k *= 1.3;
            }
        }
        tint((120.0, 128.0, 140.0), k)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generation_is_deterministic() {
        for (name, f) in ALL {
            assert_eq!(f(), f(), "{name}");
        }
    }

    #[test]
    fn textures_are_not_flat() {
        for (name, f) in ALL {
            let t = f();
            let first = t.texel(0, 0);
            let distinct = (0..SIZE)
                .flat_map(|x| (0..SIZE).map(move |y| (x, y)))
                .filter(|&(x, y)| t.texel(x, y) != first)
                .count();
            assert!(distinct > SIZE * SIZE / 4, "{name} is too flat");
        }
    }
}
