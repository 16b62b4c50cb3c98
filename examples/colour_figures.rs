//! S-CIELAB figures of the 256- or 16-colour picture on the sets `../shared/tools/scielab.py` checks,
//! computed in one process (the tool's maths through `halfcast::bench::scielab`): the default map's
//! eight views, random views of a map, and camera sequences with their surface phases dropped (as
//! `bench --frames` encodes frames from elsewhere). Faster than the tool for trying mappings.
//!
//! `cargo run --release --example colour_figures -- [256|16] [--baselines] [--dump DIR] SET ...`
//! where a set is `default`, `frames` or `MAP.cub:POSES` (POSES a file of `x,y,angle;...` as the
//! tool's `--poses`; the first eight it can render count, as with its `--random 8`). `--dump`
//! writes each view as source | shown | Floyd–Steinberg, three screen pixels per pixel, to look at.

use halfcast::bench::scielab::{self, Figures, Source, DEFAULT_MAP_VIEWS};
use halfcast::encode::palette::{xterm_rgb, ANSI16};
use halfcast::encode::quantize;
use halfcast::encode::{full_frame, ColorLevel, EncodeOptions, Palette};
use halfcast::world::door::DoorState;
use halfcast::{Camera, Framebuffer, Rgb, Scene, Vec2, View, World};

const SIZE: (u16, u16) = (120, 40);

/// The frame `render` draws for a pose (None where `render` refuses it).
fn render(world: &World, (x, y, a): (f64, f64, f64)) -> Option<Framebuffer> {
    let pos = Vec2::new(x, y);
    let z = halfcast::render::view::STANDING_EYE;
    if world.map.has_heights() && halfcast::game::pose::still_eye(&world.map, pos, z).is_err() {
        return None;
    }
    let camera = Camera::from_angle(pos, a, halfcast::camera::DEFAULT_FOV_DEG);
    let mut fb = Framebuffer::for_cells(SIZE.0, SIZE.1);
    let mut doors = DoorState::new(&world.map);
    for cell in doors.cells().to_vec() {
        doors.set_open(cell, 0.0);
    }
    let ground = world
        .map
        .floor_height(pos.x.floor() as i64, pos.y.floor() as i64);
    let sprites = halfcast::game::Level::new(&world.map, 0).sprites(world);
    let scene = Scene::new(world, camera)
        .with_view(View::new(0.0, z).on_ground(ground))
        .with_doors(&doors)
        .with_sprites(&sprites);
    let _ = scene.render_frame(&mut fb, Some(usize::from(SIZE.0) / 2));
    Some(fb)
}

fn frames_of(set: &str) -> Vec<Framebuffer> {
    if set == "default" {
        let world = World::default_world();
        return DEFAULT_MAP_VIEWS
            .iter()
            .filter_map(|&p| render(&world, p))
            .collect();
    }
    if set == "frames" {
        // A turn, a walk and a strafe on the default map and on level1, frames 0, 10, 20.
        let mut out = Vec::new();
        for (map, start) in [
            (None, (15.5, 5.5, 60.0)),
            (Some("maps/level1.cub"), (5.5, 5.5, 30.0)),
        ] {
            let world = map.map_or_else(World::default_world, |m| {
                World::from_file(std::path::Path::new(m), false)
                    .expect("the map loads")
                    .0
            });
            let (x, y, a) = start;
            for i in [0.0, 10.0, 20.0] {
                for pose in [
                    (x, y, a + 3.0 * i),
                    (x + 0.05 * i, y, 0.0),
                    (x, y + 0.05 * i, 0.0),
                ] {
                    if let Some(mut fb) = render(&world, pose) {
                        fb.clear_phases();
                        out.push(fb);
                    }
                }
            }
        }
        return out;
    }
    let (map, file) = set.split_once(':').expect("MAP:POSES");
    let world = World::from_file(std::path::Path::new(map), false)
        .expect("the map loads")
        .0;
    let poses = std::fs::read_to_string(file).expect("the poses file reads");
    poses
        .trim()
        .split(';')
        .map(|p| {
            let v: Vec<f64> = p
                .split(',')
                .map(|s| s.trim().parse().expect("x,y,angle"))
                .collect();
            (v[0], v[1], v[2])
        })
        .filter_map(|p| render(&world, p))
        .take(8)
        .collect()
}

fn shown(palette: &Palette, fb: &Framebuffer) -> Vec<Rgb> {
    let mut cells = Vec::new();
    quantize(palette, fb, &mut cells);
    let w = fb.width();
    let mut px = vec![Rgb::default(); w * fb.height()];
    for (i, c) in cells.iter().enumerate() {
        let (x, cy) = (i % w, i / w);
        px[2 * cy * w + x] = palette.rgb(c[0]);
        px[(2 * cy + 1) * w + x] = palette.rgb(c[1]);
    }
    px
}

fn line(name: &str, f: &Figures, fs: &Figures) -> String {
    format!(
        "{name:9} {:6.2} / {:6.2} ({:.3}x / {:.3}x)  chroma {:.2}  hue {:5.1}",
        f.scielab_45,
        f.scielab_9,
        f.scielab_45 / fs.scielab_45,
        f.scielab_9 / fs.scielab_9,
        f.chroma_kept.unwrap_or(f64::NAN),
        f.hue_error.unwrap_or(f64::NAN)
    )
}

/// Whether `flag` was given (and drops it from `args`).
fn take_flag(args: &mut Vec<String>, flag: &str) -> bool {
    let before = args.len();
    args.retain(|a| a != flag);
    args.len() != before
}

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let level = if args.first().map(String::as_str) == Some("16") {
        args.remove(0);
        ColorLevel::Ansi16
    } else {
        if args.first().map(String::as_str) == Some("256") {
            args.remove(0);
        }
        ColorLevel::Ansi256
    };
    let baselines = take_flag(&mut args, "--baselines");
    let dump = args.iter().position(|a| a == "--dump").map(|i| {
        args.remove(i);
        args.remove(i)
    });
    let pal: Vec<Rgb> = if level == ColorLevel::Ansi16 {
        ANSI16.to_vec()
    } else {
        (16..=255).map(xterm_rgb).collect()
    };
    let t = std::time::Instant::now();
    let palette = Palette::new(level);
    println!(
        "{level} tables ready in {:.1} ms",
        t.elapsed().as_secs_f64() * 1e3
    );
    for set in &args {
        let frames = frames_of(set);
        let (mut ours, mut near, mut fs) = (Vec::new(), Vec::new(), Vec::new());
        let (mut bytes, mut true_bytes) = (0usize, 0usize);
        for fb in &frames {
            let src = Source::new(fb);
            let px = shown(&palette, fb);
            if let Some(dir) = &dump {
                let (w, h) = (fb.width(), fb.height());
                let fsp = scielab::floyd_steinberg(src.pixels(), w, &pal);
                let sc = 3;
                let mut sheet = Framebuffer::new(3 * w * sc + 8, h * sc);
                for (p, img) in [src.pixels(), &px[..], &fsp[..]].iter().enumerate() {
                    for y in 0..h * sc {
                        for x in 0..w * sc {
                            sheet.set(p * (w * sc + 4) + x, y, img[(y / sc) * w + x / sc]);
                        }
                    }
                }
                let name = format!(
                    "{dir}/{}-{}.png",
                    set.replace(['/', ':', '.'], "_"),
                    ours.len()
                );
                std::fs::write(name, sheet.to_png().unwrap()).unwrap();
            }
            ours.push(src.compare_pixels(&px));
            let (n, f) = src.baselines(&pal);
            near.push(n);
            fs.push(f);
            bytes += full_frame(fb, &EncodeOptions::new(level)).len();
            true_bytes += full_frame(fb, &EncodeOptions::new(ColorLevel::TrueColor)).len();
        }
        let (o, n, f) = (
            scielab::mean(&ours).unwrap(),
            scielab::mean(&near).unwrap(),
            scielab::mean(&fs).unwrap(),
        );
        println!(
            "{set} ({} frames; bytes {:.1}% of truecolor full frames)",
            frames.len(),
            100.0 * bytes as f64 / true_bytes as f64
        );
        println!("  {}", line("halfcast", &o, &f));
        if baselines {
            println!("  {}", line("nearest", &n, &f));
            println!("  {}", line("fs", &f, &f));
        }
    }
}
