//! One cell's glyph and two colours: which of its 4, 6 or 8 pixels show the foreground, and
//! the two colours that keep the cell closest to its pixels.
//!
//! Colours are mixed in linear light: a group's colour is the mean light of its pixels, and the
//! split is judged there too, by squared distances with each channel weighted for how much it
//! counts (`lane_split::WEIGHT`). Quadrants and sextants try every split (7 and 31); octants
//! run one round of a 2-means: split the pixels at the light halfway between the darkest and the
//! brightest, then move each pixel to the nearer of the two groups' means. Cells of one or two
//! distinct colours are exact without any of that.
//!
//! This runs for every cell of every frame, so everything runs from tables built once (sRGB ↔
//! linear light), with no cube roots or powers per pixel, and a frame's cells of three or more
//! colours are split eight at a time, one per vector lane (`super::lane_split`).

use super::lane_split::{self, Pixels, Split, SplitSums, LANES};
use crate::color::{channel_to_linear, lab_dist2, oklab, Linear, Rgb};
use wide::f32x8 as V;

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
/// loop over the pixels unrolls. For many cells, [`choose_all`] is several times faster.
#[must_use]
#[inline]
pub fn choose_n<const N: usize>(pixels: &[Rgb]) -> GlyphCell {
    let pixels: &[Rgb; N] = pixels[..N].try_into().expect("N pixels");
    if let Some(cell) = exact(pixels) {
        return cell;
    }
    // One cell in the side-by-side split (the other lanes hold black, and are not read).
    let t = tables();
    let mut px: Pixels<N> = lane_split::pixels();
    lane_split::put(&mut px, 0, &pixels.map(|c| t.to_linear(c)));
    t.cells_of::<N>(&lane_split::split(&px, &mut SplitSums::default()))[0]
}

/// Every cell of `cells` (each `N` pixels, row-major) in order, as [`choose_n`] would choose
/// it, appended to `out`; cells of three or more colours are split `LANES` at a time.
pub fn choose_all<const N: usize>(cells: impl Iterator<Item = [Rgb; N]>, out: &mut Vec<GlyphCell>) {
    let t = tables();
    let mut px: Pixels<N> = lane_split::pixels();
    let mut waiting = [0usize; LANES];
    let mut n = 0;
    let mut sums = SplitSums::default();
    let mut solve = |px: &Pixels<N>, waiting: &[usize], out: &mut Vec<GlyphCell>| {
        let cells = t.cells_of::<N>(&lane_split::split(px, &mut sums));
        for (&at, &cell) in waiting.iter().zip(&cells) {
            out[at] = cell;
        }
    };
    for pixels in cells {
        if let Some(cell) = exact(&pixels) {
            out.push(cell);
            continue;
        }
        waiting[n] = out.len();
        out.push(GlyphCell::default());
        lane_split::put(&mut px, n, &pixels.map(|c| t.to_linear(c)));
        n += 1;
        if n == LANES {
            solve(&px, &waiting, out);
            n = 0;
        }
    }
    if n > 0 {
        // The lanes past `n` still hold earlier cells: solved again, and not read.
        solve(&px, &waiting[..n], out);
    }
}

/// The cell of `pixels` when they hold one or two distinct colours: the split is exact.
#[inline]
fn exact<const N: usize>(pixels: &[Rgb; N]) -> Option<GlyphCell> {
    #[cfg(target_arch = "x86_64")]
    if (4..=8).contains(&N) {
        return exact_lanes(pixels);
    }
    exact_each(pixels)
}

/// [`exact`] one pixel at a time.
#[inline]
fn exact_each<const N: usize>(pixels: &[Rgb; N]) -> Option<GlyphCell> {
    // Colours as one number each, and a bit per pixel, so the tests run over all pixels at once.
    let key = pixels.map(|c| u32::from(c.r) | u32::from(c.g) << 8 | u32::from(c.b) << 16);
    let first = key[0];
    let differ = bits(&key, |k| k != first);
    if differ == 0 {
        return Some(GlyphCell::uniform(pixels[0]));
    }
    let at = differ.trailing_zeros() as usize;
    let other = key[at];
    (bits(&key, |k| k != first && k != other) == 0).then(|| GlyphCell {
        mask: differ as u8,
        fg: pixels[at],
        bg: pixels[0],
    })
}

/// [`exact`] with every pixel compared in a vector lane (up to eight; the lanes past `N` repeat
/// pixel 0). The keys go into the vectors by register moves: built as an array in memory and
/// loaded as vectors, each load waited for eight stores to be forwarded, which cost more than
/// the compares saved.
#[cfg(target_arch = "x86_64")]
#[inline]
fn exact_lanes<const N: usize>(pixels: &[Rgb; N]) -> Option<GlyphCell> {
    use safe_arch::{
        cast_to_m128_from_m128i, cmp_eq_mask_i32_m128i, move_mask_m128, set_i32_m128i,
        set_splat_i32_m128i,
    };
    let key: [i32; 8] = std::array::from_fn(|i| {
        let c = pixels[if i < N { i } else { 0 }];
        i32::from(c.r) | i32::from(c.g) << 8 | i32::from(c.b) << 16
    });
    let low = set_i32_m128i(key[3], key[2], key[1], key[0]);
    let high = set_i32_m128i(key[7], key[6], key[5], key[4]);
    let equal = |k: i32| {
        let k = set_splat_i32_m128i(k);
        let bits = |v| move_mask_m128(cast_to_m128_from_m128i(cmp_eq_mask_i32_m128i(v, k))) as u32;
        bits(low) | bits(high) << 4
    };
    let first = equal(key[0]);
    if first == 0xff {
        return Some(GlyphCell::uniform(pixels[0]));
    }
    let differ = !first & 0xff;
    let at = differ.trailing_zeros() as usize;
    (first | equal(key[at]) == 0xff).then(|| GlyphCell {
        mask: differ as u8,
        fg: pixels[at],
        bg: pixels[0],
    })
}

/// A bit for each of `key`'s values for which `f` holds (bit `i` for value `i`).
#[inline]
fn bits<const N: usize>(key: &[u32; N], f: impl Fn(u32) -> bool) -> u32 {
    key.iter()
        .enumerate()
        .fold(0u32, |m, (i, &k)| m | u32::from(f(k)) << i)
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

/// The guess entry [`Tables::to_srgb`] reads for a linear light `x` in [0, 1] (the same f32
/// product and truncation as its vector lanes).
fn guess_index(x: f32) -> usize {
    ((x * 4095.0) as usize).min(4095)
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
            // The least light that [`Tables::to_srgb`] reads from entry `i`, so the value
            // nearest it is at or below the nearest of every light read from here, which is what
            // lets `to_srgb` step only up. With 4096 entries i/4095 is already that least light
            // for every `i` (checked over every f32 in [0, 1]); the walk keeps it so if the size
            // changes.
            let mut x = i as f32 / 4095.0;
            while x > 0.0 && guess_index(f32::from_bits(x.to_bits() - 1)) == i {
                x = f32::from_bits(x.to_bits() - 1);
            }
            while v < 255 && t.upper[v] < x {
                v += 1;
            }
            *g = v as u8;
        }
        t
    })
}

impl Tables {
    /// A colour in linear light.
    #[inline]
    fn to_linear(&self, c: Rgb) -> Linear {
        [
            self.linear[usize::from(c.r)],
            self.linear[usize::from(c.g)],
            self.linear[usize::from(c.b)],
        ]
    }

    /// Every lane of a side-by-side split as a cell of `N` pixels (canonical). Plain loops:
    /// `array::map` and `from_fn` here took more time (measured).
    #[inline]
    fn cells_of<const N: usize>(&self, split: &Split) -> [GlyphCell; LANES] {
        let (set, clear) = (self.to_srgb(&split.set), self.to_srgb(&split.clear));
        let mut cells = [GlyphCell::default(); LANES];
        for (k, cell) in cells.iter_mut().enumerate() {
            *cell = GlyphCell {
                mask: split.mask[k] as u8,
                fg: Rgb::new(set[0][k], set[1][k], set[2][k]),
                bg: Rgb::new(clear[0][k], clear[1][k], clear[2][k]),
            }
            .canonical(N);
        }
        cells
    }

    /// Linear light back to the nearest 8-bit sRGB value, every lane of three channels: the
    /// guess, then at most one step up along the curve's midpoints (the step down this once also
    /// took never ran). The guess is the value nearest the least light that reads its entry, so
    /// the answer is never below it; one step
    /// is enough because no guess bucket (1/4095 of linear light) holds more than one midpoint:
    /// the curve is steepest near black, at about 0.8 sRGB steps per bucket. Clamping and
    /// finding each guess run on all lanes at once; no loop walks the curve, so no branch can
    /// mispredict.
    #[inline]
    fn to_srgb(&self, light: &[[f32; LANES]; 3]) -> [[u8; LANES]; 3] {
        let mut out = [[0u8; LANES]; 3];
        for (channel, out) in light.iter().zip(&mut out) {
            let x = V::from(*channel).fast_max(V::ZERO).fast_min(V::ONE);
            let at = (x * V::splat(4095.0)).fast_trunc_int().to_array();
            let x = x.to_array();
            for k in 0..LANES {
                let v = usize::from(self.guess[(at[k] as usize).min(4095)]);
                out[k] = (v + usize::from(x[k] > self.upper[v])) as u8;
            }
        }
        out
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
    use crate::encode::lane_split::WEIGHT;

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
            assert_eq!(srgb(c.linear()), c);
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
            let got = srgb([x; 3]).r;
            let (dg, dn) = (
                (t.linear[got as usize] - x).abs(),
                (t.linear[nearest as usize] - x).abs(),
            );
            assert!(dg <= dn, "{x}: {got} against {nearest}");
        }
    }

    /// The means (in linear light) of the pixels whose bit is clear and of those whose bit is
    /// set, each black when empty: written plainly, as a reference.
    fn means<const N: usize>(lin: &[Linear; N], mask: u8) -> (Linear, Linear) {
        let mean = |set: bool| {
            let group: Vec<&Linear> = (0..N)
                .filter(|&i| (mask >> i & 1 == 1) == set)
                .map(|i| &lin[i])
                .collect();
            let n = group.len().max(1) as f32;
            [0, 1, 2].map(|c| group.iter().map(|l| l[c]).sum::<f32>() / n)
        };
        (mean(false), mean(true))
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

    /// A fixed pseudo-random walk of colours.
    fn colours() -> impl FnMut() -> Rgb {
        let mut seed = 12_345u32;
        let mut next = move || {
            seed = seed.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            (seed >> 16) as u8
        };
        move || Rgb::new(next(), next(), next())
    }

    fn linear<const N: usize>(px: &[Rgb; N]) -> [Linear; N] {
        px.map(|c| tables().to_linear(c))
    }

    /// One colour back to sRGB through [`Tables::to_srgb`], in every lane.
    fn srgb(l: Linear) -> Rgb {
        let lanes = tables().to_srgb(&l.map(|v| [v; LANES]));
        for k in 1..LANES {
            assert_eq!(
                [lanes[0][k], lanes[1][k], lanes[2][k]],
                [lanes[0][0], lanes[1][0], lanes[2][0]]
            );
        }
        Rgb::new(lanes[0][0], lanes[1][0], lanes[2][0])
    }

    /// Linear light back to sRGB by walking the midpoints as far as it takes.
    fn to_srgb_walking(x: f32) -> u8 {
        let t = tables();
        let x = x.clamp(0.0, 1.0);
        let mut v = usize::from(t.guess[guess_index(x)]);
        while v < 255 && x > t.upper[v] {
            v += 1;
        }
        while v > 0 && x < t.upper[v - 1] {
            v -= 1;
        }
        v as u8
    }

    #[test]
    fn one_step_from_the_guess_reaches_the_nearest_value() {
        let t = tables();
        let near = |x: f32| {
            let mut v = [x; 9];
            for i in 1..=4 {
                v[2 * i - 1] = f32::from_bits(x.to_bits().saturating_sub(i as u32));
                v[2 * i] = f32::from_bits(x.to_bits() + i as u32);
            }
            v
        };
        // Every place where the answer or the guess changes, a few ulps either side, and a
        // dense sweep between.
        let edges = t.upper[..255].iter().copied();
        let buckets = (0..=4096).map(|i| i as f32 / 4095.0);
        let sweep = (0..=1_000_000).map(|i| i as f32 / 1_000_000.0);
        for x in edges.chain(buckets).flat_map(near).chain(sweep) {
            let got = srgb([x, x, x]).r;
            assert_eq!(got, to_srgb_walking(x), "{x}");
        }
        for x in [-1.0, -0.0, 1.0, 2.0, f32::INFINITY] {
            assert_eq!(srgb([x, x, x]).r, to_srgb_walking(x), "{x}");
        }
    }

    #[test]
    fn sextants_and_quadrants_get_the_best_split() {
        // Every split tried by brute force.
        let mut colour = colours();
        for _ in 0..200 {
            let six: [Rgb; 6] = std::array::from_fn(|_| colour());
            let lin = linear(&six);
            let got = split_error(&lin, choose_n::<6>(&six).mask);
            let best = (1..63u8)
                .map(|m| split_error(&lin, m))
                .fold(f32::MAX, f32::min);
            assert!(got <= best + 1e-5, "{got} > {best}");
            let four: [Rgb; 4] = std::array::from_fn(|i| six[i]);
            let lin = linear(&four);
            let got = split_error(&lin, choose_n::<4>(&four).mask);
            let best = (1..15u8)
                .map(|m| split_error(&lin, m))
                .fold(f32::MAX, f32::min);
            assert!(got <= best + 1e-5, "{got} > {best}");
        }
    }

    /// The octant split written one cell at a time, plainly, as the module doc says it.
    fn two_means_alone(lin: &[Linear; 8]) -> u8 {
        let light = |l: &Linear| WEIGHT[0] * l[0] + WEIGHT[1] * l[1] + WEIGHT[2] * l[2];
        let dist = |x: &Linear, y: &Linear| {
            (0..3)
                .map(|c| WEIGHT[c] * (x[c] - y[c]) * (x[c] - y[c]))
                .sum::<f32>()
        };
        let pick =
            |f: &dyn Fn(usize) -> bool| (0..8).filter(|&i| f(i)).fold(0u8, |m, i| m | 1 << i);
        let lo = lin.iter().map(light).fold(f32::INFINITY, f32::min);
        let hi = lin.iter().map(light).fold(f32::NEG_INFINITY, f32::max);
        let mid = (lo + hi) / 2.0;
        let first = if mid < hi {
            pick(&|i| light(&lin[i]) > mid)
        } else {
            let far = lin.iter().map(|l| dist(l, &lin[0])).fold(0.0, f32::max);
            pick(&|i| dist(&lin[i], &lin[0]) > far / 2.0)
        };
        let (ca, cb) = means(lin, first);
        let next = pick(&|i| dist(&lin[i], &cb) < dist(&lin[i], &ca));
        if next == 0 || next == 0xff {
            first
        } else {
            next
        }
    }

    #[test]
    fn octants_split_as_a_two_means_of_one_cell_would() {
        let mut colour = colours();
        let mut cells: Vec<[Rgb; 8]> = (0..2000)
            .map(|_| std::array::from_fn(|_| colour()))
            .collect();
        // Three colours: a grey between black and white.
        for g in [10u8, 100, 200] {
            let grey = Rgb::new(g, g, g);
            cells.push([grey, K, W, grey, K, W, grey, grey]);
        }
        let mut differ = 0;
        for px in &cells {
            let lin = linear(px);
            let want = two_means_alone(&lin);
            let got = choose_n::<8>(px);
            // Canonical form may flip the mask; the plain version's distances are not
            // bit-for-bit the side-of-a-plane test, so a pixel on the plane may go either way.
            let same = got.mask == want || got.mask == !want;
            if !same {
                differ += 1;
                let (g, w) = (split_error(&lin, got.mask), split_error(&lin, want));
                assert!(
                    (g - w).abs() <= 1e-4 * w.max(1e-6),
                    "{px:?}: {g} against {w}"
                );
            }
        }
        assert!(differ <= cells.len() / 100, "{differ} of {}", cells.len());
    }

    #[test]
    fn a_cell_whose_light_spans_one_float_step_still_splits() {
        // The darkest and brightest pixel's weighted light are adjacent f32 values, so their
        // middle rounds up to the brightest and no pixel lies above it.
        let (a, b, h) = (
            Rgb::new(58, 159, 15),
            Rgb::new(108, 150, 10),
            Rgb::new(96, 150, 75),
        );
        let px = [a, b, h, a, b, h, a, b];
        let c = choose(&px);
        assert_ne!(c.mask, 0, "{c:?}");
        assert!(error(&px, &c) < error(&px, &GlyphCell::uniform(Rgb::mean(px))));
        let lin = linear(&px);
        assert_ne!(two_means_alone(&lin), 0);
    }

    #[test]
    fn the_vector_colour_check_agrees_with_the_plain_one_on_every_cell_of_four_colours() {
        // Colours one bit apart in red and in blue, so a lane that compared the wrong bits would
        // be caught.
        let alphabet = [
            Rgb::new(7, 7, 7),
            Rgb::new(6, 7, 7),
            Rgb::new(7, 7, 6),
            Rgb::new(6, 7, 6),
        ];
        fn all<const N: usize>(alphabet: &[Rgb; 4]) {
            for code in 0..4usize.pow(N as u32) {
                let px: [Rgb; N] = std::array::from_fn(|i| alphabet[code >> (2 * i) & 3]);
                assert_eq!(exact(&px), exact_each(&px), "{px:?}");
            }
        }
        all::<4>(&alphabet);
        all::<6>(&alphabet);
        all::<8>(&alphabet);
    }

    proptest::proptest! {
        /// A cell of two or more colours always shows two: neither side of its split is empty.
        #[test]
        fn a_cell_of_several_colours_is_never_shown_flat(
            v in proptest::array::uniform8((0u8..4, 0u8..4, 0u8..4)),
        ) {
            let px: [Rgb; 8] =
                std::array::from_fn(|i| Rgb::new(v[i].0 * 80, v[i].1 * 80, v[i].2 * 80));
            let c = choose_n::<8>(&px);
            if px.iter().any(|&p| p != px[0]) {
                proptest::prop_assert_ne!(c.mask, 0);
            }
        }

        /// A cell's glyph and colours do not depend on the cells it is solved beside.
        #[test]
        fn cells_solved_side_by_side_match_cells_solved_alone(
            seeds in proptest::collection::vec((0u32..6, proptest::array::uniform8(0u8..=255)), 1..40),
        ) {
            // Few distinct channel values, so one- and two-colour cells come up too.
            let cell = |&(kind, v): &(u32, [u8; 8])| -> [Rgb; 8] {
                std::array::from_fn(|i| {
                    let x = if kind < 2 { v[i] % (kind as u8 + 2) * 90 } else { v[i] };
                    Rgb::new(x, v[(i + kind as usize) % 8], v[7 - i])
                })
            };
            let cells: Vec<[Rgb; 8]> = seeds.iter().map(cell).collect();
            let mut together = Vec::new();
            choose_all::<8>(cells.iter().copied(), &mut together);
            let alone: Vec<GlyphCell> = cells.iter().map(|px| choose_n::<8>(px)).collect();
            proptest::prop_assert_eq!(&together, &alone);
            let six: Vec<[Rgb; 6]> = cells.iter().map(|px| std::array::from_fn(|i| px[i])).collect();
            let mut together = Vec::new();
            choose_all::<6>(six.iter().copied(), &mut together);
            let alone: Vec<GlyphCell> = six.iter().map(|px| choose_n::<6>(px)).collect();
            proptest::prop_assert_eq!(&together, &alone);
        }
    }
}
