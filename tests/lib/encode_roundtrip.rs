//! The encoder's bytes, fed into a terminal model (`vt100`), must leave every cell showing exactly
//! what was intended: the palette-mapped colours (or the ASCII shade in mono), frame after frame.

use halfcast::encode::palette::{Code, DEFAULT};
use halfcast::encode::quantize;
use halfcast::encode::{ColorLevel, EncodeOptions, Encoder, SYNC_BEGIN, SYNC_END};
use halfcast::{Camera, Framebuffer, Rgb, Scene, Vec2, World};
use proptest::prelude::*;

fn code_of(c: vt100::Color) -> Code {
    match c {
        vt100::Color::Default => DEFAULT,
        vt100::Color::Idx(i) => u32::from(i),
        vt100::Color::Rgb(r, g, b) => (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b),
    }
}

/// What a terminal cell looks like as (top, bottom) colours, from its glyph and fg/bg.
fn visual(cell: &vt100::Cell) -> [Code; 2] {
    let (fg, bg) = (code_of(cell.fgcolor()), code_of(cell.bgcolor()));
    match cell.contents().as_str() {
        "▀" => [fg, bg],
        "▄" => [bg, fg],
        "" | " " => [bg, bg],
        "█" => [fg, fg],
        other => panic!("unexpected glyph {other:?}"),
    }
}

/// Asserts the screen's view rectangle shows `fb` as `enc` intends it at its level.
fn assert_screen(screen: &vt100::Screen, enc: &Encoder, fb: &Framebuffer, origin: (u16, u16)) {
    let mut want = Vec::new();
    quantize(enc.palette(), fb, &mut want);
    let level = enc.options().level;
    let w = fb.width();
    for (i, cell_want) in want.iter().enumerate() {
        let (x, y) = ((i % w) as u16, (i / w) as u16);
        let cell = screen
            .cell(origin.1 + y, origin.0 + x)
            .expect("cell inside the screen");
        let at = format!("cell ({x},{y}) at {level}");
        if level == ColorLevel::Mono {
            let c = char::from_u32(cell_want[0]).unwrap();
            let got = cell.contents();
            let got = if got.is_empty() { " ".to_string() } else { got };
            assert_eq!(got, c.to_string(), "{at}");
            assert_eq!(code_of(cell.fgcolor()), DEFAULT, "{at}");
            assert_eq!(code_of(cell.bgcolor()), DEFAULT, "{at}");
            continue;
        }
        let got = visual(cell);
        assert_eq!(got, *cell_want, "{at}");
        for (c, raw) in [(got[0], cell.fgcolor()), (got[1], cell.bgcolor())] {
            let _ = c;
            match (level, raw) {
                (ColorLevel::TrueColor, vt100::Color::Rgb(..) | vt100::Color::Default) => {}
                (ColorLevel::Ansi256, vt100::Color::Idx(i)) => assert!(i >= 16, "{at}"),
                (ColorLevel::Ansi16, vt100::Color::Idx(i)) => assert!(i < 16, "{at}"),
                (_, vt100::Color::Default) => {}
                (l, r) => panic!("{at}: colour {r:?} at level {l}"),
            }
        }
    }
}

/// Feeds a sequence of frames through one encoder into one terminal, checking after each.
fn replay(frames: &[Framebuffer], opts: EncodeOptions, origin: (u16, u16), term: (u16, u16)) {
    let mut enc = Encoder::new(opts);
    let mut parser = vt100::Parser::new(term.1, term.0, 0);
    for (n, fb) in frames.iter().enumerate() {
        let bytes = enc.encode(fb, origin.0, origin.1).to_vec();
        if opts.level != ColorLevel::Mono && !bytes.is_empty() {
            assert!(bytes.starts_with(SYNC_BEGIN) && bytes.ends_with(SYNC_END));
        }
        if opts.level == ColorLevel::Mono {
            assert!(bytes.is_ascii(), "mono frame {n} is not ASCII");
        }
        parser.process(&bytes);
        assert_screen(parser.screen(), &enc, fb, origin);
        // Colours are reset after each frame, so other drawing is never tinted.
        assert_eq!(parser.screen().fgcolor(), vt100::Color::Default);
        assert_eq!(parser.screen().bgcolor(), vt100::Color::Default);
    }
}

/// Frames of the default map: turning on the spot, then walking east along row 5.
fn default_map_frames(cols: u16, rows: u16, n: usize) -> Vec<Framebuffer> {
    let world = World::default_world();
    let start = world.map.start.pos();
    let mut frames = Vec::new();
    for i in 0..n {
        let cam = if i < n / 2 {
            Camera::from_angle(start, 90.0 + 2.5 * i as f64, 66.0)
        } else {
            let p = Vec2::new(start.x - 3.0 + 0.15 * (i - n / 2) as f64, start.y);
            assert!(world.map.is_walkable(p));
            Camera::from_angle(p, 0.0, 66.0)
        };
        frames.push(Scene::new(&world, cam).render(cols, rows));
    }
    frames
}

#[test]
fn default_map_turn_and_walk_round_trips_at_every_level() {
    let frames = default_map_frames(72, 20, 40);
    for level in ColorLevel::ALL {
        replay(&frames, EncodeOptions::new(level), (3, 2), (80, 24));
        // The view flush against the terminal's right and bottom edges (pending-wrap cursor).
        replay(&frames, EncodeOptions::new(level), (8, 4), (80, 24));
    }
}

#[test]
fn other_beam_widths_round_trip() {
    let frames = default_map_frames(40, 12, 16);
    let opts = EncodeOptions {
        beam: 4,
        ..EncodeOptions::default()
    };
    replay(&frames, opts, (1, 1), (50, 14));
    let opts = EncodeOptions {
        beam: 1,
        ..EncodeOptions::default()
    };
    replay(&frames, opts, (1, 1), (50, 14));
}

#[test]
fn invalidate_redraws_over_a_cleared_screen() {
    let frames = default_map_frames(30, 10, 4);
    let mut enc = Encoder::new(EncodeOptions::new(ColorLevel::Ansi256));
    let mut parser = vt100::Parser::new(12, 32, 0);
    parser.process(enc.encode(&frames[0], 1, 1));
    parser.process(b"\x1b[2J");
    enc.invalidate();
    parser.process(enc.encode(&frames[1], 1, 1));
    assert_screen(parser.screen(), &enc, &frames[1], (1, 1));
}

#[test]
fn delta_skips_small_changes_but_the_screen_stays_within_the_threshold() {
    let frames = default_map_frames(40, 12, 12);
    let opts = EncodeOptions {
        delta: Some(12),
        ..EncodeOptions::default()
    };
    let mut enc = Encoder::new(opts);
    let mut exact = Encoder::new(EncodeOptions::default());
    let mut parser = vt100::Parser::new(12, 40, 0);
    let (mut lossy_bytes, mut exact_bytes) = (0, 0);
    for fb in &frames {
        let bytes = enc.encode(fb, 0, 0);
        lossy_bytes += bytes.len();
        parser.process(bytes);
        exact_bytes += exact.encode(fb, 0, 0).len();
        let shown = enc.shown();
        for (i, cell) in shown.iter().enumerate() {
            let (x, y) = (i % 40, i / 40);
            let got = visual(parser.screen().cell(y as u16, x as u16).unwrap());
            assert_eq!(got, *cell);
            let (t, b) = fb.cell(x, y);
            let px = |c: Code| Rgb::new((c >> 16) as u8, (c >> 8) as u8, c as u8);
            let d = |a: Rgb, b: Rgb| halfcast::encode::palette::distance(a, b);
            assert!(d(px(cell[0]), t) < 12 && d(px(cell[1]), b) < 12);
        }
    }
    assert!(lossy_bytes < exact_bytes, "{lossy_bytes} vs {exact_bytes}");
}

fn arb_frames() -> impl Strategy<Value = (u16, u16, Vec<Vec<Rgb>>)> {
    (1u16..14, 1u16..7).prop_flat_map(|(cols, rows)| {
        let n = usize::from(cols) * usize::from(rows) * 2;
        // A few colours so runs and repeats (the interesting cases) are common, plus random ones.
        let colour = prop_oneof![
            3 => prop::sample::select(vec![
                Rgb::new(0, 0, 0),
                Rgb::new(255, 255, 255),
                Rgb::new(96, 88, 80),
                Rgb::new(150, 146, 136),
            ]),
            1 => (any::<u8>(), any::<u8>(), any::<u8>()).prop_map(|(r, g, b)| Rgb::new(r, g, b)),
        ];
        (
            Just(cols),
            Just(rows),
            prop::collection::vec(prop::collection::vec(colour, n), 1..5),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn random_frames_round_trip(
        (cols, rows, pixels) in arb_frames(),
        origin in (0u16..4, 0u16..3),
        level in prop::sample::select(ColorLevel::ALL.to_vec()),
    ) {
        let frames: Vec<Framebuffer> = pixels
            .iter()
            .map(|px| {
                let mut fb = Framebuffer::for_cells(cols, rows);
                for (i, &c) in px.iter().enumerate() {
                    fb.set(i % usize::from(cols), i / usize::from(cols), c);
                }
                fb
            })
            .collect();
        let opts = EncodeOptions::new(level);
        replay(&frames, opts, origin, (origin.0 + cols, origin.1 + rows + 1));
    }
}
