//! The mix of every colour bin, worked out ahead of time by [`super::mixing::Solver`] and shipped
//! in the binary (deflated, a few hundred KiB), so a process only inflates it once, in
//! milliseconds, and encoding a pixel is one table read: no search on the hot path, no warm-up.
//!
//! The shipped tables are written by `cargo test --release --lib -- --ignored write_mix_tables`
//! after the weights in `mix_solver` change; a test checks them against the search.

use std::io::Read;

use super::level::ColorLevel;
use super::mixing::{bin_of, Mix, BINS};
use crate::color::Rgb;

/// The mixes of one palette and share set, one per bin.
#[derive(Debug)]
pub struct MixTable {
    /// Packed mixes ([`Mix::pack`]) in bin order.
    bins: Vec<u32>,
}

/// How a table is stored: the `a`s of every bin, then the `b`s, then the shares (runs of equal
/// bytes deflate well), deflated.
const PLANES: usize = 3;

impl MixTable {
    /// The table of packed mixes `bins` (one per bin, in bin order).
    ///
    /// # Panics
    /// When there is not one per bin.
    #[must_use]
    pub fn from_bins(bins: Vec<u32>) -> Self {
        assert_eq!(bins.len(), BINS, "one mix per bin");
        Self { bins }
    }

    /// A table as [`MixTable::to_bytes`] stored it.
    ///
    /// # Panics
    /// When the bytes are not such a table (they are shipped in the binary).
    #[must_use]
    pub fn from_bytes(stored: &[u8]) -> Self {
        let mut planes = Vec::with_capacity(PLANES * BINS);
        flate2::read::DeflateDecoder::new(stored)
            .read_to_end(&mut planes)
            .expect("a shipped mix table inflates");
        assert_eq!(planes.len(), PLANES * BINS, "a shipped mix table's size");
        let (a, rest) = planes.split_at(BINS);
        let (b, share) = rest.split_at(BINS);
        Self::from_bins(
            (0..BINS)
                .map(|k| {
                    Mix {
                        a: a[k],
                        b: b[k],
                        share: share[k],
                    }
                    .pack()
                })
                .collect(),
        )
    }

    /// The table as it is shipped (see [`MixTable::from_bytes`]).
    #[cfg(test)]
    #[must_use]
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut planes = vec![0u8; PLANES * BINS];
        for (k, &v) in self.bins.iter().enumerate() {
            let m = Mix::unpack(v);
            planes[k] = m.a;
            planes[BINS + k] = m.b;
            planes[2 * BINS + k] = m.share;
        }
        let mut z = flate2::write::DeflateEncoder::new(Vec::new(), flate2::Compression::best());
        std::io::Write::write_all(&mut z, &planes).expect("writing to memory");
        z.finish().expect("writing to memory")
    }

    /// The mix of colour `c`.
    #[must_use]
    #[inline]
    pub fn mix(&self, c: Rgb) -> Mix {
        Mix::unpack(self.bins[bin_of(c)])
    }

    /// The mix of bin `k`.
    #[cfg(test)]
    #[must_use]
    pub fn bin(&self, k: usize) -> Mix {
        Mix::unpack(self.bins[k])
    }
}

/// The palette entries a level's pictures use: the cube and grey ramp at 256 colours (the first
/// 16 are the user's theme), all 16 at 16.
#[must_use]
pub fn entries(level: ColorLevel) -> Vec<u8> {
    match level {
        ColorLevel::Ansi16 => (0..16).collect(),
        _ => (16..=255).collect(),
    }
}

/// The shipped tables of a level, fine then halves.
#[must_use]
pub fn shipped(level: ColorLevel) -> [&'static [u8]; 2] {
    match level {
        ColorLevel::Ansi16 => [
            include_bytes!("mixes/16-fine.deflate"),
            include_bytes!("mixes/16-halves.deflate"),
        ],
        _ => [
            include_bytes!("mixes/256-fine.deflate"),
            include_bytes!("mixes/256-halves.deflate"),
        ],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_survives_being_stored() {
        let bins: Vec<u32> = (0..BINS)
            .map(|k| {
                Mix {
                    a: (k % 251) as u8,
                    b: (k % 13) as u8,
                    share: (k % 17) as u8,
                }
                .pack()
            })
            .collect();
        let table = MixTable::from_bins(bins.clone());
        let back = MixTable::from_bytes(&table.to_bytes());
        assert!((0..BINS).all(|k| back.bin(k).pack() == bins[k]));
    }
}
