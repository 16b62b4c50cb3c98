//! One cell's glyph and two colours: which of its 4, 6 or 8 pixels show the foreground, and
//! the two colours that keep the cell closest to its pixels.
//!
//! Colours are mixed in linear light (a group's colour is the mean light of its pixels) and
//! judged in OKLab (the error is the sum of each pixel's squared OKLab distance to the colour
//! its side of the mask shows). The split is a 2-means: start from the two pixels farthest
//! apart, assign each pixel to the nearer colour, move each colour to its group's mean, and
//! repeat until nothing moves (at most a few rounds over ≤ 8 pixels). Cells of one or two
//! distinct colours are exact without any of that, and they are most cells.

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
        let full = ((1u16 << n) - 1) as u8;
        let mask = self.mask & full;
        if mask == 0 || self.fg == self.bg {
            return Self::uniform(self.bg);
        }
        if mask == full {
            return Self::uniform(self.fg);
        }
        if mask & 1 != 0 {
            Self {
                mask: !mask & full,
                fg: self.bg,
                bg: self.fg,
            }
        } else {
            Self { mask, ..self }
        }
    }
}

/// The cell (canonical) that best shows `pixels` (row-major, 1 to [`MAX_PIXELS`]) with two
/// colours.
#[must_use]
pub fn choose(pixels: &[Rgb]) -> GlyphCell {
    let n = pixels.len().min(MAX_PIXELS);
    let pixels = &pixels[..n];
    let Some(&first) = pixels.first() else {
        return GlyphCell::default();
    };
    // One or two distinct colours: the split is exact.
    let other = pixels.iter().copied().find(|&c| c != first);
    let Some(other) = other else {
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
    two_means(pixels)
}

/// The bits of the pixels for which `f` holds.
fn mask_where(pixels: &[Rgb], f: impl Fn(Rgb) -> bool) -> u8 {
    pixels
        .iter()
        .enumerate()
        .filter(|&(_, &c)| f(c))
        .fold(0u8, |m, (i, _)| m | (1 << i))
}

/// The 2-means split of ≥ 3 distinct colours (see the module doc). Each distinct colour is
/// taken to OKLab once; while the split moves, a group's centre is the mean of its members'
/// OKLab (cheap, and close to the OKLab of their mean light at these small spreads); the colours
/// shown are the groups' mean light.
fn two_means(pixels: &[Rgb]) -> GlyphCell {
    let n = pixels.len();
    let mut lin = [[0.0f32; 3]; MAX_PIXELS];
    let mut lab = [[0.0f32; 3]; MAX_PIXELS];
    for (i, &c) in pixels.iter().enumerate() {
        if let Some(j) = pixels[..i].iter().position(|&p| p == c) {
            (lin[i], lab[i]) = (lin[j], lab[j]);
        } else {
            lin[i] = c.linear();
            lab[i] = oklab(lin[i]);
        }
    }
    // Seeds: the two pixels farthest apart.
    let (mut a, mut b, mut far) = (0, 1, -1.0f32);
    for i in 0..n {
        for j in i + 1..n {
            let d = lab_dist2(lab[i], lab[j]);
            if d > far {
                (a, b, far) = (i, j, d);
            }
        }
    }
    let full = ((1u16 << n) - 1) as u8;
    let (mut ca, mut cb) = (lab[a], lab[b]);
    let mut mask = 0u8;
    for _ in 0..4 {
        let mut next = (0..n).fold(0u8, |m, i| {
            if lab_dist2(lab[i], cb) < lab_dist2(lab[i], ca) {
                m | (1 << i)
            } else {
                m
            }
        });
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
        ca = mean(&lab[..n], !mask);
        cb = mean(&lab[..n], mask);
    }
    let fg = to_srgb(mean(&lin[..n], mask));
    let bg = to_srgb(mean(&lin[..n], !mask));
    GlyphCell { mask, fg, bg }.canonical(n)
}

/// The mean of the triples (light, or OKLab) whose bit is set in `mask`.
fn mean(lin: &[Linear], mask: u8) -> Linear {
    let mut sum = [0.0f32; 3];
    let mut k = 0.0f32;
    for (i, l) in lin.iter().enumerate() {
        if mask & (1 << i) != 0 {
            for c in 0..3 {
                sum[c] += l[c];
            }
            k += 1.0;
        }
    }
    let k = k.max(1.0);
    [sum[0] / k, sum[1] / k, sum[2] / k]
}

/// Linear light back to the nearest 8-bit sRGB colour: a first guess from a table of 4096
/// steps, then the nearest of it and its neighbours on the transfer curve.
fn to_srgb(l: Linear) -> Rgb {
    static GUESS: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    let guess = GUESS.get_or_init(|| {
        let mut t = vec![0u8; 4096];
        let mut v = 0u8;
        for (i, g) in t.iter_mut().enumerate() {
            let x = i as f32 / 4095.0;
            while v < 255 && channel_to_linear(v + 1) <= x {
                v += 1;
            }
            *g = v;
        }
        t
    });
    let ch = |x: f32| -> u8 {
        let g = guess[((x.clamp(0.0, 1.0) * 4095.0) as usize).min(4095)];
        let mut best = g;
        for c in [
            g.saturating_sub(1),
            g.saturating_add(1),
            g.saturating_add(2),
        ] {
            if (channel_to_linear(c) - x).abs() < (channel_to_linear(best) - x).abs() {
                best = c;
            }
        }
        best
    };
    Rgb::new(ch(l[0]), ch(l[1]), ch(l[2]))
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
            assert_eq!(to_srgb(c.linear()), c);
        }
    }
}
