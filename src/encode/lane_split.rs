//! The split of a cell's pixels into two groups (see [`super::glyph_cell`]), for [`LANES`]
//! cells side by side, one cell per vector lane: every step is the same arithmetic over the
//! lanes with no branch per cell. One cell at a time, the split was most of an octant or
//! sextant frame's time.
//!
//! Quadrants and sextants try every split ([`best_split`]); octants run one round of a 2-means
//! from a split by light ([`two_means`]). Every lane does the same IEEE operations in the same
//! order, and a lane's answer never reads another lane, so a cell's result does not depend on the
//! cells it shares a batch with.

use wide::f32x8;

/// How much each channel of linear light counts when pixels are split: roughly the square roots
/// of their shares of luminance, so green differences weigh most and blue least. Measured on the
/// bench's walk path, splitting in this space keeps S-CIELAB at least as low as splitting in
/// OKLab, for none of OKLab's cube roots.
pub(super) const WEIGHT: [f32; 3] = [0.25, 0.64, 0.1225];

/// Cells solved side by side.
pub const LANES: usize = 8;

/// One value per cell.
type V = f32x8;

/// The pixels of [`LANES`] cells in linear light, channel-major: lane `k` of `px[c][p]` is
/// channel `c` of pixel `p` of the cell in lane `k`.
pub type Pixels<const N: usize> = [[V; N]; 3];

/// What [`split`] found for each lane.
pub struct Split {
    /// The pixels of the second group (bit `p` = pixel `p`).
    pub mask: [u32; LANES],
    /// The mean of the pixels whose bit is clear, channel by channel.
    pub clear: [[f32; LANES]; 3],
    /// The mean of the pixels whose bit is set, channel by channel.
    pub set: [[f32; LANES]; 3],
}

/// All-zero pixels for every lane.
#[must_use]
pub fn pixels<const N: usize>() -> Pixels<N> {
    [[V::ZERO; N]; 3]
}

/// Puts a cell's pixels (linear light, in pixel order) into lane `k`.
#[inline]
pub fn put<const N: usize>(px: &mut Pixels<N>, k: usize, cell: &[[f32; 3]; N]) {
    for (p, colour) in cell.iter().enumerate() {
        for (c, &v) in colour.iter().enumerate() {
            px[c][p].as_mut_array()[k] = v;
        }
    }
}

/// Room for [`best_split`]'s sums of every split, made once for many calls: zeroing it per
/// batch of cells was a few percent of a sextant frame, and each call writes every entry it
/// reads but the first, which stays zero.
pub struct SplitSums([[V; SPLITS]; 3]);

impl Default for SplitSums {
    fn default() -> Self {
        Self([[V::ZERO; SPLITS]; 3])
    }
}

/// Splits each lane's `N` pixels (3 to 8) into the two groups that show them best: every split
/// for up to six pixels, a 2-means for more.
#[must_use]
pub fn split<const N: usize>(px: &Pixels<N>, sums: &mut SplitSums) -> Split {
    let (member, (clear, set)) = if N <= 6 {
        let member = best_split(px, sums);
        let total: [V; 3] = std::array::from_fn(|c| px[c].iter().fold(V::ZERO, |s, &v| s + v));
        (member, means(px, &member, &total))
    } else {
        two_means(px)
    };
    let bits = member.iter().enumerate().fold(V::ZERO, |m, (p, &set)| {
        m + (set & V::splat((1u32 << p) as f32))
    });
    Split {
        mask: bits.to_array().map(|v| v as u32),
        clear: clear.map(V::to_array),
        set: set.map(V::to_array),
    }
}

/// The best split of each lane's few pixels (quadrants: 7 candidates, sextants: 31), by trying
/// each: the one whose groups' means leave the least weighted squared error. That error is the
/// total square less each group's |sum|² / size, so the best split has the largest sum of
/// those. Pixel 0 stays outside the second group (canonical form), so each split is tried once;
/// the second group's sums of all splits are built by doubling (split `j + h` is split `j` plus
/// pixel `p`, `h` = 2^(p−1)). Ties go to the first split.
fn best_split<const N: usize>(px: &Pixels<N>, sums: &mut SplitSums) -> [V; N] {
    let m = 1usize << (N - 1);
    assert!(m <= SPLITS, "best_split takes at most six pixels");
    let w = WEIGHT.map(V::splat);
    let set = &mut sums.0;
    for (sums, channel) in set.iter_mut().zip(px) {
        for (p, &v) in channel.iter().enumerate().skip(1) {
            let h = 1 << (p - 1);
            for j in 0..h {
                sums[j + h] = sums[j] + v;
            }
        }
    }
    let total: [V; 3] = std::array::from_fn(|c| set[c][m - 1] + px[c][0]);
    let norm = |v: [V; 3]| w[0] * v[0] * v[0] + w[1] * v[1] * v[1] + w[2] * v[2] * v[2];
    let score = |j: usize| {
        let s = [set[0][j], set[1][j], set[2][j]];
        let r: [V; 3] = std::array::from_fn(|c| total[c] - s[c]);
        norm(s) * V::splat(GroupSizes::<N>::INV_SET[j])
            + norm(r) * V::splat(GroupSizes::<N>::INV_REST[j])
    };
    let (mut best, mut best_score) = (V::ONE, score(1));
    for j in 2..m {
        let s = score(j);
        let better = s.simd_gt(best_score);
        best_score = better.select(s, best_score);
        best = better.select(V::splat(j as f32), best);
    }
    let mask = best.to_array().map(|j| (j as u32) << 1);
    std::array::from_fn(|p| V::new(mask.map(|m| if m >> p & 1 == 1 { TRUE } else { 0.0 })))
}

/// A lane of a mask that holds.
const TRUE: f32 = f32::from_bits(u32::MAX);

/// Most splits [`best_split`] tries: sextants' 2^5 (the empty one included).
const SPLITS: usize = 32;

/// 1 / the size of each group of split `j` of `N` pixels (`j` = the mask without pixel 0),
/// worked out at compile time.
struct GroupSizes<const N: usize>;

impl<const N: usize> GroupSizes<N> {
    /// 1 / the second group's size (0 for the empty split, which is never best).
    const INV_SET: [f32; SPLITS] = {
        let mut t = [0.0f32; SPLITS];
        let mut j = 1;
        while j < SPLITS {
            t[j] = 1.0 / j.count_ones() as f32;
            j += 1;
        }
        t
    };
    /// 1 / the first group's size (pixel 0 and the rest).
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

/// Splits each lane's `N` pixels in two steps. First at the weighted light halfway between the
/// lane's darkest and brightest pixel (where no pixel is brighter than that, as when all are
/// equally light: at half the largest distance from the first pixel); then each pixel goes to
/// the nearer of the two groups' means, once, and the means move to the new groups. A lane whose
/// second step would empty a group keeps its first split. Returns the groups and their means.
///
/// This is a 2-means started from a light split and stopped after one round. On the bench's
/// walk path (80×24) its S-CIELAB is within 0.001 of what up to four rounds from the darkest
/// and the brightest pixel gave (0.582 against 0.581 at 9 ppd, 0.326 at 18 ppd); a second round
/// would give 0.581 and 0.325. The split costs about 40 % fewer instructions (callgrind): no
/// seed colours to carry, one round instead of up to four.
fn two_means<const N: usize>(px: &Pixels<N>) -> ([V; N], ([V; 3], [V; 3])) {
    let w = WEIGHT.map(V::splat);
    let half = V::splat(0.5);
    let light: [V; N] =
        std::array::from_fn(|p| w[0] * px[0][p] + w[1] * px[1][p] + w[2] * px[2][p]);
    let (mut lo, mut hi) = (light[0], light[0]);
    for &l in &light[1..] {
        lo = lo.fast_min(l);
        hi = hi.fast_max(l);
    }
    let mid = (lo + hi) * half;
    let mut member: [V; N] = std::array::from_fn(|p| light[p].simd_gt(mid));
    // No pixel is brighter than the middle where all are equally light, and also where the
    // darkest and the brightest are one f32 step apart and the middle rounds up to the brightest.
    let level = mid.simd_ge(hi);
    if level.any() {
        // Too little light between them: split at half the largest distance from pixel 0.
        let d: [V; N] = std::array::from_fn(|p| {
            let e: [V; 3] = std::array::from_fn(|c| px[c][p] - px[c][0]);
            w[0] * e[0] * e[0] + w[1] * e[1] * e[1] + w[2] * e[2] * e[2]
        });
        let far = d.iter().fold(V::ZERO, |m, &v| m.fast_max(v)) * half;
        for (m, &d) in member.iter_mut().zip(&d) {
            *m = level.select(d.simd_gt(far), *m);
        }
    }
    let total: [V; 3] = std::array::from_fn(|c| px[c].iter().fold(V::ZERO, |s, &v| s + v));
    let (a, b) = means(px, &member, &total);
    // One round: each pixel to the nearer mean (the side of the plane halfway between them).
    let axis: [V; 3] = std::array::from_fn(|c| w[c] * (b[c] - a[c]));
    let halfway: [V; 3] = std::array::from_fn(|c| (a[c] + b[c]) * half);
    let cut = axis[0] * halfway[0] + axis[1] * halfway[1] + axis[2] * halfway[2];
    let mut next = [V::ZERO; N];
    let mut count = V::ZERO;
    for (p, n) in next.iter_mut().enumerate() {
        *n = (axis[0] * px[0][p] + axis[1] * px[1][p] + axis[2] * px[2][p]).simd_gt(cut);
        count += *n & V::ONE;
    }
    let emptied = count.simd_eq(V::ZERO) | count.simd_eq(V::splat(N as f32));
    for (n, &m) in next.iter_mut().zip(&member) {
        *n = emptied.select(m, *n);
    }
    (next, means(px, &next, &total))
}

/// Each lane's means of the pixels outside `member` and of those in it (black for an empty
/// group), given each lane's channel totals over all `N` pixels.
#[inline(always)]
fn means<const N: usize>(px: &Pixels<N>, member: &[V; N], total: &[V; 3]) -> ([V; 3], [V; 3]) {
    let mut set = [V::ZERO; 3];
    let mut count = V::ZERO;
    for (p, &m) in member.iter().enumerate() {
        count += m & V::ONE;
        for c in 0..3 {
            set[c] += px[c][p] & m;
        }
    }
    let one = V::ONE;
    let rest = (V::splat(N as f32) - count).fast_max(one);
    let count = count.fast_max(one);
    (
        std::array::from_fn(|c| (total[c] - set[c]) / rest),
        std::array::from_fn(|c| set[c] / count),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lane `k` of every pixel set to `cell[p]`, the other lanes to `rest[p]`.
    fn lanes(k: usize, cell: &[[f32; 3]; 8], rest: &[[f32; 3]; 8]) -> Pixels<8> {
        let mut px = pixels::<8>();
        for j in 0..LANES {
            put(&mut px, j, if j == k { cell } else { rest });
        }
        px
    }

    #[test]
    fn equally_light_colours_still_split_apart() {
        // Red and green of exactly equal weighted light (0.25 · 0.64 = 0.64 · 0.25), and an
        // orange halfway between them, equally light too; pixel 0 is red.
        let (r, g, o) = ([0.64, 0.0, 0.0], [0.0, 0.25, 0.0], [0.32, 0.125, 0.0]);
        let cell = [r, r, g, g, r, g, o, r];
        let light = |c: [f32; 3]| WEIGHT[0] * c[0] + WEIGHT[1] * c[1] + WEIGHT[2] * c[2];
        assert_eq!(light(r), light(g));
        assert_eq!(light(r), light(o));
        // Whatever the other lanes hold (equally light or not), lane 3 gets the same split.
        let dark_light = [
            [0.0; 3], [1.0; 3], [0.5; 3], [0.0; 3], [1.0; 3], [0.2; 3], [0.0; 3], [1.0; 3],
        ];
        for rest in [cell, dark_light] {
            let s = split(&lanes(3, &cell, &rest), &mut SplitSums::default());
            // Greens on one side; orange, a quarter of the way from red to green, stays with the
            // reds: it is not past half the largest distance from pixel 0, and the round keeps it
            // nearer them.
            let mask = s.mask[3];
            assert_eq!(mask, 0b0010_1100, "{mask:08b}");
            let green_mean = s.set.map(|c| c[3]);
            assert!(
                green_mean[1] > 0.15 && green_mean[0] < 0.2,
                "{green_mean:?}"
            );
        }
    }
}
