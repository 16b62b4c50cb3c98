//! Frames at a finer glyph setting (quadrants, sextants, octants): each cell becomes a mask and
//! two colours ([`super::glyph_cell`]), mapped to the colour level's codes, diffed against what
//! the terminal shows, and sent with the fewest colour changes.
//!
//! A cell is glyph + fg + bg. Every mask has its complement in the same set, so each changed
//! cell may be sent either way round (`mask` in fg-on-bg, or its complement with the colours
//! swapped); the writer takes whichever keeps more of the current pen, and a one-colour cell
//! is a space on that background or `█` in that foreground, whichever is already set.

use super::cursor::{write_move, Cursor};
use super::glyph_cell::{canonical, choose, choose_all, GlyphCell, MAX_PIXELS};
use super::glyph_mask::{full_mask, glyph};
use super::level::ColorLevel;
use super::palette::{distance, Code, Palette, DEFAULT, UNKNOWN};
use super::sgr;
use crate::color::Rgb;
use crate::render::framebuffer::{Framebuffer, NEUTRAL_PHASE};
use crate::render::glyphs::Glyphs;

/// A cell as codes of one colour level: `mask`'s set bits show `fg`. Canonical like
/// [`GlyphCell`] (bit 0 clear; one colour = mask 0 and `fg == bg`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CodedCell {
    /// Which pixels show the foreground.
    pub mask: u8,
    /// Foreground code.
    pub fg: Code,
    /// Background code.
    pub bg: Code,
}

/// What the encoder believes a cell shows before it has sent it.
const UNSEEN: CodedCell = CodedCell {
    mask: 0,
    fg: UNKNOWN,
    bg: UNKNOWN,
};

impl CodedCell {
    /// `cell`'s colours as `palette` codes, canonical again (two colours may meet in one code).
    #[must_use]
    pub fn of(cell: GlyphCell, palette: &Palette) -> Self {
        let (fg, bg) = (palette.code(cell.fg), palette.code(cell.bg));
        if fg == bg || cell.mask == 0 {
            Self {
                mask: 0,
                fg: bg,
                bg,
            }
        } else {
            Self {
                mask: cell.mask,
                fg,
                bg,
            }
        }
    }
}

impl CodedCell {
    /// The cell that shows `pixels` at a level that mixes (256 and 16 colours) by the rules
    /// half-blocks follow (`docs/colour.md`): a pixel whose surface wrote a dither phase
    /// (`phases`, `NEUTRAL_PHASE` where none did) takes its colour's mix at that phase, so the
    /// pattern moves with the wall; any other pixel its colour's none/half/all mix at its place
    /// in the cell's pattern ([`cell_thresholds`]), so floors stay calm. A cell can show two
    /// codes: where its pixels ask for more, the two most asked for stay and every other pixel
    /// shows the one nearer its own colour.
    #[must_use]
    pub fn mixed(pixels: &[Rgb], phases: &[u8], thresholds: &[u8], palette: &Palette) -> Self {
        let n = pixels.len().min(MAX_PIXELS);
        let mut codes = [0u8; MAX_PIXELS];
        for i in 0..n {
            let mix = if phases[i] == NEUTRAL_PHASE {
                palette
                    .half_mix_of(pixels[i])
                    .map(|m| m.pick(thresholds[i]))
            } else {
                palette.mix_of(pixels[i]).map(|m| m.pick(phases[i] >> 4))
            };
            codes[i] = mix.unwrap_or(0);
        }
        // Each code asked for and how many pixels ask for it, in the order first asked.
        let mut asked = [(0u8, 0u8); MAX_PIXELS];
        let mut kinds = 0;
        for &k in &codes[..n] {
            match asked[..kinds].iter_mut().find(|(c, _)| *c == k) {
                Some((_, count)) => *count += 1,
                None => {
                    asked[kinds] = (k, 1);
                    kinds += 1;
                }
            }
        }
        // The two asked for most (the first asked on ties): `a` the more.
        let top = |skip: Option<usize>| {
            (0..kinds)
                .filter(|&i| Some(i) != skip)
                .max_by_key(|&i| (asked[i].1, std::cmp::Reverse(i)))
        };
        let first = top(None).unwrap_or(0);
        let a = asked[first].0;
        let Some(second) = top(Some(first)) else {
            let c = Code::from(a);
            return Self {
                mask: 0,
                fg: c,
                bg: c,
            };
        };
        let b = asked[second].0;
        let (ra, rb) = (palette.rgb(Code::from(a)), palette.rgb(Code::from(b)));
        let mut mask = 0u8;
        for i in 0..n {
            let shows_b = match codes[i] {
                k if k == b => true,
                k if k == a => false,
                _ => distance(pixels[i], rb) < distance(pixels[i], ra),
            };
            mask |= u8::from(shows_b) << i;
        }
        let (mask, fg, bg) = canonical(mask, Code::from(b), Code::from(a), n);
        Self { mask, fg, bg }
    }
}

/// Each pixel's threshold (sixteenths, row-major) in a cell at a finer glyph setting, for
/// [`CodedCell::mixed`]: a small ordered pattern, so a share of a mix shows on the nearest count
/// of the cell's pixels, spread over it (half of them is a checkerboard), and every cell of one
/// colour shows the same pattern.
#[must_use]
pub fn cell_thresholds(glyphs: Glyphs) -> &'static [u8] {
    match glyphs.cell_size() {
        (2, 2) => &[2, 10, 14, 6],
        (2, 3) => &[1, 9, 11, 3, 6, 14],
        (2, 4) => &[1, 9, 13, 5, 3, 11, 15, 7],
        _ => &[4, 12],
    }
}

/// Every cell of `fb` at `palette`'s level: at truecolor the cells [`glyph_cells`] chooses
/// (left in `chosen`), where the palette mixes [`CodedCell::mixed`] (`chosen` left empty).
pub fn coded_cells(
    fb: &Framebuffer,
    palette: &Palette,
    chosen: &mut Vec<GlyphCell>,
    out: &mut Vec<CodedCell>,
) {
    code_cells(fb, None, chosen, palette, out);
}

/// [`coded_cells`], with the truecolor choice taken from `given` when the caller already made
/// it (else made into `scratch`).
fn code_cells(
    fb: &Framebuffer,
    given: Option<&[GlyphCell]>,
    scratch: &mut Vec<GlyphCell>,
    palette: &Palette,
    out: &mut Vec<CodedCell>,
) {
    out.clear();
    if palette.mixes() {
        scratch.clear();
        mixed_cells(fb, palette, out);
        return;
    }
    let chosen = match given {
        Some(cells) => cells,
        None => {
            glyph_cells(fb, scratch);
            scratch
        }
    };
    // Truecolor: the colours are the codes.
    out.extend(chosen.iter().map(|&c| CodedCell::of(c, palette)));
}

/// Every cell of `fb` by [`CodedCell::mixed`], row-major.
fn mixed_cells(fb: &Framebuffer, palette: &Palette, out: &mut Vec<CodedCell>) {
    out.clear();
    let thresholds = cell_thresholds(fb.glyphs());
    let (c, r) = fb.glyphs().cell_size();
    let mut px = [Rgb::default(); MAX_PIXELS];
    let mut ph = [NEUTRAL_PHASE; MAX_PIXELS];
    for cy in 0..fb.cell_rows() {
        for cx in 0..fb.cell_cols() {
            let n = cell_pixels(fb, cx, cy, &mut px);
            if let Some(phases) = fb.phases() {
                for dy in 0..r {
                    for dx in 0..c {
                        ph[dy * c + dx] = phases[(cy * r + dy) * fb.width() + cx * c + dx];
                    }
                }
            }
            out.push(CodedCell::mixed(&px[..n], &ph[..n], thresholds, palette));
        }
    }
}

/// The pixels of cell (cx, cy) of a framebuffer at a glyph sub-grid, row-major.
pub fn cell_pixels(fb: &Framebuffer, cx: usize, cy: usize, out: &mut [Rgb; MAX_PIXELS]) -> usize {
    let (c, r) = fb.glyphs().cell_size();
    for dy in 0..r {
        for dx in 0..c {
            out[dy * c + dx] = fb.get(cx * c + dx, cy * r + dy);
        }
    }
    c * r
}

/// Every cell of `fb`, chosen ([`choose`]), row-major. A frame drawn by the view widget and
/// then sent by the presenter is chosen once by each; the presenter hands its own choice to
/// the encoder (`crate::encode::Encoder::encode_chosen`) rather than choosing again.
pub fn glyph_cells(fb: &Framebuffer, cells: &mut Vec<GlyphCell>) {
    match fb.glyphs().cell_size() {
        (2, 2) => cells_of::<2, 4>(fb, cells),
        (2, 3) => cells_of::<3, 6>(fb, cells),
        (2, 4) => cells_of::<4, 8>(fb, cells),
        _ => {
            let (cols, rows) = (fb.cell_cols(), fb.cell_rows());
            cells.clear();
            let mut px = [Rgb::default(); MAX_PIXELS];
            for cy in 0..rows {
                for cx in 0..cols {
                    let n = cell_pixels(fb, cx, cy, &mut px);
                    cells.push(choose(&px[..n]));
                }
            }
        }
    }
}

/// [`glyph_cells`] for cells two pixels wide and `R` tall (`N` = 2·`R` pixels), read a row
/// band at a time.
fn cells_of<const R: usize, const N: usize>(fb: &Framebuffer, cells: &mut Vec<GlyphCell>) {
    let (cols, rows) = (fb.cell_cols(), fb.cell_rows());
    cells.clear();
    cells.reserve(cols * rows);
    for cy in 0..rows {
        // Each row of the band as `cols` pixel pairs, cut to exactly `cols` so reading pair
        // `cx < cols` needs no bounds check.
        let band: [&[[Rgb; 2]]; R] =
            std::array::from_fn(|dy| &fb.row(cy * R + dy)[..2 * cols].as_chunks::<2>().0[..cols]);
        let pixels = (0..cols).map(|cx| std::array::from_fn(|i| band[i / 2][cx][i % 2]));
        choose_all::<N>(pixels, cells);
    }
}

/// The picture a list of cells shows, at their glyph sub-grid (what the terminal draws).
#[must_use]
pub fn picture(cells: &[GlyphCell], cols: usize, glyphs: Glyphs) -> Framebuffer {
    let (c, r) = glyphs.cell_size();
    let rows = cells.len() / cols.max(1);
    let mut fb = Framebuffer::for_glyphs(cols as u16, rows as u16, glyphs);
    for (i, cell) in cells.iter().enumerate() {
        let (cx, cy) = (i % cols, i / cols);
        for dy in 0..r {
            for dx in 0..c {
                fb.set(cx * c + dx, cy * r + dy, cell.pixel(dy * c + dx));
            }
        }
    }
    fb
}

/// A framebuffer at a finer sub-grid as half-blocks: each cell's upper and lower pixel is the
/// mean of the pixels whose centres lie in its upper or lower half (both, for a middle row).
#[must_use]
pub fn as_half_blocks(fb: &Framebuffer) -> Framebuffer {
    let (c, r) = fb.glyphs().cell_size();
    let (cols, rows) = (fb.cell_cols(), fb.cell_rows());
    let mut half = Framebuffer::for_cells(cols as u16, rows as u16);
    for cy in 0..rows {
        for cx in 0..cols {
            let part = |upper: bool| {
                let ys = (0..r).filter(move |&dy| {
                    let twice_centre = 2 * dy + 1;
                    if upper {
                        twice_centre <= r
                    } else {
                        twice_centre >= r
                    }
                });
                Rgb::mean(ys.flat_map(|dy| (0..c).map(move |dx| fb.get(cx * c + dx, cy * r + dy))))
            };
            half.set(cx, 2 * cy, part(true));
            half.set(cx, 2 * cy + 1, part(false));
        }
    }
    half
}

/// The live encoder's state for glyph frames: what each cell shows and should show.
#[derive(Debug, Default)]
pub(crate) struct GlyphFrames {
    glyphs: Glyphs,
    cols: usize,
    rows: usize,
    origin: (u16, u16),
    shown: Vec<CodedCell>,
    intent: Vec<CodedCell>,
    chosen: Vec<GlyphCell>,
    /// True until a frame was sent since creation, resize or `invalidate`.
    fresh: bool,
    /// The encoder's lossy `delta` lever (see [`super::EncodeOptions::delta`]).
    pub(crate) delta: Option<u8>,
}

impl GlyphFrames {
    /// Forgets what the terminal shows.
    pub(crate) fn invalidate(&mut self) {
        self.shown.fill(UNSEEN);
        self.fresh = true;
    }

    /// The picture the terminal shows after the last frame (palette colours), at the sub-grid.
    pub(crate) fn shown_frame(&self, palette: &Palette) -> Framebuffer {
        let cells: Vec<GlyphCell> = self
            .shown
            .iter()
            .map(|s| GlyphCell {
                mask: s.mask,
                fg: palette.rgb(s.fg),
                bg: palette.rgb(s.bg),
            })
            .collect();
        picture(&cells, self.cols, self.glyphs)
    }

    /// Appends to `out` the bytes that turn the view rectangle at `origin` into `fb` (nothing
    /// when nothing changed); `sync` wraps them in synchronized-output markers.
    ///
    /// `chosen`, when given, are `fb`'s cells as [`glyph_cells`] chooses them (a caller that
    /// already chose them for its own use); otherwise they are chosen here where the level needs
    /// them (truecolor: [`coded_cells`] says how the others are made). With
    /// [`GlyphFrames::delta`], a cell none of whose pixels moved by that much or more
    /// ([`distance`]) since it was sent is left as it is.
    pub(crate) fn encode(
        &mut self,
        fb: &Framebuffer,
        chosen: Option<&[GlyphCell]>,
        origin: (u16, u16),
        palette: &Palette,
        sync: bool,
        out: &mut Vec<u8>,
    ) {
        let (cols, rows, glyphs) = (fb.cell_cols(), fb.cell_rows(), fb.glyphs());
        if (cols, rows, glyphs, origin) != (self.cols, self.rows, self.glyphs, self.origin)
            || self.shown.len() != cols * rows
        {
            (self.cols, self.rows, self.glyphs, self.origin) = (cols, rows, glyphs, origin);
            self.shown.clear();
            self.shown.resize(cols * rows, UNSEEN);
            self.fresh = true;
        }
        code_cells(fb, chosen, &mut self.chosen, palette, &mut self.intent);
        let level = palette.level();
        let start = out.len();
        if sync {
            out.extend_from_slice(super::SYNC_BEGIN);
        }
        let mut pen = if self.fresh {
            (UNKNOWN, UNKNOWN)
        } else {
            (DEFAULT, DEFAULT)
        };
        let mut cursor = Cursor::Unknown;
        let mut drew = false;
        let full = full_mask(glyphs);
        for i in 0..self.intent.len() {
            let want = self.intent[i];
            let shown = self.shown[i];
            if shown == want
                || self
                    .delta
                    .is_some_and(|n| within(shown, want, full, n, palette))
            {
                continue;
            }
            let (x, y) = ((i % cols) as u16, (i / cols) as u16);
            let (col, row) = (origin.0 + x, origin.1 + y);
            write_move(out, cursor, col, row);
            let (ch, colours) = pick_form(want, pen, full, level);
            sgr::write(out, level, pen, colours);
            pen = colours;
            push_char(out, glyph(glyphs, ch));
            cursor = Cursor::At { col: col + 1, row };
            self.shown[i] = want;
            drew = true;
        }
        if !drew {
            out.truncate(start);
            return;
        }
        self.fresh = false;
        sgr::write(out, level, pen, (DEFAULT, DEFAULT));
        if sync {
            out.extend_from_slice(super::SYNC_END);
        }
    }
}

/// Appends `ch` in UTF-8. Copying `encode_utf8`'s slice is a `memcpy` call per cell (its
/// length is only known at run time); a copy of each fixed length is a move or two.
#[inline]
fn push_char(out: &mut Vec<u8>, ch: char) {
    let mut buf = [0u8; 4];
    match ch.encode_utf8(&mut buf).len() {
        1 => out.push(buf[0]),
        2 => out.extend_from_slice(&buf[..2]),
        3 => out.extend_from_slice(&buf[..3]),
        _ => out.extend_from_slice(&buf),
    }
}

/// Whether every pixel of a cell showing `shown` would move by less than `n` ([`distance`])
/// if it showed `want` instead: the lossy `--delta` lever at a finer glyph setting. A cell never
/// sent is never close.
fn within(shown: CodedCell, want: CodedCell, full: u8, n: u8, palette: &Palette) -> bool {
    if shown.fg == UNKNOWN || shown.bg == UNKNOWN {
        return false;
    }
    let near = |a: Code, b: Code| distance(palette.rgb(a), palette.rgb(b)) < u32::from(n);
    // The four ways a pixel can go (ink or paper, to ink or paper), each checked if some pixel
    // goes that way.
    let (s, w) = (shown.mask & full, want.mask & full);
    (s & w == 0 || near(shown.fg, want.fg))
        && (s & !w & full == 0 || near(shown.fg, want.bg))
        && (!s & w & full == 0 || near(shown.bg, want.fg))
        && (!s & !w & full == 0 || near(shown.bg, want.bg))
}

/// A whole glyph frame as printable lines (`render --format ansi`): every cell in the form
/// `GlyphFrames` would pick, each row ending with a colour reset and a newline.
#[must_use]
pub fn full_lines(fb: &Framebuffer, palette: &Palette) -> Vec<u8> {
    let glyphs = fb.glyphs();
    let (cols, level, full) = (fb.cell_cols(), palette.level(), full_mask(glyphs));
    let (mut chosen, mut cells) = (Vec::new(), Vec::new());
    coded_cells(fb, palette, &mut chosen, &mut cells);
    let mut out = Vec::with_capacity(cells.len() * 12);
    for row in cells.chunks(cols.max(1)) {
        let mut pen = (DEFAULT, DEFAULT);
        for &c in row {
            let (mask, colours) = pick_form(c, pen, full, level);
            sgr::write(&mut out, level, pen, colours);
            pen = colours;
            push_char(&mut out, glyph(glyphs, mask));
        }
        sgr::write(&mut out, level, pen, (DEFAULT, DEFAULT));
        out.push(b'\n');
    }
    out
}

/// The mask to send and the pen to send it with: the form of `cell` that changes the fewest
/// bytes of the current `pen`.
fn pick_form(
    cell: CodedCell,
    pen: (Code, Code),
    full: u8,
    level: ColorLevel,
) -> (u8, (Code, Code)) {
    if cell.mask == 0 {
        // One colour: a space on it, or a full block in it.
        let c = cell.bg;
        if pen.1 == c {
            return (0, pen);
        }
        if pen.0 == c {
            return (full, pen);
        }
        return (0, (pen.0, c));
    }
    let straight = (cell.fg, cell.bg);
    let turned = (cell.bg, cell.fg);
    let turned_mask = !cell.mask & full;
    if misdrawn(cell.mask, full) {
        return (turned_mask, turned);
    }
    if misdrawn(turned_mask, full) {
        return (cell.mask, straight);
    }
    if sgr::cost(level, pen, turned) < sgr::cost(level, pen, straight) {
        (turned_mask, turned)
    } else {
        (cell.mask, straight)
    }
}

/// Octant masks of one corner pixel, whose characters (the one-quarter blocks U+1CEA0, U+1CEA3,
/// U+1CEA8 and U+1CEAB) terminals that draw octants get wrong: VTE 0.78 draws them on a 4×4
/// grid, so a 10-pixel-wide cell splits 4 + 6 (measured, docs/output.md), and kitty before 0.47
/// leaves them to the font. Their complements are ordinary octants, so such a cell is always
/// sent the other way round.
const MISDRAWN_OCTANTS: [u8; 4] = [0x01, 0x02, 0x40, 0x80];

/// Whether `mask`, at a setting whose full mask is `full`, is one of [`MISDRAWN_OCTANTS`].
fn misdrawn(mask: u8, full: u8) -> bool {
    full == 0xFF && MISDRAWN_OCTANTS.contains(&mask)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::oklab;
    use crate::render::dither_phase;

    fn frame(glyphs: Glyphs, f: impl Fn(usize, usize) -> Rgb) -> Framebuffer {
        let mut fb = Framebuffer::for_glyphs(6, 3, glyphs);
        for y in 0..fb.height() {
            for x in 0..fb.width() {
                fb.set(x, y, f(x, y));
            }
        }
        fb
    }

    #[test]
    fn a_still_frame_sends_nothing_the_second_time() {
        for g in [Glyphs::Quadrant, Glyphs::Sextant, Glyphs::Octant] {
            let fb = frame(g, |x, y| Rgb::new((x * 37) as u8, (y * 11) as u8, 90));
            for level in [
                ColorLevel::TrueColor,
                ColorLevel::Ansi256,
                ColorLevel::Ansi16,
            ] {
                let p = Palette::new(level);
                let mut e = GlyphFrames::default();
                let mut out = Vec::new();
                e.encode(&fb, None, (0, 0), &p, true, &mut out);
                assert!(!out.is_empty());
                out.clear();
                e.encode(&fb, None, (0, 0), &p, true, &mut out);
                assert!(out.is_empty(), "{g} {level}");
            }
        }
    }

    #[test]
    fn with_delta_a_cell_is_resent_only_once_a_pixel_moved_that_far() {
        let p = Palette::new(ColorLevel::TrueColor);
        let base = |x: usize, y: usize| Rgb::new((x * 37) as u8, (y * 11) as u8, 90);
        let mut e = GlyphFrames {
            delta: Some(12),
            ..GlyphFrames::default()
        };
        let mut out = Vec::new();
        let send = |e: &mut GlyphFrames, fb: &Framebuffer, out: &mut Vec<u8>| {
            out.clear();
            e.encode(fb, None, (0, 0), &p, false, out);
        };
        send(&mut e, &frame(Glyphs::Octant, base), &mut out);
        assert!(!out.is_empty(), "the first frame is always sent");
        // Every pixel a little bluer (distance 2·4 = 8 < 12): nothing goes out.
        let bluer = |x, y| {
            let c = base(x, y);
            Rgb::new(c.r, c.g, c.b + 4)
        };
        send(&mut e, &frame(Glyphs::Octant, bluer), &mut out);
        assert!(out.is_empty(), "{}", String::from_utf8_lossy(&out));
        // One pixel much brighter: its cell alone is sent again.
        let one = |x, y| {
            if (x, y) == (3, 5) {
                Rgb::new(250, 250, 250)
            } else {
                bluer(x, y)
            }
        };
        send(&mut e, &frame(Glyphs::Octant, one), &mut out);
        let text = String::from_utf8_lossy(&out);
        assert_eq!(text.matches('H').count(), 1, "one cell moved to: {text}");
        assert!(text.starts_with("\x1b[2;2H"), "{text}");
        // Without delta the small move is sent.
        e.delta = None;
        send(&mut e, &frame(Glyphs::Octant, bluer), &mut out);
        assert!(!out.is_empty());
    }

    #[test]
    fn at_256_colours_a_brown_a_dark_red_and_a_warm_grey_keep_their_hue_in_every_glyph_cell() {
        // Each pixel takes its mix as in a half-block cell (a wall's phase, or the cell's own
        // pattern where none was written), so a flat colour keeps its mix's hue, measured as for
        // half-blocks: brown 7.6–8.6°, dark red 1.7–2.7°, warm grey 18.5° on a wall and 29° in
        // cells alone (encode::quantize's test says why it is yellower). Before, a cell's two
        // colours became their nearest entries and a flat brown showed grey.
        let hue = |a: [f32; 3], b: [f32; 3]| {
            let cos = (a[1] * b[1] + a[2] * b[2]) / (a[1].hypot(a[2]) * b[1].hypot(b[2]));
            cos.clamp(-1.0, 1.0).acos().to_degrees()
        };
        let p = Palette::new(ColorLevel::Ansi256);
        for (name, c, max) in [
            ("brown", Rgb::new(118, 78, 44), 10.0),
            ("dark red", Rgb::new(92, 22, 18), 10.0),
            ("warm grey", Rgb::new(132, 124, 112), 30.0),
        ] {
            let settings = [Glyphs::Quadrant, Glyphs::Sextant, Glyphs::Octant]
                .into_iter()
                .flat_map(|g| [(g, false), (g, true)]);
            for (g, patterned) in settings {
                let mut fb = frame(g, |_, _| c);
                if patterned {
                    // As a wall writes them: a surface lattice about a pixel fine.
                    for y in 0..fb.height() {
                        for x in 0..fb.width() {
                            fb.set_phase(x, y, dither_phase::at(x as i64, y as i64));
                        }
                    }
                }
                let (mut chosen, mut cells) = (Vec::new(), Vec::new());
                coded_cells(&fb, &p, &mut chosen, &mut cells);
                let n = g.cell_size().0 * g.cell_size().1;
                let mut light = [0.0f32; 3];
                for cell in &cells {
                    for i in 0..n {
                        let code = if cell.mask >> i & 1 == 1 {
                            cell.fg
                        } else {
                            cell.bg
                        };
                        let l = p.rgb(code).linear();
                        (0..3).for_each(|k| light[k] += l[k] / (n * cells.len()) as f32);
                    }
                }
                let err = hue(oklab(c.linear()), oklab(light));
                assert!(
                    err <= max,
                    "{name} at {g} (patterned {patterned}): hue off by {err:.1}°"
                );
                if !patterned {
                    // Every cell of a flat floor is the same cell: nothing moves while it stays.
                    assert!(cells.iter().all(|&k| k == cells[0]), "{name} at {g}");
                }
            }
        }
    }

    #[test]
    fn one_changed_pixel_resends_one_cell() {
        let mut fb = frame(Glyphs::Octant, |_, _| Rgb::new(10, 20, 30));
        let p = Palette::new(ColorLevel::TrueColor);
        let mut e = GlyphFrames::default();
        let mut out = Vec::new();
        e.encode(&fb, None, (2, 1), &p, false, &mut out);
        fb.set(3, 5, Rgb::new(255, 255, 255));
        out.clear();
        e.encode(&fb, None, (2, 1), &p, false, &mut out);
        // Cell (1, 1): pixel (1, 1) of it, bit 3 = BLOCK OCTANT-4, white on the old colour.
        assert_eq!(
            String::from_utf8(out).unwrap(),
            "\x1b[3;4H\x1b[38;2;255;255;255;48;2;10;20;30m\u{1CD03}\x1b[m"
        );
    }

    #[test]
    fn the_shown_picture_is_the_masks_in_their_colours() {
        let fb = frame(Glyphs::Quadrant, |x, y| {
            if (x + y) % 2 == 0 {
                Rgb::new(200, 0, 0)
            } else {
                Rgb::new(0, 0, 200)
            }
        });
        let p = Palette::new(ColorLevel::TrueColor);
        let mut e = GlyphFrames::default();
        e.encode(&fb, None, (0, 0), &p, false, &mut Vec::new());
        assert_eq!(e.shown_frame(&p), fb);
    }
}
