//! What one terminal cell shows: a whole grapheme cluster (`e` + a combining accent, 👍 + a skin
//! tone), or nothing for the second column of a wide character.

use std::fmt;

use ratatui_core::buffer::CellWidth;
use unicode_segmentation::UnicodeSegmentation;

/// Bytes kept inline: a letter with two combining marks, or an emoji with a modifier, fits.
const INLINE: usize = 15;

/// One cell's grapheme cluster, compared whole (so `e\u{301}` differs from `e\u{300}`); empty
/// for the column a wide character covers. Short clusters are stored without allocating.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Glyph(Repr);

#[derive(Clone, PartialEq, Eq, Hash)]
enum Repr {
    Inline { len: u8, bytes: [u8; INLINE] },
    Heap(Box<str>),
}

impl Glyph {
    /// The second column of a wide character: shows no glyph of its own.
    pub const CONTINUATION: Glyph = Glyph(Repr::Inline {
        len: 0,
        bytes: [0; INLINE],
    });

    /// The cluster `s` (stored as given: a cell shows what it holds).
    #[must_use]
    pub fn new(s: &str) -> Self {
        if s.len() <= INLINE {
            let mut bytes = [0; INLINE];
            bytes[..s.len()].copy_from_slice(s.as_bytes());
            // Lossless: `s.len()` is at most `INLINE` here.
            Glyph(Repr::Inline {
                len: s.len() as u8,
                bytes,
            })
        } else {
            Glyph(Repr::Heap(s.into()))
        }
    }

    /// The cluster as text.
    #[must_use]
    pub fn as_str(&self) -> &str {
        match &self.0 {
            // Built from a `&str` cut at its own end, so always whole UTF-8.
            Repr::Inline { len, bytes } => {
                std::str::from_utf8(&bytes[..usize::from(*len)]).unwrap_or_default()
            }
            Repr::Heap(s) => s,
        }
    }

    /// The first character (a space for a continuation): what a one-`char` view of the cell shows.
    #[must_use]
    pub fn first_char(&self) -> char {
        self.as_str().chars().next().unwrap_or(' ')
    }

    /// Whether this is the covered second column of a wide character.
    #[must_use]
    pub fn is_continuation(&self) -> bool {
        self.as_str().is_empty()
    }

    /// Columns the cluster takes on screen (2 for a wide character, 0 for a continuation), by
    /// ratatui's own rule ([`width_of`]).
    #[must_use]
    pub fn width(&self) -> usize {
        width_of(self.as_str())
    }
}

/// The columns ratatui gives `cluster` in a `Buffer` (its `CellWidth`: `unicode-width`'s width
/// of the whole cluster, one column for any single byte), so a frame read back from bytes lays
/// out its cells where the buffer did.
#[must_use]
pub fn width_of(cluster: &str) -> usize {
    match cluster.len() {
        0 => 0,
        1 => 1,
        _ => usize::from(cluster.cell_width()),
    }
}

/// One grid row's glyphs as a terminal lays them out: a cell per grapheme cluster, plus a
/// continuation cell for each extra column a wide one takes.
pub(crate) fn glyph_row(row: &str) -> Vec<Glyph> {
    let mut glyphs = Vec::new();
    for g in row.graphemes(true) {
        glyphs.push(Glyph::new(g));
        for _ in 1..width_of(g) {
            glyphs.push(Glyph::CONTINUATION);
        }
    }
    glyphs
}

impl From<char> for Glyph {
    fn from(c: char) -> Self {
        Glyph::new(c.encode_utf8(&mut [0; 4]))
    }
}

impl From<&str> for Glyph {
    fn from(s: &str) -> Self {
        Glyph::new(s)
    }
}

impl PartialEq<char> for Glyph {
    fn eq(&self, c: &char) -> bool {
        self.as_str() == c.encode_utf8(&mut [0; 4])
    }
}

impl PartialEq<&str> for Glyph {
    fn eq(&self, s: &&str) -> bool {
        self.as_str() == *s
    }
}

impl fmt::Display for Glyph {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl fmt::Debug for Glyph {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.as_str(), f)
    }
}

impl Default for Glyph {
    /// A space: what an empty terminal cell shows.
    fn default() -> Self {
        Glyph::from(' ')
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_clusters_compare_whole() {
        assert_ne!(Glyph::new("e\u{301}"), Glyph::new("e\u{300}"));
        assert_ne!(Glyph::new("👍🏽"), Glyph::new("👍🏿"));
        assert_eq!(Glyph::new("👍🏽").width(), 2);
        let family = "👨\u{200d}👩\u{200d}👧\u{200d}👦";
        assert_eq!(Glyph::new(family).as_str(), family);
        assert_eq!(Glyph::from('▀'), '▀');
        assert!(Glyph::CONTINUATION.is_continuation());
        assert_eq!(Glyph::new("🇯🇵").width(), 2);
        assert_eq!(Glyph::new(family).width(), 2);
        assert_eq!(Glyph::new("1\u{fe0f}\u{20e3}").width(), 2);
        assert_eq!(Glyph::CONTINUATION.first_char(), ' ');
    }
}
