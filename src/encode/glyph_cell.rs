//! One cell's glyph and two colours: which of its 4, 6 or 8 pixels show the foreground, and
//! the two colours that keep the cell closest to its pixels.
//!
//! Colours are mixed in linear light: a group's colour is the mean light of its pixels, and the
//! split is judged there too, by squared distances with each channel weighted for how much it
//! counts ([`WEIGHT`]). Quadrants and sextants try every split (7 and 31); octants use a 2-means:
//! start from the darkest and the brightest pixel, assign each pixel to the nearer colour, move each colour to
//! its group's mean, and repeat until nothing moves (a few rounds over ≤ 8 pixels). Cells of
//! one or two distinct colours are exact without any of that.
//!
//! Everything runs from tables built once (sRGB ↔ linear light), with no cube roots or powers
//! per pixel: this runs for every cell of every frame.

use crate::color::{channel_to_linear, lab_dist2, oklab, Linear, Rgb};

/// Most pixels a cell has (octants: 2×4).
pub const MAX_PIXELS: usize = 8;

/// A cell as the terminal draws it: `mask`'s set bits (see [`super::glyph_mask`]) show `fg`,
/// the others `bg`. Canonical: bit 0 is clear (pixel 0 shows `bg`), and a cell of one colour
/// has mask 0 and `fg == bg`, so equal pictures are equal cells.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct GlyphCell {
    /// Which pixels show the foreground.
    pub mask: u8,
    /// The glyph's ink.
    pub fg: Rgb,
    /// The cell's paper.
    pub bg: Rgb,
}

impl GlyphCell {
    /// A cell of one colour.
    #[must_use]
    pub fn uniform(c: Rgb) -> Self {
        Self {
            mask: 0,
            fg: c,
            bg: c,
        }
    }

    /// The colour pixel `i` shows.
    #[must_use]
    #[inline]
    pub fn pixel(&self, i: usize) -> Rgb {
        if self.mask & (1 << i) != 0 {
            self.fg
        } else {
            self.bg
        }
    }

    /// The same picture in canonical form (see the type's doc) for a cell of `n` pixels.
    #[must_use]
    pub fn canonical(self, n: usize) -> Self {
        let (mask, fg, bg) = canonical(self.mask, self.fg, self.bg, n);
        Self { mask, fg, bg }
    }
}

/// A two-colour cell of `n` pixels (`mask`'s set bits show `fg`) in canonical form, whatever its
/// colours are (RGB or palette codes): bit 0 clear, and one colour as mask 0 with `fg == bg`, so
/// equal pictures are equal cells.
#[must_use]
pub fn canonical<T: PartialEq + Copy>(mask: u8, fg: T, bg: T, n: usize) -> (u8, T, T) {
    let full = ((1u16 << n) - 1) as u8;
    let mask = mask & full;
    if mask == 0 || fg == bg {
        (0, bg, bg)
    } else if mask == full {
        (0, fg, fg)
    } else if mask & 1 != 0 {
        (!mask & full, bg, fg)
    } else {
        (mask, fg, bg)
    }
}

/// The cell (canonical) that best shows `pixels` (row-major, 1 to [`MAX_PIXELS`]) with two
/// colours.
#[must_use]
pub fn choose(pixels: &[Rgb]) -> GlyphCell {
    let n = pixels.len().min(MAX_PIXELS);
    match n {
        0 => GlyphCell::default(),
        1 => choose_n::<1>(pixels),
        2 => choose_n::<2>(pixels),
        3 => choose_n::<3>(pixels),
        4 => choose_n::<4>(pixels),
        5 => choose_n::<5>(pixels),
        6 => choose_n::<6>(pixels),
        7 => choose_n::<7>(pixels),
        _ => choose_n::<8>(pixels),
    }
}

/// [`choose`] for exactly `N` pixels (the first `N` of `pixels`): with the count known, every
/// loop over the pixels unrolls.
#[must_use]
#[inline]
pub fn choose_n<const N: usize>(pixels: &[Rgb]) -> GlyphCell {
    let pixels: &[Rgb; N] = pixels[..N].try_into().expect("N pixels");
    let first = pixels[0];
    // One or two distinct colours: the split is exact.
    let Some(other) = pixels.iter().copied().find(|&c| c != first) else {
        return GlyphCell::uniform(first);
    };
    if pixels.iter().all(|&c| c == first || c == other) {
        let mask = mask_where(pixels, |c| c == other);
        return GlyphCell {
            mask,
            fg: other,
            bg: first,
        };
    }
    let t = tables();
    let lin: [Linear; N] = std::array::from_fn(|i| {
        let c = pixels[i];
        [
            t.linear[usize::from(c.r)],
            t.linear[usize::from(c.g)],
            t.linear[usize::from(c.b)],
        ]
    });
    let mask = if N <= 6 {
        best_split(&lin)
    } else {
        two_means(&lin)
    };
    let (bg, fg) = means(&lin, mask);
    GlyphCell {
        mask,
        fg: t.to_srgb(fg),
        bg: t.to_srgb(bg),
    }
    .canonical(N)
}

/// The bits of the pixels for which `f` holds.
fn mask_where(pixels: &[Rgb], f: impl Fn(Rgb) -> bool) -> u8 {
    pixels
        .iter()
        .enumerate()
        .filter(|&(_, &c)| f(c))
        .fold(0u8, |m, (i, _)| m | (1 << i))
}

/// How much each channel of linear light counts when pixels are split: roughly the square roots
/// of their shares of luminance, so green differences weigh most and blue least. Measured on the
/// bench's walk path, splitting in this space keeps S-CIELAB at least as low as splitting in
/// OKLab, for none of OKLab's cube roots.
const WEIGHT: [f32; 3] = [0.25, 0.64, 0.1225];

/// The split of ≥ 3 distinct colours (see the module doc): seeds are the darkest and the
/// brightest pixel; then each pixel goes to the nearer group centre and the centres move to
/// their groups' means until nothing moves. The pixels are held channel by channel, so each
/// step runs over all of them at once.
fn two_means<const N: usize>(lin: &[Linear; N]) -> u8 {
    let full = ((1u16 << N) - 1) as u8;
    let ch: [[f32; N]; 3] = [0, 1, 2].map(|c| lin.map(|l| l[c]));
    // Seeds: the darkest and the brightest pixel (weighted light), found in one pass.
    let mut light = [0.0f32; N];
    for i in 0..N {
        light[i] = WEIGHT[0] * ch[0][i] + WEIGHT[1] * ch[1][i] + WEIGHT[2] * ch[2][i];
    }
    let (mut a, mut b) = (0, 0);
    for i in 1..N {
        if light[i] < light[a] {
            a = i;
        }
        if light[i] > light[b] {
            b = i;
        }
    }
    if a == b {
        // Equal light, different colours: the pixel farthest from the first.
        let mut far = 0.0f32;
        for (i, l) in lin.iter().enumerate() {
            let d = [0, 1, 2].map(|c| l[c] - lin[0][c]);
            let d = WEIGHT[0] * d[0] * d[0] + WEIGHT[1] * d[1] * d[1] + WEIGHT[2] * d[2] * d[2];
            if d > far {
                (b, far) = (i, d);
            }
        }
    }
    // The pixels nearer `cb` than `ca`: those on `cb`'s side of the plane halfway between.
    let nearer_b = |ca: Linear, cb: Linear| {
        let axis = [0, 1, 2].map(|c| WEIGHT[c] * (cb[c] - ca[c]));
        let mid = [0, 1, 2].map(|c| (ca[c] + cb[c]) / 2.0);
        let mut side = [0.0f32; N];
        for (i, s) in side.iter_mut().enumerate() {
            *s = axis[0] * (ch[0][i] - mid[0])
                + axis[1] * (ch[1][i] - mid[1])
                + axis[2] * (ch[2][i] - mid[2]);
        }
        let mut mask = 0u8;
        for (i, &s) in side.iter().enumerate() {
            mask |= u8::from(s > 0.0) << i;
        }
        mask
    };
    let (mut ca, mut cb) = (lin[a], lin[b]);
    let mut mask = 0u8;
    for _ in 0..4 {
        let mut next = nearer_b(ca, cb);
        if next == 0 {
            // Every pixel nearer `a`'s centre: the far seed keeps its own pixel.
            next = 1 << b;
        } else if next == full {
            next = full & !(1 << a);
        }
        if next == mask {
            break;
        }
        mask = next;
        (ca, cb) = means(lin, mask);
    }
    mask
}

/// The best split of a few pixels (quadrants: 7 candidates, sextants: 31) by trying each:
/// the one whose groups' means leave the least weighted squared error. That error is the total
/// square less each group's |sum|² / size, so the best split has the largest sum of those.
/// Pixel 0 stays on the background side (canonical form), so each split is tried once. The
/// foreground sums of all splits are built by doubling (split `j + h` is split `j` plus pixel
/// `p`, `h` = 2^(p−1)), then all scores are computed side by side.
fn best_split<const N: usize>(lin: &[Linear; N]) -> u8 {
    let m = 1usize << (N - 1);
    assert!(m <= SPLITS, "best_split takes at most six pixels");
    let mut set = [[0.0f32; SPLITS]; 3];
    for (p, l) in lin.iter().enumerate().skip(1) {
        let h = 1 << (p - 1);
        for c in 0..3 {
            for j in 0..h {
                set[c][j + h] = set[c][j] + l[c];
            }
        }
    }
    let total: Linear = [0, 1, 2].map(|c| set[c][m - 1] + lin[0][c]);
    let (inv_set, inv_rest) = (&GroupSizes::<N>::INV_SET, &GroupSizes::<N>::INV_REST);
    let mut score = [0.0f32; SPLITS];
    for j in 0..m {
        let (s, r) = (
            [set[0][j], set[1][j], set[2][j]],
            [0, 1, 2].map(|c| total[c] - set[c][j]),
        );
        let norm =
            |v: Linear| WEIGHT[0] * v[0] * v[0] + WEIGHT[1] * v[1] * v[1] + WEIGHT[2] * v[2] * v[2];
        score[j] = norm(s) * inv_set[j] + norm(r) * inv_rest[j];
    }
    let mut best = 1;
    for j in 2..m {
        if score[j] > score[best] {
            best = j;
        }
    }
    (best << 1) as u8
}

/// Most splits [`best_split`] tries: sextants' 2^5 (the empty one included).
const SPLITS: usize = 32;

/// 1 / the size of each group of split `j` of `N` pixels (`j` = the mask without pixel 0),
/// worked out at compile time.
struct GroupSizes<const N: usize>;

impl<const N: usize> GroupSizes<N> {
    /// 1 / the foreground's size (0 for the empty split, which is never best).
    const INV_SET: [f32; SPLITS] = {
        let mut t = [0.0f32; SPLITS];
        let mut j = 1;
        while j < SPLITS {
            t[j] = 1.0 / j.count_ones() as f32;
            j += 1;
        }
        t
    };
    /// 1 / the background's size (pixel 0 and the rest).
    const INV_REST: [f32; SPLITS] = {
        let mut t = [0.0f32; SPLITS];
        let mut j = 0;
        while j < SPLITS {
            let rest = N as i64 - j.count_ones() as i64;
            t[j] = if rest > 0 { 1.0 / rest as f32 } else { 0.0 };
            j += 1;
        }
        t
    };
}

/// The means of the colours whose bit is clear in `mask` and of those whose bit is set (each
/// black when its group is empty).
#[inline]
fn means<const N: usize>(lin: &[Linear; N], mask: u8) -> (Linear, Linear) {
    let (mut all, mut set) = ([0.0f32; 3], [0.0f32; 3]);
    for (i, l) in lin.iter().enumerate() {
        let m = f32::from(mask >> i & 1);
        for c in 0..3 {
            all[c] += l[c];
            set[c] += m * l[c];
        }
    }
    let k = (mask & ((1u16 << N) - 1) as u8).count_ones() as f32;
    let rest = N as f32 - k;
    (
        [0, 1, 2].map(|c| (all[c] - set[c]) / rest.max(1.0)),
        set.map(|v| v / k.max(1.0)),
    )
}

/// The sRGB transfer curve both ways, built once: 8-bit channel → linear light, and back.
struct Tables {
    /// Each 8-bit value in linear light.
    linear: [f32; 256],
    /// `upper[v]`: the linear light halfway between `v` and `v + 1`, where rounding back turns
    /// from one to the other.
    upper: [f32; 256],
    /// A first guess of the value nearest a linear light `x`, at `x` · 4095.
    guess: [u8; 4096],
}

fn tables() -> &'static Tables {
    static TABLES: std::sync::OnceLock<Box<Tables>> = std::sync::OnceLock::new();
    TABLES.get_or_init(|| {
        let mut t = Box::new(Tables {
            linear: [0.0; 256],
            upper: [f32::INFINITY; 256],
            guess: [0; 4096],
        });
        for v in 0..=255u8 {
            t.linear[usize::from(v)] = channel_to_linear(v);
        }
        for v in 0..255 {
            t.upper[v] = (t.linear[v] + t.linear[v + 1]) / 2.0;
        }
        let mut v = 0usize;
        for (i, g) in t.guess.iter_mut().enumerate() {
            let x = i as f32 / 4095.0;
            while v < 255 && t.upper[v] < x {
                v += 1;
            }
            *g = v as u8;
        }
        t
    })
}

impl Tables {
    /// Linear light back to the nearest 8-bit sRGB colour: the guess, then a step or two
    /// along the curve's midpoints.
    #[inline]
    fn to_srgb(&self, l: Linear) -> Rgb {
        let ch = |x: f32| -> u8 {
            let x = x.clamp(0.0, 1.0);
            let mut v = usize::from(self.guess[((x * 4095.0) as usize).min(4095)]);
            while v < 255 && x > self.upper[v] {
                v += 1;
            }
            while v > 0 && x < self.upper[v - 1] {
                v -= 1;
            }
            v as u8
        };
        Rgb::new(ch(l[0]), ch(l[1]), ch(l[2]))
    }
}

/// The OKLab error of showing `pixels` as `cell`: the sum of squared distances.
#[must_use]
pub fn error(pixels: &[Rgb], cell: &GlyphCell) -> f32 {
    pixels
        .iter()
        .enumerate()
        .map(|(i, &c)| lab_dist2(oklab(c.linear()), oklab(cell.pixel(i).linear())))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    const K: Rgb = Rgb::new(0, 0, 0);
    const W: Rgb = Rgb::new(255, 255, 255);

    #[test]
    fn one_and_two_colours_are_exact_and_canonical() {
        assert_eq!(choose(&[W; 8]), GlyphCell::uniform(W));
        let c = choose(&[W, K, K, W]);
        assert_eq!(
            c,
            GlyphCell {
                mask: 0b0110,
                fg: K,
                bg: W
            }
        );
        assert_eq!(error(&[W, K, K, W], &c), 0.0);
        let flipped = GlyphCell {
            mask: 0b1001,
            fg: W,
            bg: K,
        };
        assert_eq!(flipped.canonical(4), c);
    }

    #[test]
    fn three_colours_split_dark_from_light_and_mix_in_linear_light() {
        let grey = Rgb::new(40, 40, 40);
        let px = [W, W, W, W, K, grey, K, grey];
        let c = choose(&px);
        assert_eq!(c.mask, 0b1111_0000);
        assert_eq!(c.bg, W);
        // The mean light of 0 and 40 is not sRGB 20 but brighter: about 27.
        let m = c.fg.r;
        assert!((25..=28).contains(&m), "{m}");
        assert!(error(&px, &c) < error(&px, &GlyphCell::uniform(Rgb::mean(px))));
    }

    #[test]
    fn srgb_round_trips_through_linear_light() {
        for v in 0..=255u8 {
            let c = Rgb::new(v, v, v);
            assert_eq!(tables().to_srgb(c.linear()), c);
        }
    }

    #[test]
    fn linear_light_goes_back_to_the_nearest_srgb_value() {
        let t = tables();
        for i in 0..=2000 {
            let x = i as f32 / 2000.0;
            let nearest = (0..=255u8)
                .min_by(|&a, &b| {
                    let (da, db) = (
                        (t.linear[a as usize] - x).abs(),
                        (t.linear[b as usize] - x).abs(),
                    );
                    da.total_cmp(&db)
                })
                .unwrap();
            let got = t.to_srgb([x; 3]).r;
            let (dg, dn) = (
                (t.linear[got as usize] - x).abs(),
                (t.linear[nearest as usize] - x).abs(),
            );
            assert!(dg <= dn, "{x}: {got} against {nearest}");
        }
    }

    /// The weighted squared error of showing `lin` split by `mask` in its groups' means.
    fn split_error<const N: usize>(lin: &[Linear; N], mask: u8) -> f32 {
        let (bg, fg) = means(lin, mask);
        lin.iter()
            .enumerate()
            .map(|(i, l)| {
                let m = if mask >> i & 1 == 1 { fg } else { bg };
                (0..3)
                    .map(|c| WEIGHT[c] * (l[c] - m[c]).powi(2))
                    .sum::<f32>()
            })
            .sum()
    }

    #[test]
    fn sextants_and_quadrants_get_the_best_split() {
        // A fixed pseudo-random walk of colours; every split is tried by brute force.
        let mut seed = 12_345u32;
        let mut next = || {
            seed = seed.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            (seed >> 16) as f32 / 65_536.0
        };
        for _ in 0..200 {
            let six: [Linear; 6] = std::array::from_fn(|_| [next(), next(), next()]);
            let got = split_error(&six, best_split(&six));
            let best = (1..63u8)
                .map(|m| split_error(&six, m))
                .fold(f32::MAX, f32::min);
            assert!(got <= best + 1e-5, "{got} > {best}");
            let four: [Linear; 4] = std::array::from_fn(|i| six[i]);
            let got = split_error(&four, best_split(&four));
            let best = (1..15u8)
                .map(|m| split_error(&four, m))
                .fold(f32::MAX, f32::min);
            assert!(got <= best + 1e-5, "{got} > {best}");
        }
    }
}
