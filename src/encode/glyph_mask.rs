//! Masks to characters: which block character draws a cell whose pixels are split in two.
//!
//! A cell's mask has one bit per pixel, row-major from the top-left: bit `row · cols + col` is
//! set where the pixel shows the foreground (the glyph's ink), clear where it shows the
//! background. So half-blocks have bit 0 = upper, bit 1 = lower; quadrants bits 0 1 / 2 3;
//! sextants 0 1 / 2 3 / 4 5 (Unicode's "BLOCK SEXTANT-n" is bit n−1); octants 0 1 / 2 3 / 4 5 /
//! 6 7 (Unicode's "BLOCK OCTANT-n" is bit n−1).
//!
//! The tables follow how Unicode assigned them: a mask that an older block character already
//! draws keeps that character (space, `▀ ▄ ▌ ▐ █`, the quadrants U+2596–259F, the quarter blocks),
//! and the rest are numbered in increasing mask order through their block: sextants from U+1FB00
//! (60 of 64), octants from U+1CD00 (230 of 256).

use crate::render::glyphs::Glyphs;

/// Half-blocks by mask (bit 0 upper, bit 1 lower).
const HALF: [char; 4] = [' ', '▀', '▄', '█'];

/// Quadrants by mask (bit 0 upper left, 1 upper right, 2 lower left, 3 lower right).
const QUADRANT: [char; 16] = [
    ' ', '▘', '▝', '▀', '▖', '▌', '▞', '▛', '▗', '▚', '▐', '▜', '▄', '▙', '▟', '█',
];

/// The first sextant character (BLOCK SEXTANT-1).
const SEXTANT_BASE: u32 = 0x1FB00;

/// The first octant character (BLOCK OCTANT-3: octants 1, 2 and 12 are quarter blocks).
const OCTANT_BASE: u32 = 0x1CD00;

/// Octant masks that Unicode gives to block characters other than the quadrant ones: eighths and
/// quarters of the cell (Symbols for Legacy Computing and its Supplement, and `▂ ▆`).
const OCTANT_ELSEWHERE: [(u8, char); 10] = [
    (0x01, '\u{1CEA8}'), // LEFT HALF UPPER ONE QUARTER BLOCK
    (0x02, '\u{1CEAB}'), // RIGHT HALF UPPER ONE QUARTER BLOCK
    (0x03, '\u{1FB82}'), // UPPER ONE QUARTER BLOCK
    (0x14, '\u{1FBE6}'), // MIDDLE LEFT ONE QUARTER BLOCK
    (0x28, '\u{1FBE7}'), // MIDDLE RIGHT ONE QUARTER BLOCK
    (0x3F, '\u{1FB85}'), // UPPER THREE QUARTERS BLOCK
    (0x40, '\u{1CEA3}'), // LEFT HALF LOWER ONE QUARTER BLOCK
    (0x80, '\u{1CEA0}'), // RIGHT HALF LOWER ONE QUARTER BLOCK
    (0xC0, '\u{2582}'),  // LOWER ONE QUARTER BLOCK
    (0xFC, '\u{2586}'),  // LOWER THREE QUARTERS BLOCK
];

/// The quadrant mask an octant mask is, when its rows pair up (rows 0 = 1 and 2 = 3).
const fn octant_as_quadrant(m: u8) -> Option<u8> {
    let (r0, r1, r2, r3) = (m & 3, (m >> 2) & 3, (m >> 4) & 3, (m >> 6) & 3);
    if r0 == r1 && r2 == r3 {
        Some(r0 | (r2 << 2))
    } else {
        None
    }
}

/// The half-block-column character a sextant mask is, when each column is all on or all off.
const fn sextant_as_columns(m: u8) -> Option<char> {
    match m {
        0 => Some(' '),
        0b01_0101 => Some('▌'),
        0b10_1010 => Some('▐'),
        0b11_1111 => Some('█'),
        _ => None,
    }
}

const fn build_sextants() -> [char; 64] {
    let mut t = [' '; 64];
    let mut next = SEXTANT_BASE;
    let mut m = 0;
    while m < 64 {
        t[m] = match sextant_as_columns(m as u8) {
            Some(c) => c,
            None => {
                let c = next;
                next += 1;
                match char::from_u32(c) {
                    Some(c) => c,
                    None => panic!("sextant codepoint"),
                }
            }
        };
        m += 1;
    }
    t
}

const fn build_octants() -> [char; 256] {
    let mut t = [' '; 256];
    let mut next = OCTANT_BASE;
    let mut m = 0;
    while m < 256 {
        let mut elsewhere = None;
        let mut k = 0;
        while k < OCTANT_ELSEWHERE.len() {
            if OCTANT_ELSEWHERE[k].0 as usize == m {
                elsewhere = Some(OCTANT_ELSEWHERE[k].1);
            }
            k += 1;
        }
        t[m] = match (octant_as_quadrant(m as u8), elsewhere) {
            (Some(q), _) => QUADRANT[q as usize],
            (None, Some(c)) => c,
            (None, None) => {
                let c = next;
                next += 1;
                match char::from_u32(c) {
                    Some(c) => c,
                    None => panic!("octant codepoint"),
                }
            }
        };
        m += 1;
    }
    t
}

/// Sextants by mask.
static SEXTANT: [char; 64] = build_sextants();

/// Octants by mask.
static OCTANT: [char; 256] = build_octants();

/// The character that draws `mask` (see the module doc for the bit order) at setting `glyphs`;
/// bits beyond the cell's pixels are ignored.
#[must_use]
#[inline]
pub fn glyph(glyphs: Glyphs, mask: u8) -> char {
    match glyphs {
        Glyphs::Half => HALF[usize::from(mask & 3)],
        Glyphs::Quadrant => QUADRANT[usize::from(mask & 15)],
        Glyphs::Sextant => SEXTANT[usize::from(mask & 63)],
        Glyphs::Octant => OCTANT[usize::from(mask)],
    }
}

/// The mask `ch` draws at setting `glyphs`, if it is one of that setting's characters (what a
/// frame read back from ANSI needs).
#[must_use]
pub fn mask_of(glyphs: Glyphs, ch: char) -> Option<u8> {
    let table: &[char] = match glyphs {
        Glyphs::Half => &HALF,
        Glyphs::Quadrant => &QUADRANT,
        Glyphs::Sextant => &SEXTANT,
        Glyphs::Octant => &OCTANT,
    };
    table.iter().position(|&c| c == ch).map(|m| m as u8)
}

/// All bits of a cell at `glyphs` (the mask of a full block).
#[must_use]
#[inline]
pub fn full_mask(glyphs: Glyphs) -> u8 {
    ((1u16 << glyphs.pixels_per_cell()) - 1) as u8
}

#[cfg(test)]
mod tests {
    use super::*;
    use unicode_width::UnicodeWidthChar;

    /// Unicode's names of the block characters outside the sextant and octant runs that the
    /// tables use, written from the code charts (U+2580 Block Elements, U+1FB00 Symbols for
    /// Legacy Computing, U+1CC00 its Supplement).
    const NAMES: [(char, &str); 26] = [
        (' ', "SPACE"),
        ('\u{2580}', "UPPER HALF BLOCK"),
        ('\u{2582}', "LOWER ONE QUARTER BLOCK"),
        ('\u{2584}', "LOWER HALF BLOCK"),
        ('\u{2586}', "LOWER THREE QUARTERS BLOCK"),
        ('\u{2588}', "FULL BLOCK"),
        ('\u{258C}', "LEFT HALF BLOCK"),
        ('\u{2590}', "RIGHT HALF BLOCK"),
        ('\u{2596}', "QUADRANT LOWER LEFT"),
        ('\u{2597}', "QUADRANT LOWER RIGHT"),
        ('\u{2598}', "QUADRANT UPPER LEFT"),
        (
            '\u{2599}',
            "QUADRANT UPPER LEFT AND LOWER LEFT AND LOWER RIGHT",
        ),
        ('\u{259A}', "QUADRANT UPPER LEFT AND LOWER RIGHT"),
        (
            '\u{259B}',
            "QUADRANT UPPER LEFT AND UPPER RIGHT AND LOWER LEFT",
        ),
        (
            '\u{259C}',
            "QUADRANT UPPER LEFT AND UPPER RIGHT AND LOWER RIGHT",
        ),
        ('\u{259D}', "QUADRANT UPPER RIGHT"),
        ('\u{259E}', "QUADRANT UPPER RIGHT AND LOWER LEFT"),
        (
            '\u{259F}',
            "QUADRANT UPPER RIGHT AND LOWER LEFT AND LOWER RIGHT",
        ),
        ('\u{1FB82}', "UPPER ONE QUARTER BLOCK"),
        ('\u{1FB85}', "UPPER THREE QUARTERS BLOCK"),
        ('\u{1FBE6}', "MIDDLE LEFT ONE QUARTER BLOCK"),
        ('\u{1FBE7}', "MIDDLE RIGHT ONE QUARTER BLOCK"),
        ('\u{1CEA0}', "RIGHT HALF LOWER ONE QUARTER BLOCK"),
        ('\u{1CEA3}', "LEFT HALF LOWER ONE QUARTER BLOCK"),
        ('\u{1CEA8}', "LEFT HALF UPPER ONE QUARTER BLOCK"),
        ('\u{1CEAB}', "RIGHT HALF UPPER ONE QUARTER BLOCK"),
    ];

    /// A character's Unicode name: from [`NAMES`], or by the sextant and octant runs' rule —
    /// "BLOCK SEXTANT-" / "BLOCK OCTANT-" and the cell numbers, in increasing order of the
    /// numbers read as a binary mask, skipping patterns drawn by the characters in [`NAMES`].
    fn name(c: char) -> String {
        if let Some(&(_, n)) = NAMES.iter().find(|&&(k, _)| k == c) {
            return n.to_owned();
        }
        let cp = u32::from(c);
        let (word, base, bits) = match cp {
            0x1FB00..=0x1FB3B => ("SEXTANT", 0x1FB00, 6),
            0x1CD00..=0x1CDE5 => ("OCTANT", 0x1CD00, 8),
            _ => panic!("U+{cp:04X} is not a block character"),
        };
        // The run's n-th pattern: the n-th mask (from 1) whose shape no named character draws.
        let drawn_elsewhere = |m: u32| -> bool {
            NAMES
                .iter()
                .any(|&(_, n)| shape_of_name(n, bits) == Some(m as u8))
        };
        let mask = (1..(1u32 << bits))
            .filter(|&m| !drawn_elsewhere(m))
            .nth((cp - base) as usize)
            .expect("in the run");
        let cells: String = (0..bits)
            .filter(|b| mask & (1 << b) != 0)
            .map(|b| char::from(b'1' + b as u8))
            .collect();
        format!("BLOCK {word}-{cells}")
    }

    /// The pixels (mask over `bits` = 6 or 8 pixels, 2 columns) that a block character's name
    /// describes, read from its words: which half or quadrant, which quarter rows, or the
    /// numbered cells of "BLOCK SEXTANT-…" / "BLOCK OCTANT-…".
    fn shape_of_name(name: &str, bits: u32) -> Option<u8> {
        let rows = bits / 2;
        let col = |c: u32| -> u32 { (0..rows).map(|r| 1 << (2 * r + c)).sum() };
        // Rows top..bottom as fractions of the cell: [from, to).
        let band = |from: f64, to: f64| -> u32 {
            (0..rows)
                .filter(|&r| {
                    let mid = (f64::from(r) + 0.5) / f64::from(rows);
                    mid > from && mid < to
                })
                .map(|r| 3 << (2 * r))
                .sum()
        };
        let full = (1u32 << bits) - 1;
        if let Some(cells) = name
            .strip_prefix("BLOCK SEXTANT-")
            .or_else(|| name.strip_prefix("BLOCK OCTANT-"))
        {
            return cells
                .bytes()
                .map(|d| 1u32 << (d - b'1'))
                .sum::<u32>()
                .try_into()
                .ok();
        }
        let m: u32 = match name {
            "SPACE" => 0,
            "FULL BLOCK" => full,
            "UPPER HALF BLOCK" => band(0.0, 0.5),
            "LOWER HALF BLOCK" => band(0.5, 1.0),
            "LEFT HALF BLOCK" => col(0),
            "RIGHT HALF BLOCK" => col(1),
            "UPPER ONE QUARTER BLOCK" => band(0.0, 0.25),
            "LOWER ONE QUARTER BLOCK" => band(0.75, 1.0),
            "UPPER THREE QUARTERS BLOCK" => band(0.0, 0.75),
            "LOWER THREE QUARTERS BLOCK" => band(0.25, 1.0),
            "MIDDLE LEFT ONE QUARTER BLOCK" => band(0.25, 0.75) & col(0),
            "MIDDLE RIGHT ONE QUARTER BLOCK" => band(0.25, 0.75) & col(1),
            "LEFT HALF UPPER ONE QUARTER BLOCK" => band(0.0, 0.25) & col(0),
            "RIGHT HALF UPPER ONE QUARTER BLOCK" => band(0.0, 0.25) & col(1),
            "LEFT HALF LOWER ONE QUARTER BLOCK" => band(0.75, 1.0) & col(0),
            "RIGHT HALF LOWER ONE QUARTER BLOCK" => band(0.75, 1.0) & col(1),
            q => {
                let parts = q.strip_prefix("QUADRANT ")?;
                parts
                    .split(" AND ")
                    .map(|p| {
                        let (v, h) = p.split_once(' ').expect("two words");
                        let rows = if v == "UPPER" {
                            band(0.0, 0.5)
                        } else {
                            band(0.5, 1.0)
                        };
                        rows & col(u32::from(h == "RIGHT"))
                    })
                    .sum()
            }
        };
        // On a 3-row grid only whole columns are a shape (no band of rows is a half or quarter).
        let banded = ["UPPER", "LOWER", "MIDDLE"]
            .iter()
            .any(|w| name.contains(w));
        (!(banded && rows == 3)).then_some(m as u8)
    }

    /// Every mask's character is width 1, its name describes exactly that mask's pixels, and
    /// every character of the setting's set is used once.
    fn check(glyphs: Glyphs, bits: u32) {
        let mut seen = std::collections::HashSet::new();
        for m in 0..(1u32 << glyphs.pixels_per_cell()) {
            let c = glyph(glyphs, m as u8);
            assert_eq!(c.width(), Some(1), "U+{:04X}", u32::from(c));
            assert!(seen.insert(c), "{glyphs} U+{:04X} twice", u32::from(c));
            assert_eq!(mask_of(glyphs, c), Some(m as u8));
            let n = name(c);
            // Half-blocks and quadrants are checked on the octant grid (rows doubled).
            let want = match glyphs {
                Glyphs::Half => {
                    let row = |r: u32| {
                        if m & (1 << r) != 0 {
                            0x0F << (4 * r)
                        } else {
                            0
                        }
                    };
                    row(0) | row(1)
                }
                Glyphs::Quadrant => (0..4)
                    .filter(|b| m & (1 << b) != 0)
                    .map(|b: u32| 0b101u32 << ((b / 2) * 4 + b % 2))
                    .sum(),
                _ => m,
            };
            assert_eq!(
                shape_of_name(&n, bits).map(u32::from),
                Some(want),
                "{glyphs} mask {m:#x}: U+{:04X} {n}",
                u32::from(c)
            );
        }
    }

    #[test]
    fn half_blocks_match_their_names() {
        check(Glyphs::Half, 8);
    }

    #[test]
    fn quadrants_match_their_names() {
        check(Glyphs::Quadrant, 8);
    }

    #[test]
    fn sextants_match_their_names_and_fill_their_run() {
        check(Glyphs::Sextant, 6);
        assert_eq!(glyph(Glyphs::Sextant, 1), '\u{1FB00}');
        assert_eq!(name('\u{1FB00}'), "BLOCK SEXTANT-1");
        assert_eq!(glyph(Glyphs::Sextant, 62), '\u{1FB3B}');
        assert_eq!(name('\u{1FB3B}'), "BLOCK SEXTANT-23456");
        assert_eq!(name('\u{1FB13}'), "BLOCK SEXTANT-35");
        assert_eq!(name('\u{1FB14}'), "BLOCK SEXTANT-235");
    }

    #[test]
    fn octants_match_their_names_and_fill_their_run() {
        check(Glyphs::Octant, 8);
        // Spot checks written from the chart, independent of the run rule.
        assert_eq!(glyph(Glyphs::Octant, 0b100), '\u{1CD00}'); // BLOCK OCTANT-3
        assert_eq!(glyph(Glyphs::Octant, 0b1000), '\u{1CD03}'); // BLOCK OCTANT-4
        assert_eq!(glyph(Glyphs::Octant, 0xFE), '\u{1CDE5}'); // BLOCK OCTANT-2345678
        let in_run = (0..=255u8)
            .filter(|&m| (0x1CD00..=0x1CDE5).contains(&u32::from(glyph(Glyphs::Octant, m))))
            .count();
        assert_eq!(in_run, 230);
    }

    #[test]
    fn full_masks() {
        let f: Vec<u8> = Glyphs::ALL.iter().map(|&g| full_mask(g)).collect();
        assert_eq!(f, [3, 15, 63, 255]);
        assert!(Glyphs::ALL.iter().all(|&g| glyph(g, full_mask(g)) == '█'));
    }
}
