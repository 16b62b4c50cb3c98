//! The glyph ladder's sub-grid: the same camera at every setting, walls square on screen, and
//! one ray per pixel column.

use halfcast::encode::{ColorLevel, EncodeOptions, Encoder};
use halfcast::map::parse_map;
use halfcast::world::{TextureSource, World};
use halfcast::{Camera, Framebuffer, Glyphs, Rgb, Scene};

/// A room with one wall block at (6, 3), seen face-on from (1.5, 3.5) looking east; floor and
/// ceiling flat colours, so the wall's rows are the pixels of neither.
fn room() -> World {
    let text = "NO textures/bricks.png\nSO textures/bricks.png\nWE textures/stone.png\n\
                EA textures/stone.png\nF 0,0,255\nC 0,255,0\n\n\
                1111111111\n1000000001\n1000000001\n1E00001001\n1000000001\n1111111111\n";
    let map = parse_map("room.cub", text.as_bytes()).unwrap();
    World::load(map, &TextureSource::Embedded, true).unwrap().0
}

/// The block's face on screen in terminal cells: (width in columns, height in rows).
fn face_in_cells(world: &World, cols: u16, rows: u16, glyphs: Glyphs) -> (f64, f64) {
    let cam = Camera::from_angle(world.map.start.pos(), 0.0, 66.0);
    let mut fb = Framebuffer::for_glyphs(cols, rows, glyphs);
    let cast = Scene::new(world, cam).render_into(&mut fb, None);
    // One ray per pixel column: 2W of them when the cell is two pixels wide.
    assert_eq!(cast.columns.len(), fb.width());
    let (cw, ch) = glyphs.cell_size();
    let on_block: Vec<usize> = (0..fb.width())
        .filter(|&x| cast.columns[x].cell == (6, 3))
        .collect();
    let centre = on_block[on_block.len() / 2];
    let (floor, ceiling) = (Rgb::new(0, 0, 255), Rgb::new(0, 255, 0));
    let wall_rows = (0..fb.height())
        .filter(|&y| {
            let c = fb.get(centre, y);
            c != floor && c != ceiling
        })
        .count();
    (
        on_block.len() as f64 / cw as f64,
        wall_rows as f64 / ch as f64,
    )
}

#[test]
fn a_wall_seen_face_on_is_square_at_every_setting() {
    let world = room();
    for glyphs in Glyphs::ALL {
        let (w, h) = face_in_cells(&world, 120, 40, glyphs);
        // A cell is twice as tall as wide: a square face is twice as many columns as rows.
        // Expected: focal 120 / (2·tan 33°) = 92.4 columns per unit at distance 1, 4.5 away.
        assert!((w - 20.5).abs() < 0.6, "{glyphs}: {w} columns");
        assert!(
            (h - w / 2.0).abs() < 0.6,
            "{glyphs}: {w} columns × {h} rows"
        );
    }
}

/// The default map's camera as the game starts it.
fn start_camera(world: &World) -> Camera {
    let start = world.map.start;
    Camera::from_angle(start.pos(), start.angle_deg(), 66.0)
}

#[test]
fn a_still_camera_sends_nothing_after_the_first_frame_at_every_setting() {
    let world = World::default_world();
    let scene = Scene::new(&world, start_camera(&world));
    for glyphs in Glyphs::ALL {
        for level in ColorLevel::ALL {
            let mut fb = Framebuffer::for_glyphs(50, 23, glyphs);
            let mut e = Encoder::new(EncodeOptions::new(level));
            scene.render_into(&mut fb, None);
            assert!(!e.encode(&fb, 0, 1).is_empty());
            scene.render_into(&mut fb, None);
            assert!(e.encode(&fb, 0, 1).is_empty(), "{glyphs} at {level}");
        }
    }
}

/// Golden pictures of the default view at 80×24 cells as the terminal shows it at each setting
/// (each cell's mask in its two colours). Update after an intended change:
/// `HALFCAST_UPDATE_GOLDEN=1 cargo test --test lib glyph_grid` (and look at every image).
#[test]
fn golden_default_view_at_each_setting() {
    use halfcast::output::glyph_picture::shown_picture;
    use halfcast::snapshot::{assert_png_golden, Tolerance};
    let world = World::default_world();
    let scene = Scene::new(&world, start_camera(&world));
    for glyphs in Glyphs::ALL {
        let mut fb = Framebuffer::for_glyphs(80, 24, glyphs);
        scene.render_into(&mut fb, None);
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join(format!("tests/images/glyphs/default_{glyphs}.png"));
        assert_png_golden(&shown_picture(&fb), path, Tolerance::default());
    }
}

/// A frame sent to a terminal at any glyph setting reads back (through a terminal model) to the
/// setting it was sent at and to the picture the terminal shows, pixel for pixel: what `diff` and
/// snapshot tests of ANSI frames compare.
#[cfg(feature = "vt100")]
#[test]
fn ansi_frames_read_back_at_their_glyph_setting() {
    use halfcast::encode::full_frame;
    use halfcast::termframe::{parse_frame, FrameFormat, FramePixels, TermFrame};
    let world = World::default_world();
    let cam = Camera::from_angle(world.map.start.pos(), 20.0, 66.0);
    for glyphs in Glyphs::ALL {
        let mut fb = Framebuffer::for_glyphs(48, 14, glyphs);
        Scene::new(&world, cam).render_into(&mut fb, None);
        let bytes = full_frame(&fb, &EncodeOptions::default());
        let (frame, format) = parse_frame(&bytes).unwrap();
        assert_eq!(format, FrameFormat::Ansi);
        assert_eq!((frame.cols, frame.rows), (48, 14), "{glyphs}");
        assert_eq!(frame.glyphs(), glyphs, "the setting the frame was sent at");
        let shown = TermFrame::from_framebuffer(&fb).to_framebuffer();
        let read = frame.to_framebuffer();
        assert_eq!((read.width(), read.height()), (fb.width(), fb.height()));
        assert_eq!(read.glyphs(), glyphs);
        let differing = (0..read.height())
            .flat_map(|y| (0..read.width()).map(move |x| (x, y)))
            .filter(|&(x, y)| read.get(x, y) != shown.get(x, y))
            .count();
        assert_eq!(
            differing, 0,
            "{glyphs}: pixels read back unlike the cells sent"
        );
    }
}

/// Cells of one odd corner pixel never go out as the one-quarter blocks (U+1CEA0/A3/A8/AB),
/// which VTE and older kitty draw wrongly, but as their complements with the colours swapped;
/// the terminal still shows the same picture.
#[cfg(feature = "vt100")]
#[test]
fn octant_corner_pixels_go_out_as_their_complements() {
    use halfcast::encode::full_frame;
    use halfcast::termframe::{parse_frame, FramePixels, TermFrame};
    let quarter = ['\u{1CEA0}', '\u{1CEA3}', '\u{1CEA8}', '\u{1CEAB}'];
    for corner in [(0, 0), (1, 0), (0, 3), (1, 3)] {
        let mut fb = Framebuffer::for_glyphs(6, 3, Glyphs::Octant);
        for y in 0..fb.height() {
            for x in 0..fb.width() {
                let odd = (x % 2, y % 4) == corner;
                let c = if odd {
                    Rgb::new(250, 250, 250)
                } else {
                    Rgb::new(20, 30, 40 + x as u8)
                };
                fb.set(x, y, c);
            }
        }
        let bytes = full_frame(&fb, &EncodeOptions::default());
        let text = String::from_utf8(bytes.clone()).unwrap();
        assert!(text.chars().all(|c| !quarter.contains(&c)), "{corner:?}");
        let (read, _) = parse_frame(&bytes).unwrap();
        let shown = TermFrame::from_framebuffer(&fb).to_framebuffer();
        assert_eq!(read.to_framebuffer().pixels(), shown.pixels(), "{corner:?}");
    }
}
