//! One floor or ceiling row where neither lamps nor moving lights shine (every map by day; at
//! night, a map without `LIGHT` lines or moving lights): the row's one shade for every pixel,
//! each map cell's paint looked up once per run of pixels in it, and a texture's sizes read once
//! per run, so a pixel costs its two coordinates, one texel and the shade. The pixels are the
//! same as the general caster's in [`super::raster`]: the same sums in the same order.

use crate::color::Rgb;
use crate::render::fast_floor::fast_floor;
use crate::render::light::Shade;
use crate::vec2::Vec2;
use crate::world::{texel_index, Fill, World};

/// What one row of floor or ceiling shows at each pixel: the world, which surface, where the
/// row's first pixel lands and how far each next pixel steps, and the row's shade.
pub(crate) struct PlainRow<'a> {
    /// Paints and textures.
    pub world: &'a World,
    /// Floor (below the horizon) or ceiling.
    pub is_floor: bool,
    /// The map point pixel 0 shows.
    pub start: Vec2,
    /// How far the map point moves from one pixel to the next.
    pub step: Vec2,
    /// The row's light (one distance for the whole row).
    pub shade: Shade,
}

impl PlainRow<'_> {
    /// Paints every pixel of `row` for which `open(x)` holds (the others belong to walls).
    pub fn paint(&self, row: &mut [Rgb], open: impl Fn(usize) -> bool) {
        let w = row.len();
        let mut x = 0;
        while x < w {
            if !open(x) {
                x += 1;
                continue;
            }
            let (fx, fy) = self.at(x);
            let cell = (fast_floor(fx), fast_floor(fy));
            // The pixels from `x` up to `end` lie in this map cell (they may still be walls').
            let end = self.run_end(x, cell, w);
            match self.world.surface_fill(cell.0, cell.1, self.is_floor) {
                Fill::Colour(c) => {
                    let c = self.shade.apply(c);
                    while x < end && open(x) {
                        row[x] = c;
                        x += 1;
                    }
                }
                Fill::Texture(t) => {
                    let texels = t.texels();
                    let (tw, th) = (t.width(), t.height());
                    let (wf, hf) = (tw as f64, th as f64);
                    let (ci, cj) = (cell.0 as f64, cell.1 as f64);
                    while x < end && open(x) {
                        let (fx, fy) = self.at(x);
                        let tx = texel_index((fx - ci) * wf).min(tw - 1);
                        let ty = texel_index((fy - cj) * hf).min(th - 1);
                        row[x] = self.shade.apply(texels[tx * th + ty]);
                        x += 1;
                    }
                }
            }
        }
    }

    /// The map point pixel `x` shows (the general caster's sums, in its order).
    #[inline]
    fn at(&self, x: usize) -> (f64, f64) {
        let x = x as f64;
        (
            self.start.x + self.step.x * x,
            self.start.y + self.step.y * x,
        )
    }

    /// The first pixel after `x` (at most `w`) that lies outside map cell `cell`, where pixel
    /// `x` lies inside it. Each coordinate is a sum of a constant and a multiple of the pixel
    /// number, rounded, so it never turns back along the row: the pixels of one cell are one
    /// run. Its end is worked out where the row crosses the cell's edges, then moved a pixel at a
    /// time until the exact sums agree (by none or one pixel on a map; far off it, where the
    /// coordinates run past 2⁵³, by more).
    fn run_end(&self, x: usize, cell: (i64, i64), w: usize) -> usize {
        let inside = |p: usize| {
            let (fx, fy) = self.at(p);
            (fast_floor(fx), fast_floor(fy)) == cell
        };
        let mut end = w;
        for (start, step, c) in [
            (self.start.x, self.step.x, cell.0),
            (self.start.y, self.step.y, cell.1),
        ] {
            let edge = if step > 0.0 {
                c as f64 + 1.0
            } else if step < 0.0 {
                c as f64
            } else {
                continue;
            };
            let cross = ((edge - start) / step).ceil();
            if cross < end as f64 {
                end = (cross.max(x as f64 + 1.0)) as usize;
            }
        }
        let mut end = end.clamp(x + 1, w);
        while end > x + 1 && !inside(end - 1) {
            end -= 1;
        }
        while end < w && inside(end) {
            end += 1;
        }
        end
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::Cell;

    /// A pixel cast alone, as the general caster in [`super::raster`] does: the map cell's zone,
    /// its paint, then the texel.
    fn each_pixel(r: &PlainRow, x: usize) -> Rgb {
        let xf = x as f64;
        let (fx, fy) = (r.start.x + r.step.x * xf, r.start.y + r.step.y * xf);
        let (ci, cj) = (fast_floor(fx), fast_floor(fy));
        let zone = match r.world.map.cell(ci, cj) {
            Cell::Floor { zone } => zone,
            _ => 0,
        };
        let paint = if r.is_floor {
            r.world.floor_paint(zone)
        } else {
            r.world.ceiling_paint(zone)
        };
        let texel = r.world.fill(paint).at_unit(fx - ci as f64, fy - cj as f64);
        r.shade.apply(texel)
    }

    /// The map cell pixel `x` lies in.
    fn cell_at(r: &PlainRow, x: usize) -> (i64, i64) {
        let (fx, fy) = r.at(x);
        (fast_floor(fx), fast_floor(fy))
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]
        /// Runs found from the cells' edges paint what casting each pixel alone paints: every
        /// direction along the row, starts on and off the map, steps from a pixel per cell to
        /// hundreds, on floors and ceilings, with walls' pixels left alone.
        #[test]
        fn runs_paint_what_each_pixel_alone_would(
            start in (-3.0f64..30.0, -3.0f64..30.0),
            far in 0u32..4,
            step in (-0.5f64..0.5, -0.5f64..0.5),
            tiny in 0u32..4,
            is_floor: bool,
            walls in proptest::collection::vec(0usize..300, 0..6),
            mul in 0u16..=256,
        ) {
            let world = World::default_world();
            // Some rows step along one axis only, or barely move.
            let step = match tiny {
                0 => Vec2::new(step.0, 0.0),
                1 => Vec2::new(0.0, step.1),
                2 => Vec2::new(step.0 * 1e-3, step.1 * 1e-3),
                _ => Vec2::new(step.0, step.1),
            };
            // Some rows lie far off the map, where rounding moves a run's estimated end most.
            let start = match far {
                0 => (start.0 * 1e11, start.1 * 1e11),
                1 => (start.0 + 4e12, start.1 - 7e12),
                _ => start,
            };
            let shade = Shade { mul, add: [3, 1, 2], keep: 200 };
            let start = Vec2::new(start.0, start.1);
            let r = PlainRow { world: &world, is_floor, start, step, shade };
            let marker = Rgb::new(1, 2, 3);
            let open = |x: usize| !walls.iter().any(|&w| x >= w && x < w + 7);
            let mut row = vec![marker; 300];
            r.paint(&mut row, open);
            for (x, &px) in row.iter().enumerate() {
                let want = if open(x) { each_pixel(&r, x) } else { marker };
                proptest::prop_assert_eq!(px, want, "pixel {}", x);
            }
        }

        /// Each run ends at the first pixel in another map cell, found here pixel by pixel.
        #[test]
        fn a_run_ends_at_the_first_pixel_in_another_cell(
            start in (-1e13f64..1e13, -1e13f64..1e13),
            scale in 0u32..3,
            step in (-0.5f64..0.5, -0.5f64..0.5),
        ) {
            let world = World::default_world();
            let k = [1e-12, 1e-6, 1.0][scale as usize];
            let start = Vec2::new(start.0 * k, start.1 * k);
            let step = Vec2::new(step.0, step.1);
            let r = PlainRow { world: &world, is_floor: true, start, step, shade: Shade::IDENTITY };
            let w = 200;
            let mut x = 0;
            while x < w {
                let cell = cell_at(&r, x);
                let want = (x + 1..w).find(|&p| cell_at(&r, p) != cell).unwrap_or(w);
                proptest::prop_assert_eq!(r.run_end(x, cell, w), want, "from {}", x);
                x = want;
            }
        }
    }
}
