//! The pixel grid every renderer writes and every output reads: W × 2H for a W × H-cell view
//! in half-blocks, or the finer sub-grid of another [`Glyphs`] setting (2W × 2H, 2W × 3H, 2W × 4H).

use std::sync::Arc;

use crate::color::Rgb;
use crate::render::glyphs::Glyphs;
use crate::render::light::{Lighting, ShadeTable};

/// Row-major RGB pixels; two pixel rows make one terminal cell row.
///
/// A rendered frame also carries a dither phase per pixel (see [`Framebuffer::phases`]); frames
/// from elsewhere (PNG files) have none. Equality compares the picture only.
#[derive(Debug, Clone)]
pub struct Framebuffer {
    width: usize,
    height: usize,
    pixels: Vec<Rgb>,
    /// Per-pixel dither phase, tied to the surface the pixel shows; `None` until a renderer
    /// writes one.
    phases: Option<Vec<u8>>,
    /// Whether renderers write phases at all ([`Framebuffer::wants_phases`]).
    phases_wanted: bool,
    /// How many pixels a terminal cell shows (half-blocks unless made for another setting).
    glyphs: Glyphs,
    /// The last frame's distance table and the light it samples, reused while the light stays.
    shades: Option<(Lighting, Arc<ShadeTable>)>,
}

impl PartialEq for Framebuffer {
    /// Same size and pixels: the phases are a hint to the encoder, not part of the picture.
    fn eq(&self, other: &Self) -> bool {
        (self.width, self.height) == (other.width, other.height) && self.pixels == other.pixels
    }
}

impl Eq for Framebuffer {}

/// The phase of a pixel no surface wrote: mid-range, so a threshold rounds to the nearer colour.
pub const NEUTRAL_PHASE: u8 = 128;

impl Framebuffer {
    /// A black framebuffer of `width` × `height` pixels.
    #[must_use]
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            pixels: vec![Rgb::default(); width * height],
            phases: None,
            phases_wanted: true,
            glyphs: Glyphs::Half,
            shades: None,
        }
    }

    /// The framebuffer for `cols` × `rows` cells drawn with `glyphs`: each cell is that setting's
    /// pixels (1×2, 2×2, 2×3 or 2×4).
    #[must_use]
    pub fn for_glyphs(cols: u16, rows: u16, glyphs: Glyphs) -> Self {
        let (c, r) = glyphs.cell_size();
        let mut fb = Self::new(usize::from(cols) * c, usize::from(rows) * r);
        fb.glyphs = glyphs;
        fb
    }

    /// Resizes to `cols` × `rows` cells at `glyphs` only when that changes anything (contents
    /// become black then), so per-frame reuse is free.
    pub fn resize_cells(&mut self, cols: u16, rows: u16, glyphs: Glyphs) {
        let (c, r) = glyphs.cell_size();
        let size = (usize::from(cols) * c, usize::from(rows) * r);
        if (size, glyphs) != ((self.width, self.height), self.glyphs) {
            self.renew(Self::for_glyphs(cols, rows, glyphs));
        }
    }

    /// Becomes `fresh` (a new size or glyph setting) but keeps whether phases are wanted: that
    /// is the caller's choice, not part of the picture.
    fn renew(&mut self, fresh: Self) {
        *self = Self {
            phases_wanted: self.phases_wanted,
            ..fresh
        };
    }

    /// Whether renderers should write dither phases. Only an encoder that draws colours as mixes
    /// of palette entries (256 and 16 colours) reads them, so a caller that shows frames at
    /// truecolor or in mono turns them off and the renderers skip that work (about a tenth of
    /// a render). On by default.
    #[must_use]
    pub fn wants_phases(&self) -> bool {
        self.phases_wanted
    }

    /// Sets [`Framebuffer::wants_phases`]; turning them off drops the phases already written.
    pub fn set_phases_wanted(&mut self, wanted: bool) {
        self.phases_wanted = wanted;
        if !wanted {
            self.phases = None;
        }
    }

    /// The distance table for `light`: the one kept from the last frame drawn here while the
    /// light is the same (building it was a few % of a small frame's time), else a new one.
    pub fn shade_table(&mut self, light: &Lighting) -> Arc<ShadeTable> {
        match &self.shades {
            Some((kept, table)) if kept == light => Arc::clone(table),
            _ => {
                let table = Arc::new(ShadeTable::new(light));
                self.shades = Some((*light, Arc::clone(&table)));
                table
            }
        }
    }

    /// The glyph setting whose sub-grid these pixels are.
    #[must_use]
    pub fn glyphs(&self) -> Glyphs {
        self.glyphs
    }

    /// A pixel's height over its width on screen ([`Glyphs::pixel_height`]): what the
    /// renderers divide the vertical focal length by, so walls stay square.
    #[must_use]
    pub fn pixel_height(&self) -> f64 {
        self.glyphs.pixel_height()
    }

    /// Terminal columns this framebuffer covers.
    #[must_use]
    pub fn cell_cols(&self) -> usize {
        self.width / self.glyphs.cell_size().0
    }

    /// The framebuffer for a terminal area of `cols` × `rows` cells (two pixel rows per cell).
    #[must_use]
    pub fn for_cells(cols: u16, rows: u16) -> Self {
        Self::new(usize::from(cols), usize::from(rows) * 2)
    }

    /// Width in pixels (= terminal columns).
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels (= 2 × terminal rows).
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    /// Resizes (contents become black, half-blocks) only when the size changed, so per-frame
    /// reuse is free.
    pub fn resize(&mut self, width: usize, height: usize) {
        if (width, height, Glyphs::Half) != (self.width, self.height, self.glyphs) {
            self.renew(Self::new(width, height));
        }
    }

    /// The pixel at (x, y).
    #[must_use]
    #[inline]
    pub fn get(&self, x: usize, y: usize) -> Rgb {
        self.pixels[y * self.width + x]
    }

    /// Sets the pixel at (x, y).
    #[inline]
    pub fn set(&mut self, x: usize, y: usize, c: Rgb) {
        self.pixels[y * self.width + x] = c;
    }

    /// One pixel row, left to right.
    #[must_use]
    pub fn row(&self, y: usize) -> &[Rgb] {
        &self.pixels[y * self.width..(y + 1) * self.width]
    }

    /// Rows `rows` of column `x`, top to bottom (those inside the frame): what a wall stripe
    /// paints, without a bounds check or a multiply per pixel.
    pub fn column_mut(
        &mut self,
        x: usize,
        rows: std::ops::Range<usize>,
    ) -> impl Iterator<Item = &mut Rgb> {
        let w = self.width.max(1);
        let n = if x < self.width { rows.len() } else { 0 };
        let first = (rows.start * w + x).min(self.pixels.len());
        self.pixels[first..].iter_mut().step_by(w).take(n)
    }

    /// One pixel row, writable (the floor caster fills rows).
    pub fn row_mut(&mut self, y: usize) -> &mut [Rgb] {
        &mut self.pixels[y * self.width..(y + 1) * self.width]
    }

    /// All pixels, row-major.
    #[must_use]
    pub fn pixels(&self) -> &[Rgb] {
        &self.pixels
    }

    /// The dither phases, row-major, when a renderer wrote them: each pixel's value (0–255) is
    /// tied to the point of the surface it shows (texel, floor position), so a threshold pattern
    /// read from it moves with the surface rather than staying fixed to the screen.
    #[must_use]
    pub fn phases(&self) -> Option<&[u8]> {
        self.phases.as_deref()
    }

    /// One pixel row of phases, created (all `NEUTRAL_PHASE`) on first use: what renderers write.
    pub fn phase_row_mut(&mut self, y: usize) -> &mut [u8] {
        let n = self.width * self.height;
        let phases = self.phases.get_or_insert_with(|| vec![NEUTRAL_PHASE; n]);
        &mut phases[y * self.width..(y + 1) * self.width]
    }

    /// The whole plane of phases, row-major, created (all `NEUTRAL_PHASE`) on first use: for
    /// renderers that write down a column.
    pub fn phases_mut(&mut self) -> &mut [u8] {
        let n = self.width * self.height;
        self.phases.get_or_insert_with(|| vec![NEUTRAL_PHASE; n])
    }

    /// Sets the phase at (x, y) (creating the plane on first use).
    #[inline]
    pub fn set_phase(&mut self, x: usize, y: usize, phase: u8) {
        self.phase_row_mut(y)[x] = phase;
    }

    /// Drops the phases (the frame then encodes as a frame from elsewhere would).
    pub fn clear_phases(&mut self) {
        self.phases = None;
    }

    /// The two pixels a terminal cell (cx, cy) shows: (upper, lower).
    #[must_use]
    #[inline]
    pub fn cell(&self, cx: usize, cy: usize) -> (Rgb, Rgb) {
        (self.get(cx, 2 * cy), self.get(cx, 2 * cy + 1))
    }

    /// Number of whole terminal rows this framebuffer covers.
    #[must_use]
    pub fn cell_rows(&self) -> usize {
        self.height / self.glyphs.cell_size().1
    }

    /// Encodes as an RGB PNG of exactly width × height pixels.
    ///
    /// # Errors
    /// The encoder's message if `image` fails.
    pub fn to_png(&self) -> Result<Vec<u8>, String> {
        crate::png::rgb(self.width, self.height, |x, y| self.get(x, y))
    }

    /// Decodes a PNG (or other readable image) into a framebuffer, for diffs and `bench --frames`.
    ///
    /// # Errors
    /// The decoder's message when the bytes are not an image.
    pub fn from_image_bytes(bytes: &[u8]) -> Result<Self, String> {
        let img = image::load_from_memory(bytes)
            .map_err(|e| e.to_string())?
            .to_rgb8();
        Ok(Self::from_image(&img))
    }

    /// A framebuffer holding a decoded image's pixels (for images decoded within limits).
    #[must_use]
    pub fn from_image(img: &image::RgbImage) -> Self {
        let pixels = img.pixels().map(|p| Rgb::new(p[0], p[1], p[2])).collect();
        Self {
            width: img.width() as usize,
            height: img.height() as usize,
            pixels,
            phases: None,
            phases_wanted: true,
            glyphs: Glyphs::Half,
            shades: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_column_is_its_pixels_top_to_bottom_and_stops_at_the_frame() {
        let mut fb = Framebuffer::for_cells(3, 2);
        for (i, px) in fb.column_mut(1, 1..3).enumerate() {
            *px = Rgb::new(i as u8 + 1, 0, 0);
        }
        assert_eq!(fb.get(1, 0), Rgb::default());
        assert_eq!(fb.get(1, 1), Rgb::new(1, 0, 0));
        assert_eq!(fb.get(1, 2), Rgb::new(2, 0, 0));
        assert_eq!(fb.get(1, 3), Rgb::default());
        assert_eq!(fb.get(0, 1), Rgb::default());
        assert_eq!(fb.column_mut(1, 1..3).count(), 2);
        assert_eq!(fb.column_mut(2, 3..9).count(), 1);
        assert_eq!(fb.column_mut(1, 4..4).count(), 0);
        assert_eq!(fb.column_mut(3, 0..4).count(), 0);
    }

    #[test]
    fn the_shade_table_is_kept_while_the_light_stays_and_made_anew_when_it_changes() {
        let mut fb = Framebuffer::for_cells(3, 2);
        let fog = Lighting {
            fog: Some(crate::map::Fog {
                colour: Rgb::new(10, 20, 30),
                density: 0.3,
            }),
            ..Lighting::default()
        };
        let first = fb.shade_table(&fog);
        assert!(Arc::ptr_eq(&first, &fb.shade_table(&fog)));
        assert_eq!(*first, ShadeTable::new(&fog));
        let night = Lighting { night: true, ..fog };
        let other = fb.shade_table(&night);
        assert_eq!(*other, ShadeTable::new(&night));
        assert_ne!(*other, *first);
        assert_eq!(*fb.shade_table(&fog), ShadeTable::new(&fog));
    }

    #[test]
    fn cell_reads_upper_and_lower_pixel() {
        let mut fb = Framebuffer::for_cells(3, 2);
        fb.set(1, 2, Rgb::new(1, 2, 3));
        fb.set(1, 3, Rgb::new(4, 5, 6));
        assert_eq!(fb.cell(1, 1), (Rgb::new(1, 2, 3), Rgb::new(4, 5, 6)));
        assert_eq!((fb.width(), fb.height(), fb.cell_rows()), (3, 4, 2));
    }

    #[test]
    fn png_round_trip() {
        let mut fb = Framebuffer::new(4, 6);
        fb.set(3, 5, Rgb::new(9, 8, 7));
        let back = Framebuffer::from_image_bytes(&fb.to_png().unwrap()).unwrap();
        assert_eq!(back, fb);
    }
}
