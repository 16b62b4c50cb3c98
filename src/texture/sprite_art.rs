//! Procedural sprite sheets: a barrel, a pillar, a hanging lamp, a potted plant and an 8-view
//! walking creature (the game's pickups are in `super::pickup_art`), drawn with simple shapes and shaded as if round. Deterministic, like
//! [`super::generate`].

use super::generate::{fbm, tint, white};
use super::pickup_art;
use super::sheet::SpriteSheet;
use crate::color::Rgb;

pub use super::ART_SIZE as SIZE;

/// Views and frames in the creature's sheet.
pub const CREATURE_VIEWS: usize = 8;
/// Animation frames per view in the creature's sheet.
pub const CREATURE_FRAMES: usize = 4;

/// A sprite-sheet generator: no inputs, same sheet every time.
pub type SheetGenerator = fn() -> SpriteSheet;

/// Every generated sprite with the file stem it is saved under in `textures/sprites/`.
pub const ALL: [(&str, SheetGenerator); 9] = [
    ("barrel", barrel),
    ("pillar", pillar),
    ("lamp", lamp),
    ("plant", plant),
    ("creature", creature),
    ("treasure", pickup_art::treasure),
    ("key", pickup_art::key),
    ("exit", pickup_art::exit),
    ("orb", pickup_art::orb),
];

const CLEAR: (Rgb, u8) = (Rgb::new(0, 0, 0), 0);

/// Brightness across a cylinder seen side-on: u in [−1, 1] from left to right edge,
/// lit from the front-left.
fn cylinder(u: f64) -> f64 {
    let nz = (1.0 - u * u).max(0.0).sqrt();
    0.35 + 0.55 * (nz * 0.8 - u * 0.45).max(0.0) + 0.15 * nz.powi(8)
}

/// A wooden barrel with two iron hoops, standing on the bottom edge.
#[must_use]
pub fn barrel() -> SpriteSheet {
    SpriteSheet::from_fn(SIZE, SIZE, |x, y| {
        if y < 22 {
            return CLEAR;
        }
        let t = (y as f64 - 22.0) / 42.0;
        let half = 17.0 * (0.86 + 0.14 * (std::f64::consts::PI * t).sin());
        let u = (x as f64 + 0.5 - 32.0) / half;
        if u.abs() > 1.0 {
            return CLEAR;
        }
        let k = cylinder(u);
        let hoop = (0.12..0.2).contains(&t) || (0.8..0.88).contains(&t);
        if hoop {
            return (tint((86.0, 88.0, 94.0), k * 1.1), 255);
        }
        let stave = ((u.asin() * 6.0 / std::f64::consts::PI) + 3.0).fract();
        let seam = !(0.06..0.94).contains(&stave);
        let grain = fbm(x, y * 3 % SIZE, 91) * 0.25;
        let base = if seam {
            (70.0, 42.0, 22.0)
        } else {
            (150.0, 96.0, 52.0)
        };
        (tint(base, k * (0.85 + grain)), 255)
    })
}

/// A full-height fluted stone column with a wider capital and base.
#[must_use]
pub fn pillar() -> SpriteSheet {
    SpriteSheet::from_fn(SIZE, SIZE, |x, y| {
        let half = if !(6..SIZE - 6).contains(&y) {
            19.0
        } else if !(9..SIZE - 9).contains(&y) {
            16.0
        } else {
            13.0
        };
        let u = (x as f64 + 0.5 - 32.0) / half;
        if u.abs() > 1.0 {
            return CLEAR;
        }
        let mut k = cylinder(u) * (0.85 + 0.3 * fbm(x, y, 95));
        let shaft = (9..SIZE - 9).contains(&y);
        if shaft && ((u.asin() * 8.0 / std::f64::consts::PI) + 4.0).fract() < 0.25 {
            k *= 0.75;
        }
        if y == 5 || y == 8 || y == SIZE - 9 || y == SIZE - 6 {
            k *= 0.6;
        }
        (tint((176.0, 170.0, 156.0), k), 255)
    })
}

/// A lamp on a chain: dark shade, bright bulb and a soft halo (partial alpha).
/// Meant to hang from the ceiling (`SPRITE x,y lamp scale=0.5 hang`).
#[must_use]
pub fn lamp() -> SpriteSheet {
    SpriteSheet::from_fn(SIZE, SIZE, |x, y| {
        let (fx, fy) = (x as f64 + 0.5, y as f64 + 0.5);
        let dx = fx - 32.0;
        // The bulb and its halo.
        let bulb = (dx * dx + (fy - 42.0) * (fy - 42.0)).sqrt();
        if y < 24 && (31..33).contains(&x) {
            let link = if y % 4 < 2 { 1.0 } else { 0.7 };
            return (tint((120.0, 116.0, 100.0), link), 255);
        }
        if (24..38).contains(&y) {
            let t = (fy - 24.0) / 14.0;
            let half = 5.0 + 13.0 * t;
            let u = dx / half;
            if u.abs() <= 1.0 {
                let rim = if y == 37 { 1.3 } else { 1.0 };
                return (tint((60.0, 110.0, 70.0), cylinder(u) * rim), 255);
            }
        }
        if bulb < 5.0 {
            return (Rgb::new(255, 244, 200), 255);
        }
        if bulb < 14.0 && y >= 36 {
            let a = ((14.0 - bulb) / 9.0).powi(2) * 160.0;
            return (Rgb::new(255, 226, 140), a.round() as u8);
        }
        CLEAR
    })
}

/// A potted plant: a terracotta pot and a fan of long leaves.
#[must_use]
pub fn plant() -> SpriteSheet {
    // Leaves: (angle from vertical in degrees, length in pixels).
    const LEAVES: [(f64, f64); 9] = [
        (-62.0, 22.0),
        (-44.0, 30.0),
        (-26.0, 34.0),
        (-10.0, 38.0),
        (4.0, 40.0),
        (18.0, 36.0),
        (34.0, 31.0),
        (50.0, 27.0),
        (66.0, 21.0),
    ];
    SpriteSheet::from_fn(SIZE, SIZE, |x, y| {
        let (fx, fy) = (x as f64 + 0.5, y as f64 + 0.5);
        if y >= 46 {
            let t = (fy - 46.0) / 18.0;
            let half = 12.0 - 3.0 * t;
            let u = (fx - 32.0) / half;
            if u.abs() <= 1.0 {
                let rim = if y < 49 { 1.2 } else { 1.0 };
                return (tint((176.0, 92.0, 56.0), cylinder(u) * rim), 255);
            }
            return CLEAR;
        }
        let base = (32.0, 47.0);
        for (i, &(deg, len)) in LEAVES.iter().enumerate() {
            let a = f64::to_radians(deg);
            let (dx, dy) = (a.sin(), -a.cos());
            let (px, py) = (fx - base.0, fy - base.1);
            let along = px * dx + py * dy;
            if !(0.0..=len).contains(&along) {
                continue;
            }
            // Droop: the tip bends down a little, more for wide leaves.
            let droop = (along / len).powi(2) * 6.0 * a.sin().abs();
            let across2 = px * -dy + (py - droop) * dx;
            let width = 3.6 * (std::f64::consts::PI * along / len).sin() + 0.6;
            if across2.abs() <= width {
                let vein = across2.abs() < 0.6;
                let tone = 0.75 + 0.1 * (i % 3) as f64 + 0.2 * white(x as i64, y as i64, 97);
                let shade = if across2 > 0.0 { 0.85 } else { 1.05 };
                let c = if vein {
                    tint((150.0, 190.0, 90.0), tone)
                } else {
                    tint((52.0, 132.0, 58.0), tone * shade)
                };
                return (c, 255);
            }
        }
        CLEAR
    })
}

/// A small RGBA canvas for layering shapes (the creature is drawn back to front).
struct Canvas {
    px: Vec<(Rgb, u8)>,
}

impl Canvas {
    fn new() -> Self {
        Self {
            px: vec![CLEAR; SIZE * SIZE],
        }
    }

    /// Fills an ellipse, colouring each pixel by its normalised offset (nx, ny) in [−1, 1].
    fn ellipse(&mut self, cx: f64, cy: f64, rx: f64, ry: f64, paint: impl Fn(f64, f64) -> Rgb) {
        if rx <= 0.0 || ry <= 0.0 {
            return;
        }
        for y in 0..SIZE {
            for x in 0..SIZE {
                let nx = (x as f64 + 0.5 - cx) / rx;
                let ny = (y as f64 + 0.5 - cy) / ry;
                if nx * nx + ny * ny <= 1.0 {
                    self.px[y * SIZE + x] = (paint(nx, ny), 255);
                }
            }
        }
    }
}

/// Sphere-like shading for a normalised offset: lit from the upper front-left.
fn sphere(nx: f64, ny: f64) -> f64 {
    let nz = (1.0 - nx * nx - ny * ny).max(0.0).sqrt();
    let l = (-0.4 * nx - 0.5 * ny + 0.77 * nz).max(0.0);
    0.3 + 0.75 * l
}

/// One picture of the creature: seen from `view` (0 = front, counter-clockwise in 45° steps)
/// at walk-cycle `frame`.
fn creature_picture(view: usize, frame: usize) -> Canvas {
    use std::f64::consts::{FRAC_PI_2, PI, TAU};
    let mut c = Canvas::new();
    let theta = view as f64 * PI / 4.0;
    let phase = frame as f64 / CREATURE_FRAMES as f64 * TAU;
    let bob = phase.sin().abs() * 2.0;
    let (cx, cy, rx, ry) = (32.0, 36.0 - bob, 15.0, 16.0);
    // A feature at azimuth phi (0 = front, +90° = the creature's left) lands at this x offset
    // and faces the viewer by `facing` (> 0 = visible).
    let place = |phi: f64| ((phi - theta).sin(), (phi - theta).cos());
    // Feet first (always below the body), lifting in turn.
    for (side, lift_phase) in [(FRAC_PI_2, 0.0), (-FRAC_PI_2, PI)] {
        let (s, _) = place(side);
        let lift = (phase + lift_phase).sin().max(0.0) * 4.0;
        let fx = cx + s * 8.0;
        c.ellipse(fx, 57.5 - lift, 6.0, 3.5, |nx, ny| {
            tint((76.0, 54.0, 96.0), sphere(nx, ny))
        });
    }
    // The tail, behind the body unless seen from behind.
    let (ts, tf) = place(PI);
    let tail = |c: &mut Canvas| {
        c.ellipse(cx + ts * (rx + 1.0), cy + 8.0, 5.0, 5.0, |nx, ny| {
            tint((250.0, 150.0, 60.0), sphere(nx, ny))
        });
    };
    if tf <= 0.0 {
        tail(&mut c);
    }
    // Arms: far arm behind the body, near arm in front; they swing with the walk.
    let arms = [(FRAC_PI_2, 0.0), (-FRAC_PI_2, PI)];
    let arm = |c: &mut Canvas, side: f64, swing_phase: f64| {
        let (s, _) = place(side);
        let swing = (phase + swing_phase).sin() * 3.0;
        c.ellipse(cx + s * (rx + 1.0), cy + 2.0 + swing, 4.0, 6.0, |nx, ny| {
            tint((110.0, 76.0, 170.0), sphere(nx, ny))
        });
    };
    for &(side, sp) in &arms {
        if place(side).1 < 0.0 {
            arm(&mut c, side, sp);
        }
    }
    // Antenna stalk and a ball that blinks with the frame.
    for y in 12..20 {
        c.px[y * SIZE + 32] = (Rgb::new(60, 50, 70), 255);
    }
    let glow = if frame.is_multiple_of(2) { 1.1 } else { 0.7 };
    c.ellipse(32.5, 11.0 - bob, 3.0, 3.0, |nx, ny| {
        tint((250.0, 220.0, 80.0), sphere(nx, ny) * glow)
    });
    // Body.
    c.ellipse(cx, cy, rx, ry, |nx, ny| {
        tint((132.0, 88.0, 200.0), sphere(nx, ny))
    });
    // Belly patch on the front, foreshortened with the view.
    let (bs, bf) = place(0.0);
    if bf > 0.1 {
        c.ellipse(cx + bs * rx * 0.6, cy + 6.0, 7.0 * bf, 7.0, |nx, ny| {
            tint((210.0, 180.0, 236.0), sphere(nx * 0.5, ny * 0.5) * 0.95)
        });
    }
    if tf > 0.0 {
        tail(&mut c);
    }
    // Eyes at ±28° from the front, above the middle; squashed when seen at an angle.
    for side in [0.5f64, -0.5] {
        let (s, f) = place(side);
        if f > 0.15 {
            let ex = cx + s * rx * 0.92;
            let ey = cy - 5.0;
            c.ellipse(ex, ey, 4.0 * f, 4.5, |_, _| Rgb::new(246, 246, 240));
            c.ellipse(ex + s * 1.0, ey + 0.5, 2.0 * f, 2.4, |_, _| {
                Rgb::new(20, 16, 30)
            });
        }
    }
    for &(side, sp) in &arms {
        if place(side).1 >= 0.0 {
            arm(&mut c, side, sp);
        }
    }
    c
}

/// The creature: 8 views (left to right: front, then counter-clockwise) × 4 walk frames (top to
/// bottom), each 64 × 64. Use with `views=8 frames=4 fps=...`.
#[must_use]
pub fn creature() -> SpriteSheet {
    let pictures: Vec<Vec<Canvas>> = (0..CREATURE_FRAMES)
        .map(|f| {
            (0..CREATURE_VIEWS)
                .map(|v| creature_picture(v, f))
                .collect()
        })
        .collect();
    SpriteSheet::from_fn(SIZE * CREATURE_VIEWS, SIZE * CREATURE_FRAMES, |x, y| {
        pictures[y / SIZE][x / SIZE].px[(y % SIZE) * SIZE + x % SIZE]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generation_is_deterministic_and_has_both_clear_and_solid_texels() {
        for (name, f) in ALL {
            let s = f();
            assert_eq!(s, f(), "{name}");
            let mut clear = 0;
            let mut solid = 0;
            for x in 0..s.width() {
                for y in 0..s.height() {
                    match s.texel(x, y).1 {
                        0 => clear += 1,
                        255 => solid += 1,
                        _ => {}
                    }
                }
            }
            assert!(
                clear > 100 && solid > 100,
                "{name}: {clear} clear, {solid} solid"
            );
        }
    }

    #[test]
    fn the_eight_creature_views_differ() {
        let s = creature();
        let picture = |v: usize| -> Vec<(Rgb, u8)> {
            (0..SIZE * SIZE)
                .map(|i| s.texel(v * SIZE + i % SIZE, i / SIZE))
                .collect()
        };
        for a in 0..CREATURE_VIEWS {
            for b in a + 1..CREATURE_VIEWS {
                assert_ne!(picture(a), picture(b), "views {a} and {b}");
            }
        }
    }
}
