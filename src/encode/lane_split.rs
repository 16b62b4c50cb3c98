//! The split of a cell's pixels into two groups (see [`super::glyph_cell`]), for [`LANES`]
//! cells side by side, one cell per vector lane: every step is the same arithmetic over the
//! lanes with no branch per cell. One cell at a time, the split was most of an octant or
//! sextant frame's time.
//!
//! Quadrants and sextants try every split ([`best_split`]); octants run a 2-means
//! ([`two_means`]). A 2-means cell whose groups have stopped moving is a fixed point of a round
//! (the same groups give the same centres, which give the same groups), so running every lane
//! for as many rounds as the slowest needs gives each cell what it would get alone. Every lane
//! does the same IEEE operations in the same order, so a cell's result does not depend on the
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

/// Most rounds of assigning pixels and moving the centres.
const ROUNDS: usize = 4;

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
        (member, means(px, &member))
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

/// Splits each lane's `N` pixels: seeds are the darkest and the brightest pixel by weighted
/// light (where all are equally light, the first pixel and the one farthest from it); then
/// each pixel goes to the nearer centre and the centres move to their groups' means, until no
/// lane moves or [`ROUNDS`] have run. Neither group is ever left empty. Returns the groups and
/// their means (the centres of the last round: the first round always moves every lane, so they
/// are the means of the groups returned).
fn two_means<const N: usize>(px: &Pixels<N>) -> ([V; N], ([V; 3], [V; 3])) {
    let w = WEIGHT.map(V::splat);
    let at = |p: usize| -> [V; 3] { [px[0][p], px[1][p], px[2][p]] };
    let light: [V; N] =
        std::array::from_fn(|p| w[0] * px[0][p] + w[1] * px[1][p] + w[2] * px[2][p]);
    // Seeds: the first darkest and the first brightest pixel, with their colours and indices.
    let (mut lo, mut hi) = (light[0], light[0]);
    let (mut a, mut b) = (at(0), at(0));
    let (mut a_at, mut b_at) = (V::ZERO, V::ZERO);
    for (p, &l) in light.iter().enumerate().skip(1) {
        let (darker, brighter) = (l.simd_lt(lo), l.simd_gt(hi));
        lo = darker.select(l, lo);
        hi = brighter.select(l, hi);
        a_at = darker.select(V::splat(p as f32), a_at);
        b_at = brighter.select(V::splat(p as f32), b_at);
        let c = at(p);
        a = std::array::from_fn(|i| darker.select(c[i], a[i]));
        b = std::array::from_fn(|i| brighter.select(c[i], b[i]));
    }
    let level = lo.simd_eq(hi);
    if level.any() {
        // Equal light, different colours: the second seed is the pixel farthest from the first.
        let mut far = V::ZERO;
        let first = at(0);
        for p in 1..N {
            let c = at(p);
            let d: [V; 3] = std::array::from_fn(|i| c[i] - first[i]);
            let d = w[0] * d[0] * d[0] + w[1] * d[1] * d[1] + w[2] * d[2] * d[2];
            let farther = level & d.simd_gt(far);
            far = farther.select(d, far);
            b_at = farther.select(V::splat(p as f32), b_at);
            b = std::array::from_fn(|i| farther.select(c[i], b[i]));
        }
    }
    let mut member = [V::ZERO; N];
    for _ in 0..ROUNDS {
        let next = nearer_second(px, &a, &b, a_at, b_at);
        let moved = next
            .iter()
            .zip(&member)
            .fold(V::ZERO, |m, (&n, &o)| m | (n ^ o));
        if !moved.any() {
            break;
        }
        member = next;
        (a, b) = means(px, &member);
    }
    (member, (a, b))
}

/// For each pixel, the lanes where it lies nearer `b` than `a` (on `b`'s side of the plane
/// halfway between), never none or all of a lane's pixels: then the seed of the empty side
/// (pixel `a_at` or `b_at`) keeps its own pixel.
#[inline(always)]
fn nearer_second<const N: usize>(
    px: &Pixels<N>,
    a: &[V; 3],
    b: &[V; 3],
    a_at: V,
    b_at: V,
) -> [V; N] {
    let w = WEIGHT.map(V::splat);
    let axis: [V; 3] = std::array::from_fn(|c| w[c] * (b[c] - a[c]));
    let mid: [V; 3] = std::array::from_fn(|c| (a[c] + b[c]) * V::splat(0.5));
    let mut next = [V::ZERO; N];
    let mut count = V::ZERO;
    let one = V::ONE;
    for (p, n) in next.iter_mut().enumerate() {
        let s = axis[0] * (px[0][p] - mid[0])
            + axis[1] * (px[1][p] - mid[1])
            + axis[2] * (px[2][p] - mid[2]);
        *n = s.simd_gt(V::ZERO);
        count += *n & one;
    }
    let none = count.simd_eq(V::ZERO);
    let all = count.simd_eq(V::splat(N as f32));
    if (none | all).any() {
        for (p, n) in next.iter_mut().enumerate() {
            let here = V::splat(p as f32);
            let only_b = b_at.simd_eq(here);
            let not_a = !a_at.simd_eq(here);
            *n = none.select(only_b, all.select(not_a, *n));
        }
    }
    next
}

/// Each lane's means of the pixels outside `member` and of those in it (black for an empty
/// group).
#[inline(always)]
fn means<const N: usize>(px: &Pixels<N>, member: &[V; N]) -> ([V; 3], [V; 3]) {
    let (mut all, mut set) = ([V::ZERO; 3], [V::ZERO; 3]);
    let mut count = V::ZERO;
    for (p, &m) in member.iter().enumerate() {
        count += m & V::ONE;
        for c in 0..3 {
            all[c] += px[c][p];
            set[c] += px[c][p] & m;
        }
    }
    let one = V::ONE;
    let rest = (V::splat(N as f32) - count).fast_max(one);
    let count = count.fast_max(one);
    (
        std::array::from_fn(|c| (all[c] - set[c]) / rest),
        std::array::from_fn(|c| set[c] / count),
    )
}
