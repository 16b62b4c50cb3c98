//! How a reduced-colour frame looks to a person at a terminal: S-CIELAB (Zhang & Wandell, 1996),
//! the maths of `../shared/tools/scielab.py` in Rust, so `halfcast bench --json` prints the same
//! figures the tool checks (a test runs both on the same frames).
//!
//! At a terminal one half-block pixel is about 0.22° (an 8×16-px cell at 96 dpi seen from 60 cm),
//! about 4.5 pixels per degree (ppd), where the eye still resolves single pixels: dither shows as
//! noise. S-CIELAB filters luminance, red–green and blue–yellow (opponent channels that are zero for
//! greys) with the eye's own spreads at a given ppd, then takes the CIELAB distance per pixel.
//! 9 ppd stands for small fonts or a farther seat. Beside it: chroma kept and hue error of 4×4-pixel
//! blocks in OKLab (does the scene keep its colours?), and two baselines measured on the same
//! frame: each pixel the nearest palette colour in CIELAB, and Floyd–Steinberg as Pillow does it.

use crate::color::Rgb;
use crate::render::framebuffer::Framebuffer;

/// The two viewing conditions every figure is given at (pixels per degree of visual angle).
pub const PPDS: [f64; 2] = [4.5, 9.0];

/// The default map's views (x, y, angle in degrees) that `scielab.py --scenes` renders at
/// 120×40: the one list the colour tests and `examples/colour_figures.rs` judge by.
pub const DEFAULT_MAP_VIEWS: [(f64, f64, f64); 8] = [
    (15.5, 5.5, 90.0),
    (15.5, 5.5, 125.0),
    (15.5, 5.5, 0.0),
    (10.5, 8.5, 200.0),
    (20.5, 3.5, 270.0),
    (5.5, 5.5, 45.0),
    (12.5, 9.5, 160.0),
    (24.5, 9.5, 30.0),
];

/// sRGB (linear) → CIE XYZ (D65), as the tool writes it (four decimals).
const M_XYZ: [[f64; 3]; 3] = [
    [0.4124, 0.3576, 0.1805],
    [0.2126, 0.7152, 0.0722],
    [0.0193, 0.1192, 0.9505],
];

/// Each opponent channel's filter: weights and spreads (degrees) of its Gaussians.
const FILTERS: [&[(f64, f64)]; 3] = [
    &[(1.003_27, 0.05), (0.114_416, 0.225), (-0.117_686, 7.0)],
    &[(0.616_725, 0.0685), (0.383_275, 0.826)],
    &[(0.567_885, 0.0920), (0.432_115, 0.6451)],
];

/// Blocks whose source chroma (OKLab) is below this carry too little colour to judge.
const MIN_CHROMA: f64 = 0.03;

/// Fewer coloured blocks than this and chroma kept and hue error are not judged.
const MIN_BLOCKS: usize = 20;

/// A block's chroma ratio counts at most this much (one over-saturated block cannot hide grey ones).
const MAX_RATIO: f64 = 2.0;

/// The figures of one frame shown against its source (or a mean of frames).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Figures {
    /// Mean per-pixel CIELAB ΔE with no filtering.
    pub plain_de: f64,
    /// Mean S-CIELAB ΔE at 4.5 pixels per degree (a normal font and seat).
    pub scielab_45: f64,
    /// Mean S-CIELAB ΔE at 9 pixels per degree (small fonts or a farther seat).
    pub scielab_9: f64,
    /// Mean blurred chroma shown / source over coloured 4×4 blocks (1 keeps colourfulness, 0 is
    /// grey); `None` when fewer than 20 blocks carry colour.
    pub chroma_kept: Option<f64>,
    /// Mean angle (degrees) between the source's and the shown chroma directions over the same
    /// blocks; `None` as for `chroma_kept`.
    pub hue_error: Option<f64>,
}

/// An sRGB channel value in linear light, in double precision (the figures are compared with
/// the tool's to many digits).
fn lin(v: u8) -> f64 {
    let a = f64::from(v) / 255.0;
    if a <= 0.040_45 {
        a / 12.92
    } else {
        ((a + 0.055) / 1.055).powf(2.4)
    }
}

fn mat(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
}

/// The reference white's XYZ (the matrix applied to linear (1, 1, 1)).
fn white() -> [f64; 3] {
    mat(&M_XYZ, [1.0; 3])
}

fn xyz(c: Rgb) -> [f64; 3] {
    mat(&M_XYZ, [lin(c.r), lin(c.g), lin(c.b)])
}

/// CIE XYZ → CIELAB against [`white`].
fn lab(xyz: [f64; 3]) -> [f64; 3] {
    let w = white();
    let f = |t: f64| {
        if t > (6.0f64 / 29.0).powi(3) {
            t.max(0.0).cbrt()
        } else {
            t / (3.0 * (6.0f64 / 29.0).powi(2)) + 4.0 / 29.0
        }
    };
    let (fx, fy, fz) = (f(xyz[0] / w[0]), f(xyz[1] / w[1]), f(xyz[2] / w[2]));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

fn de(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// A one-dimensional Gaussian of spread `s` pixels (`exp(-x²/s²)`, radius ⌈3s⌉, at least 1),
/// normalised to sum 1.
fn gauss(s: f64) -> Vec<f64> {
    let r = (3.0 * s).ceil().max(1.0) as i64;
    let s2 = s.max(1e-6).powi(2);
    let g: Vec<f64> = (-r..=r).map(|x| (-((x * x) as f64) / s2).exp()).collect();
    let sum: f64 = g.iter().sum();
    g.into_iter().map(|v| v / sum).collect()
}

/// Index `i` (which may lie up to a kernel radius outside `0..n`) of a line padded symmetrically
/// (mirrored including the edge sample) when the radius is below `n`, else by repeating the edge.
fn padded(i: i64, n: i64, symmetric: bool) -> usize {
    let j = if !symmetric {
        i.clamp(0, n - 1)
    } else if i < 0 {
        -i - 1
    } else if i >= n {
        2 * n - 1 - i
    } else {
        i
    };
    j as usize
}

/// Convolves a `w`×`h` plane with `g` along rows, then along columns (each line padded as
/// [`padded`] says). Each output sums its taps in kernel order, as a plain dot product would;
/// the loops run tap by tap over whole lines so the inner loop is a contiguous multiply-add
/// (the figures are computed by every `bench` run and by the colour tests in debug builds).
fn conv2(plane: &[f64], w: usize, h: usize, g: &[f64]) -> Vec<f64> {
    if w == 0 || h == 0 {
        return Vec::new();
    }
    let r = (g.len() / 2) as i64;
    let mut tmp = vec![0.0; w * h];
    let sym_x = r < w as i64;
    let mut line = Vec::with_capacity(w + g.len());
    for (row, acc) in plane.chunks_exact(w).zip(tmp.chunks_exact_mut(w)) {
        line.clear();
        line.extend((0..(w + g.len() - 1) as i64).map(|i| row[padded(i - r, w as i64, sym_x)]));
        for (k, &gk) in g.iter().enumerate() {
            for (a, &v) in acc.iter_mut().zip(&line[k..k + w]) {
                *a += gk * v;
            }
        }
    }
    let mut out = vec![0.0; w * h];
    let sym_y = r < h as i64;
    for (y, acc) in out.chunks_exact_mut(w).enumerate() {
        for (k, &gk) in g.iter().enumerate() {
            let src = padded(y as i64 + k as i64 - r, h as i64, sym_y);
            for (a, &v) in acc.iter_mut().zip(&tmp[src * w..(src + 1) * w]) {
                *a += gk * v;
            }
        }
    }
    out
}

/// A frame's pixels as a `w`×`h` image of sRGB colours.
struct Image<'a> {
    w: usize,
    h: usize,
    px: &'a [Rgb],
}

/// The frame filtered as the eye sees it at `ppd`, in CIELAB, per pixel.
fn scielab(img: &Image, ppd: f64) -> Vec<[f64; 3]> {
    let w3 = white();
    let n = img.w * img.h;
    // Opponent channels that are zero for greys: Y, X/Xn − Y, Y − Z/Zn.
    let mut opp = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    for (i, &c) in img.px.iter().enumerate() {
        let [x, y, z] = xyz(c);
        opp[0][i] = y;
        opp[1][i] = x / w3[0] - y;
        opp[2][i] = y - z / w3[2];
    }
    let mut filtered = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    for (c, parts) in FILTERS.iter().enumerate() {
        for &(weight, spread) in *parts {
            let blurred = conv2(&opp[c], img.w, img.h, &gauss(spread * ppd));
            for (f, b) in filtered[c].iter_mut().zip(blurred) {
                *f += weight * b;
            }
        }
    }
    (0..n)
        .map(|i| {
            let (o1, o2, o3) = (filtered[0][i], filtered[1][i], filtered[2][i]);
            lab([w3[0] * (o2 + o1), o1, w3[2] * (o1 - o3)])
        })
        .collect()
}

/// OKLab of a linear-light colour in double precision (negative LMS clamps to 0, as the tool does).
fn oklab(l: [f64; 3]) -> [f64; 3] {
    let lms = [
        0.412_221_470_8 * l[0] + 0.536_332_536_3 * l[1] + 0.051_445_992_9 * l[2],
        0.211_903_498_2 * l[0] + 0.680_699_545_1 * l[1] + 0.107_396_956_6 * l[2],
        0.088_302_461_9 * l[0] + 0.281_718_837_6 * l[1] + 0.629_978_700_5 * l[2],
    ]
    .map(|v: f64| v.max(0.0).cbrt());
    [
        0.210_454_255_3 * lms[0] + 0.793_617_785 * lms[1] - 0.004_072_046_8 * lms[2],
        1.977_998_495_1 * lms[0] - 2.428_592_205 * lms[1] + 0.450_593_709_9 * lms[2],
        0.025_904_037_1 * lms[0] + 0.782_771_766_2 * lms[1] - 0.808_675_766 * lms[2],
    ]
}

/// The 4×4-block means of a frame in linear light, in OKLab (whole blocks only).
fn blocks(img: &Image) -> Vec<[f64; 3]> {
    let (bw, bh) = (img.w / 4, img.h / 4);
    let mut out = Vec::with_capacity(bw * bh);
    for by in 0..bh {
        for bx in 0..bw {
            let mut acc = [0.0; 3];
            for y in 4 * by..4 * by + 4 {
                for &c in &img.px[y * img.w + 4 * bx..y * img.w + 4 * bx + 4] {
                    for (a, v) in acc.iter_mut().zip([lin(c.r), lin(c.g), lin(c.b)]) {
                        *a += v;
                    }
                }
            }
            out.push(oklab(acc.map(|a| a / 16.0)));
        }
    }
    out
}

/// Chroma kept and hue error (degrees) of `shown` against `src` over blocks with colour.
fn chroma_hue(src: &Image, shown: &Image) -> (Option<f64>, Option<f64>) {
    let (a, b) = (blocks(src), blocks(shown));
    let (mut kept, mut hue, mut n) = (0.0, 0.0, 0usize);
    for (s, o) in a.iter().zip(&b) {
        let (cs, co) = (s[1].hypot(s[2]), o[1].hypot(o[2]));
        if cs < MIN_CHROMA {
            continue;
        }
        n += 1;
        kept += (co / cs).min(MAX_RATIO);
        let cos = (s[1] * o[1] + s[2] * o[2]) / (cs * co).max(1e-9);
        hue += cos.clamp(-1.0, 1.0).acos().to_degrees();
    }
    if n < MIN_BLOCKS {
        (None, None)
    } else {
        (Some(kept / n as f64), Some(hue / n as f64))
    }
}

fn image(fb: &Framebuffer) -> (usize, usize, Vec<Rgb>) {
    let (w, h) = (fb.width(), fb.height());
    let px = (0..h).flat_map(|y| fb.row(y).iter().copied()).collect();
    (w, h, px)
}

/// A source frame with its filtered views cached, so several ways of showing it (halfcast,
/// nearest, Floyd–Steinberg) are compared without filtering the source again.
pub struct Source {
    w: usize,
    h: usize,
    px: Vec<Rgb>,
    lab: Vec<[f64; 3]>,
    filtered: [Vec<[f64; 3]>; 2],
    /// The two viewing conditions of its figures ([`PPDS`] unless [`Source::at_ppds`]).
    ppds: [f64; 2],
}

impl Source {
    /// Prepares `fb` as the truth the others are measured against.
    #[must_use]
    pub fn new(fb: &Framebuffer) -> Self {
        Self::at_ppds(fb, PPDS)
    }

    /// [`Source::new`] for other viewing conditions: `ppds` pixels per degree of this frame's
    /// own grid (a finer glyph grid has more pixels per degree at the same seat). The figures'
    /// `scielab_45` and `scielab_9` fields then hold these two conditions.
    #[must_use]
    pub fn at_ppds(fb: &Framebuffer, ppds: [f64; 2]) -> Self {
        let (w, h, px) = image(fb);
        let img = Image { w, h, px: &px };
        let filtered = ppds.map(|p| scielab(&img, p));
        let lab_px = px.iter().map(|&c| lab(xyz(c))).collect();
        Self {
            w,
            h,
            px,
            lab: lab_px,
            filtered,
            ppds,
        }
    }

    /// The source's pixels, row-major.
    #[must_use]
    pub fn pixels(&self) -> &[Rgb] {
        &self.px
    }

    /// The figures of `shown` (same size as the source) against it.
    ///
    /// # Panics
    /// When the sizes differ.
    #[must_use]
    pub fn compare(&self, shown: &Framebuffer) -> Figures {
        let (w, h, px) = image(shown);
        assert_eq!((w, h), (self.w, self.h), "frames of different sizes");
        self.compare_pixels(&px)
    }

    /// [`Source::compare`] on row-major pixels.
    #[must_use]
    pub fn compare_pixels(&self, px: &[Rgb]) -> Figures {
        let n = (self.w * self.h).max(1) as f64;
        let img = Image {
            w: self.w,
            h: self.h,
            px,
        };
        let plain = px
            .iter()
            .zip(&self.lab)
            .map(|(&c, &l)| de(lab(xyz(c)), l))
            .sum::<f64>()
            / n;
        let s = [0, 1].map(|k| {
            scielab(&img, self.ppds[k])
                .iter()
                .zip(&self.filtered[k])
                .map(|(&a, &b)| de(a, b))
                .sum::<f64>()
                / n
        });
        let src = Image {
            w: self.w,
            h: self.h,
            px: &self.px,
        };
        let (chroma_kept, hue_error) = chroma_hue(&src, &img);
        Figures {
            plain_de: plain,
            scielab_45: s[0],
            scielab_9: s[1],
            chroma_kept,
            hue_error,
        }
    }

    /// The baselines on this frame for `palette` (xterm RGBs): nearest, then Floyd–Steinberg.
    #[must_use]
    pub fn baselines(&self, palette: &[Rgb]) -> (Figures, Figures) {
        (
            self.compare_pixels(&nearest(&self.px, palette)),
            self.compare_pixels(&floyd_steinberg(&self.px, self.w, palette)),
        )
    }
}

/// Each pixel replaced by the palette colour nearest in CIELAB (first on ties): no dither.
#[must_use]
pub fn nearest(px: &[Rgb], palette: &[Rgb]) -> Vec<Rgb> {
    let labs: Vec<[f64; 3]> = palette.iter().map(|&c| lab(xyz(c))).collect();
    let mut memo = std::collections::HashMap::new();
    px.iter()
        .map(|&c| {
            *memo.entry(c).or_insert_with(|| {
                let l = lab(xyz(c));
                let mut best = (f64::MAX, palette[0]);
                for (p, pl) in palette.iter().zip(&labs) {
                    let d = (0..3).map(|i| (pl[i] - l[i]).powi(2)).sum::<f64>();
                    if d < best.0 {
                        best = (d, *p);
                    }
                }
                best.1
            })
        })
        .collect()
}

/// Floyd–Steinberg error diffusion to `palette` as Pillow's `Image.quantize(palette=…,
/// dither=FLOYDSTEINBERG)` does it (what the tool runs): integer errors in sixteenths, left to
/// right on every row; a colour in the palette is itself, any other the entry nearest (squared
/// RGB distance, first on ties) to the corner of its 4×4×4 cache slot. Pillow's end-of-row quirk
/// (the last column's carried blue error stands for all three channels) is kept.
#[must_use]
pub fn floyd_steinberg(px: &[Rgb], w: usize, palette: &[Rgb]) -> Vec<Rgb> {
    let mut slot: Vec<u16> = vec![u16::MAX; 64 * 64 * 64];
    let exact: std::collections::HashMap<Rgb, usize> = palette
        .iter()
        .enumerate()
        .rev()
        .map(|(i, &c)| (c, i))
        .collect();
    let mut index_of = |r: i32, g: i32, b: i32| -> usize {
        if let Some(&i) = exact.get(&Rgb::new(r as u8, g as u8, b as u8)) {
            return i;
        }
        let k = (r >> 2) as usize + ((g >> 2) as usize) * 64 + ((b >> 2) as usize) * 4096;
        if slot[k] == u16::MAX {
            let (r0, g0, b0) = (r & !3, g & !3, b & !3);
            let mut best = (i32::MAX, 0usize);
            for (i, p) in palette.iter().enumerate() {
                let d = (r0 - i32::from(p.r)).pow(2)
                    + (g0 - i32::from(p.g)).pow(2)
                    + (b0 - i32::from(p.b)).pow(2);
                if d < best.0 {
                    best = (d, i);
                }
            }
            slot[k] = best.1 as u16;
        }
        usize::from(slot[k])
    };
    let h = px.len().checked_div(w).unwrap_or(0);
    let mut out = Vec::with_capacity(px.len());
    // errors[3 * (x + 1) + c]: what row y carries into pixel x of the next row (×16).
    let mut errors = vec![0i32; 3 * (w + 1)];
    for y in 0..h {
        let (mut cur, mut e0, mut e1) = ([0i32; 3], [0i32; 3], [0i32; 3]);
        for x in 0..w {
            let c = px[y * w + x];
            let input = [i32::from(c.r), i32::from(c.g), i32::from(c.b)];
            let v: [i32; 3] =
                [0, 1, 2].map(|k| (input[k] + (cur[k] + errors[3 * x + 3 + k]) / 16).clamp(0, 255));
            let i = index_of(v[0], v[1], v[2]);
            let p = palette[i];
            out.push(p);
            let pv = [i32::from(p.r), i32::from(p.g), i32::from(p.b)];
            for k in 0..3 {
                let err = v[k] - pv[k];
                errors[3 * x + k] = 3 * err + e0[k];
                e0[k] = 5 * err + e1[k];
                e1[k] = err;
                cur[k] = 7 * err;
            }
        }
        errors[3 * w] = e0[2];
        errors[3 * w + 1] = e1[2];
        errors[3 * w + 2] = e1[2];
    }
    out
}

/// The mean of several frames' figures (chroma and hue over the frames that have them).
#[must_use]
pub fn mean(all: &[Figures]) -> Option<Figures> {
    if all.is_empty() {
        return None;
    }
    let n = all.len() as f64;
    let avg = |v: Vec<f64>| (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64);
    Some(Figures {
        plain_de: all.iter().map(|f| f.plain_de).sum::<f64>() / n,
        scielab_45: all.iter().map(|f| f.scielab_45).sum::<f64>() / n,
        scielab_9: all.iter().map(|f| f.scielab_9).sum::<f64>() / n,
        chroma_kept: avg(all.iter().filter_map(|f| f.chroma_kept).collect()),
        hue_error: avg(all.iter().filter_map(|f| f.hue_error).collect()),
    })
}
