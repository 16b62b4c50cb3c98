//! Framebuffer → one (top, bottom) code pair per cell at a colour level (mono: the shade character).

use super::level::ColorLevel;
use super::palette::{Code, Palette};
use crate::encode::shade::shade_char;
use crate::render::framebuffer::{Framebuffer, NEUTRAL_PHASE};

/// The mono glyph of a cell: the shade-ramp character of its two pixels' mean luminance.
#[must_use]
#[inline]
pub fn mono_char(top: crate::Rgb, bottom: crate::Rgb) -> char {
    shade_char(((u16::from(top.luma()) + u16::from(bottom.luma())) / 2) as u8)
}

/// Fills `cells` (row-major, `width × cell_rows`) with what each cell should show.
///
/// Colour levels give `[top code, bottom code]`; mono gives `[char, 0]`. At 256 and 16 colours
/// each pixel shows its colour's mix (`super::mixing`) thresholded by the dither phase its
/// surface wrote (a cell reads its upper pixel's), so patterns lie on the surfaces; cells no
/// surface wrote a phase for (floors, ceilings, frames from elsewhere) mix within the cell only.
pub fn quantize(palette: &Palette, fb: &Framebuffer, cells: &mut Vec<[Code; 2]>) {
    let (w, rows) = (fb.width(), fb.cell_rows());
    cells.clear();
    cells.reserve(w * rows);
    for cy in 0..rows {
        let (top, bottom) = (fb.row(2 * cy), fb.row(2 * cy + 1));
        match (palette.level(), fb.phases()) {
            (ColorLevel::Mono, _) => cells.extend(
                top.iter()
                    .zip(bottom)
                    .map(|(&t, &b)| [u32::from(mono_char(t, b)), 0]),
            ),
            (_, Some(phases)) if palette.mixes() => {
                let pt = &phases[2 * cy * w..(2 * cy + 1) * w];
                cells.extend(
                    top.iter()
                        .zip(bottom)
                        .zip(pt)
                        .map(|((&t, &b), &p)| palette.cell_at(t, b, p)),
                );
            }
            _ => cells.extend(
                top.iter()
                    .zip(bottom)
                    .map(|(&t, &b)| palette.cell_at(t, b, NEUTRAL_PHASE)),
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::{oklab, Rgb};
    use crate::render::dither_phase;

    /// A `w`×`h`-pixel field of colour `c`, with the phases a wall facing the camera writes (a
    /// lattice step of one pixel across and one cell up) when `patterned`.
    fn field(c: Rgb, w: usize, h: usize, patterned: bool) -> Framebuffer {
        let mut fb = Framebuffer::new(w, h);
        for y in 0..h {
            for x in 0..w {
                fb.set(x, y, c);
                if patterned {
                    fb.set_phase(x, y, dither_phase::at(x as i64, (y / 2) as i64));
                }
            }
        }
        fb
    }

    /// The OKLab colour of what the terminal shows for `fb` at `level`, blurred to one mean.
    fn shown_mean(level: ColorLevel, fb: &Framebuffer) -> [f32; 3] {
        let palette = Palette::new(level);
        let mut cells = Vec::new();
        quantize(&palette, fb, &mut cells);
        let mut acc = [0.0f32; 3];
        for c in &cells {
            for code in c {
                let l = palette.rgb(*code).linear();
                for i in 0..3 {
                    acc[i] += l[i];
                }
            }
        }
        let n = (2 * cells.len()) as f32;
        oklab(acc.map(|a| a / n))
    }

    fn hue_deg(a: [f32; 3], b: [f32; 3]) -> f32 {
        let cos = (a[1] * b[1] + a[2] * b[2]) / (a[1].hypot(a[2]) * b[1].hypot(b[2])).max(1e-9);
        cos.clamp(-1.0, 1.0).acos().to_degrees()
    }

    #[test]
    fn a_brown_a_dark_red_and_a_warm_grey_keep_their_hue() {
        // The nearest 256-colour entries of these are greys or far-off hues; the brown's and the
        // dark red's mixes keep the hue within 10° (measured 8.6° and 1.7–2.7°), on a wall's
        // pattern and within cells alone. The warm grey misses issue 20's 10°: on a wall's pattern
        // its mix (grey 128 with a share of 175/135/95) is 18.5° off, within cells alone (grey 128
        // with half 135/135/95) 29°, yellower; no pair of two entries does better without pulling
        // two hues side by side (olive with violet reaches 2°, as confetti), which the mixes now
        // charge for. This bound keeps it from getting worse.
        for (name, c, max) in [
            ("brown", Rgb::new(118, 78, 44), 10.0),
            ("dark red", Rgb::new(92, 22, 18), 10.0),
            ("warm grey", Rgb::new(132, 124, 112), 30.0),
        ] {
            let source = oklab(c.linear());
            for patterned in [true, false] {
                let shown = shown_mean(ColorLevel::Ansi256, &field(c, 16, 16, patterned));
                let err = hue_deg(source, shown);
                assert!(
                    err <= max,
                    "{name} (patterned {patterned}): hue off by {err:.1}°"
                );
            }
        }
    }

    #[test]
    fn a_warm_floor_with_no_pattern_shows_no_stripes_of_far_colours() {
        // Where no surface wrote a pattern a half share draws alternate pixel rows, fixed to the
        // screen: heights.cub's warm floor came out as grey and orange stripes (an entry 53 a/b
        // units off the colour). Along a ramp of such warm greys every entry a cell shows stays
        // near the colour (18 at most when this was written).
        let palette = Palette::new(ColorLevel::Ansi256);
        let lab = |c: Rgb| crate::encode::mix_solver::lab(c.linear());
        for r in 40..200u16 {
            let c = Rgb::new(r as u8, (r * 9 / 10) as u8, (r * 78 / 100) as u8);
            let (want, mix) = (lab(c), palette.half_mix_of(c).unwrap());
            for entry in [mix.a, mix.b] {
                let got = lab(palette.rgb(u32::from(entry)));
                let off = (got[1] - want[1]).hypot(got[2] - want[2]);
                assert!(off <= 25.0, "{c:?}: entry {entry} is {off:.1} off in a/b");
            }
        }
    }

    #[test]
    fn truecolor_cells_are_the_pixels() {
        let fb = field(Rgb::new(1, 2, 3), 4, 4, true);
        let mut cells = Vec::new();
        quantize(&Palette::new(ColorLevel::TrueColor), &fb, &mut cells);
        assert!(cells.iter().all(|c| *c == [0x010203, 0x010203]));
    }

    #[test]
    fn a_cell_depends_on_its_pixels_and_phase_only_never_on_its_place() {
        let palette = Palette::new(ColorLevel::Ansi256);
        let (t, b) = (Rgb::new(90, 60, 40), Rgb::new(70, 50, 45));
        for phase in [8, 40, 128, 248] {
            let here = palette.cell_at(t, b, phase);
            let mut fb = Framebuffer::new(24, 24);
            for y in 0..24 {
                for x in 0..24 {
                    fb.set(x, y, if y % 2 == 0 { t } else { b });
                    fb.set_phase(x, y, phase);
                }
            }
            let mut cells = Vec::new();
            quantize(&palette, &fb, &mut cells);
            assert!(cells.iter().all(|c| *c == here), "phase {phase}");
        }
    }
}
