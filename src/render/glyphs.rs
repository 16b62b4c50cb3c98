//! The glyph setting: how many pixels one terminal cell shows, and so the framebuffer's sub-grid.
//!
//! A terminal cell is taken to be twice as tall as it is wide. Half-blocks show 1×2 pixels per
//! cell, quadrants 2×2, sextants 2×3 and octants 2×4. The renderer draws at that grid with the
//! same camera; where the grid's pixels are not square on screen (quadrants: twice as tall as
//! wide; sextants: 4∶3) the vertical projection is scaled by [`Glyphs::pixel_height`], so a wall
//! seen face-on is square at every setting.

use std::fmt;
use std::str::FromStr;

/// Which block characters draw the 3-D view (half-blocks work everywhere; the others need a
/// font or a terminal that draws them).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Glyphs {
    /// `▀`/`▄`: 1×2 pixels per cell.
    #[default]
    Half,
    /// Quadrants (U+2596–259F and the half blocks): 2×2.
    Quadrant,
    /// Sextants (Unicode 13, U+1FB00–1FB3B): 2×3.
    Sextant,
    /// Octants (Unicode 16, U+1CD00–1CDE5): 2×4.
    Octant,
}

impl Glyphs {
    /// Every setting, coarsest first (the glyph key's cycle order).
    pub const ALL: [Glyphs; 4] = [
        Glyphs::Half,
        Glyphs::Quadrant,
        Glyphs::Sextant,
        Glyphs::Octant,
    ];

    /// Pixels per cell: (columns, rows).
    #[must_use]
    pub fn cell_size(self) -> (usize, usize) {
        match self {
            Glyphs::Half => (1, 2),
            Glyphs::Quadrant => (2, 2),
            Glyphs::Sextant => (2, 3),
            Glyphs::Octant => (2, 4),
        }
    }

    /// Pixels in one cell (the bits of its mask).
    #[must_use]
    pub fn pixels_per_cell(self) -> usize {
        let (c, r) = self.cell_size();
        c * r
    }

    /// A pixel's height over its width on screen, for a cell twice as tall as wide: 1 for
    /// half-blocks and octants, 2 for quadrants, 4/3 for sextants. The vertical projection
    /// divides the focal length by it.
    #[must_use]
    pub fn pixel_height(self) -> f64 {
        let (c, r) = self.cell_size();
        2.0 * c as f64 / r as f64
    }

    /// The next setting in the glyph key's cycle: half → quadrant → sextant → octant → half.
    #[must_use]
    pub fn cycled(self) -> Self {
        match self {
            Glyphs::Half => Glyphs::Quadrant,
            Glyphs::Quadrant => Glyphs::Sextant,
            Glyphs::Sextant => Glyphs::Octant,
            Glyphs::Octant => Glyphs::Half,
        }
    }

    /// The name on the command line, in config files, recordings and JSON.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Glyphs::Half => "half",
            Glyphs::Quadrant => "quadrant",
            Glyphs::Sextant => "sextant",
            Glyphs::Octant => "octant",
        }
    }
}

impl fmt::Display for Glyphs {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Glyphs {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "half" | "half-block" | "halfblock" => Ok(Glyphs::Half),
            "quadrant" | "quadrants" => Ok(Glyphs::Quadrant),
            "sextant" | "sextants" => Ok(Glyphs::Sextant),
            "octant" | "octants" => Ok(Glyphs::Octant),
            _ => Err(format!(
                "'{s}' is not a glyph setting (half, quadrant, sextant or octant)"
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_the_cycle_visits_all() {
        let mut g = Glyphs::Half;
        for want in Glyphs::ALL {
            assert_eq!(g, want);
            assert_eq!(g.name().parse::<Glyphs>(), Ok(g));
            g = g.cycled();
        }
        assert_eq!(g, Glyphs::Half);
        assert_eq!(
            "braille".parse::<Glyphs>().unwrap_err(),
            "'braille' is not a glyph setting (half, quadrant, sextant or octant)"
        );
    }

    #[test]
    fn pixels_are_square_for_half_and_octant_only() {
        let h: Vec<f64> = Glyphs::ALL.iter().map(|g| g.pixel_height()).collect();
        assert_eq!(h, [1.0, 2.0, 4.0 / 3.0, 1.0]);
        let n: Vec<usize> = Glyphs::ALL.iter().map(|g| g.pixels_per_cell()).collect();
        assert_eq!(n, [2, 4, 6, 8]);
    }
}
