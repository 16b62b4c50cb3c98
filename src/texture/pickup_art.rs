//! Procedural sprites for the game's objects: a treasure chest, a key (drawn pale so a map's
//! key colour can tint it), the exit's glowing arch and the tag projectile's orb. Deterministic,
//! like the rest of [`super::sprite_art`].

use super::generate::{fbm, tint, white};
use super::sheet::SpriteSheet;
use super::ART_SIZE as SIZE;
use crate::color::Rgb;

const CLEAR: (Rgb, u8) = (Rgb::new(0, 0, 0), 0);

/// Gold, the colour treasure reads as at a glance.
const GOLD: (f64, f64, f64) = (236.0, 184.0, 60.0);

/// A small wooden chest with gold bands and a lid bulging with coins, standing on the bottom edge.
#[must_use]
pub fn treasure() -> SpriteSheet {
    SpriteSheet::from_fn(SIZE, SIZE, |x, y| {
        let (fx, fy) = (x as f64 + 0.5, y as f64 + 0.5);
        let u = (fx - 32.0) / 20.0;
        if u.abs() > 1.0 || y < 22 {
            return CLEAR;
        }
        // Coins heaped above the lid: a half ellipse with glints.
        let heap = (1.0 - u * u).sqrt() * 8.0;
        if fy < 32.0 {
            if fy < 32.0 - heap {
                return CLEAR;
            }
            let glint = white(x as i64 / 2, y as i64 / 2, 41) > 0.8;
            let k = if glint {
                1.25
            } else {
                0.8 + 0.3 * fbm(x, y, 43)
            };
            return (tint(GOLD, k), 255);
        }
        let side = 0.75 + 0.35 * (1.0 - u.abs());
        // Lid rim, bands, and the lock plate in the middle.
        let band = (32..36).contains(&y) || (u.abs() > 0.78 && u.abs() <= 0.92);
        let plate = (fx - 32.0).abs() < 4.0 && (36.0..44.0).contains(&fy);
        if band || plate {
            let keyhole = plate && (fx - 32.0).abs() < 1.0 && (38.0..42.0).contains(&fy);
            if keyhole {
                return (Rgb::new(30, 20, 10), 255);
            }
            return (tint(GOLD, side), 255);
        }
        let plank = if (y - 36) % 7 == 0 { 0.7 } else { 1.0 };
        let grain = 0.85 + 0.3 * fbm(x, y * 3 % SIZE, 47);
        (tint((128.0, 74.0, 36.0), side * plank * grain), 255)
    })
}

/// A key standing on its tip, in pale metal: the bow's ring on top, the bit on the right.
#[must_use]
pub fn key() -> SpriteSheet {
    SpriteSheet::from_fn(SIZE, SIZE, |x, y| {
        let (fx, fy) = (x as f64 + 0.5, y as f64 + 0.5);
        let (dx, dy) = (fx - 32.0, fy - 20.0);
        let r = (dx * dx + dy * dy).sqrt();
        // Shading: lit from the upper left.
        let lit = |nx: f64, ny: f64| 0.75 + 0.3 * (-0.6 * nx - 0.8 * ny).clamp(-1.0, 1.0);
        if (5.5..11.0).contains(&r) {
            let k = lit(dx / r, dy / r);
            return (tint((235.0, 232.0, 222.0), k), 255);
        }
        let shaft = (fx - 32.0).abs() < 2.5 && (30.0..60.0).contains(&fy);
        let bit = (34.5..42.0).contains(&fx)
            && ((46.0..50.0).contains(&fy) || (53.0..57.0).contains(&fy));
        if shaft || bit {
            let k = if shaft {
                lit((fx - 32.0) / 2.5, 0.0)
            } else {
                0.9
            };
            return (tint((235.0, 232.0, 222.0), k), 255);
        }
        CLEAR
    })
}

/// The exit: a stone arch around a glowing green doorway (partly transparent, so the room
/// behind shows through the glow).
#[must_use]
pub fn exit() -> SpriteSheet {
    SpriteSheet::from_fn(SIZE, SIZE, |x, y| {
        let (fx, fy) = (x as f64 + 0.5, y as f64 + 0.5);
        let dx = fx - 32.0;
        // The opening: a rectangle below a half circle of radius 16 centred at y = 22.
        let inside = |half: f64| {
            dx.abs() <= half && (fy >= 22.0 || dx * dx + (fy - 22.0).powi(2) <= half * half)
        };
        if inside(16.0) && fy > 6.0 {
            let edge = 1.0 - (dx.abs() / 16.0).powi(2);
            let wave = 0.5 + 0.5 * ((fy * 0.35) + dx * 0.1).sin();
            let a = (90.0 + 120.0 * edge * (0.6 + 0.4 * wave)).round() as u8;
            return (tint((120.0, 255.0, 150.0), 0.7 + 0.3 * wave), a);
        }
        if inside(22.0) && fy > 0.0 {
            let stone = 0.7 + 0.4 * fbm(x, y, 53);
            let joint = (y % 8 == 0) || ((x + if (y / 8) % 2 == 0 { 0 } else { 4 }) % 8 == 0);
            let k = if joint { stone * 0.6 } else { stone };
            return (tint((150.0, 146.0, 138.0), k), 255);
        }
        CLEAR
    })
}

/// The tag projectile: a white-hot core in a soft yellow halo that fades to nothing.
#[must_use]
pub fn orb() -> SpriteSheet {
    SpriteSheet::from_fn(SIZE, SIZE, |x, y| {
        let (dx, dy) = (x as f64 + 0.5 - 32.0, y as f64 + 0.5 - 32.0);
        let r = (dx * dx + dy * dy).sqrt() / 32.0;
        if r >= 1.0 {
            return CLEAR;
        }
        if r < 0.25 {
            return (Rgb::new(255, 252, 236), 255);
        }
        let fade = ((1.0 - r) / 0.75).powf(1.6);
        (
            tint((255.0, 214.0, 96.0), 0.8 + 0.2 * fade),
            (fade * 255.0).round() as u8,
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn coloured(sheet: &SpriteSheet, pick: impl Fn(Rgb) -> bool) -> usize {
        let mut n = 0;
        for x in 0..sheet.width() {
            for y in 0..sheet.height() {
                let (c, a) = sheet.texel(x, y);
                if a > 0 && pick(c) {
                    n += 1;
                }
            }
        }
        n
    }

    #[test]
    fn treasure_reads_as_gold_and_the_key_is_pale_so_a_tint_shows() {
        let gold = coloured(&treasure(), |c| c.r > 180 && c.g > 130 && c.b < 90);
        assert!(gold > 300, "{gold} gold texels");
        let key = key();
        let pale = coloured(&key, |c| {
            let (hi, lo) = (c.r.max(c.g).max(c.b), c.r.min(c.g).min(c.b));
            hi > 90 && hi - lo < 24
        });
        let any = coloured(&key, |_| true);
        assert!(any > 200 && pale * 10 >= any * 9, "{pale} pale of {any}");
    }

    #[test]
    fn the_exit_glows_through_and_the_orb_fades_out() {
        let exit = exit();
        let (_, mid) = exit.texel(32, 40);
        assert!(
            (1..255).contains(&mid),
            "the doorway is see-through glow: {mid}"
        );
        let (_, frame) = exit.texel(12, 40);
        assert_eq!(frame, 255, "the arch is solid");
        let orb = orb();
        let alpha = |x| orb.texel(x, 32).1;
        assert_eq!(alpha(32), 255);
        assert!(alpha(50) < alpha(40) && alpha(40) < 255 && alpha(63) < 8);
    }
}
