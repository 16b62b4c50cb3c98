//! Issue 14's rendering rules checked pixel by pixel against an independent reference: for every
//! pixel this file marches that pixel's own 3-D ray through the grid (it shares no code with the
//! column renderer) and names the surface it meets first; `Scene::render` must show that
//! surface's colour. Random maps with random `Hz` heights, shut doors, poses, pitches, eye
//! heights, FOVs and sizes; every surface a flat colour (walls: one-colour texture files), so colours compare
//! exactly. At most 0.5 % of a frame's pixels may differ (rays grazing an edge).

use halfcast::camera::Camera;
use halfcast::{Framebuffer, Rgb, Scene, Vec2, View, World};

/// A small deterministic generator (xorshift64*), so failures reproduce from the case number.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    /// Even channels: textures keep those exactly (odd ones may come back one lower).
    fn colour(&mut self) -> Rgb {
        let mut ch = || 30 + 2 * self.below(110) as u8;
        Rgb::new(ch(), ch(), ch())
    }
}

/// What one grid cell is, for the reference.
#[derive(Clone, Copy)]
enum Cell {
    Solid,
    Open {
        floor: f64,
        ceil: f64,
        zone: usize,
    },
    /// A shut door: open 0..1 like a plain cell, its panel across the middle (the line
    /// y = j + 0.5 when `panel_y`, between walls west and east; else x = i + 0.5).
    Door {
        panel_y: bool,
    },
}

/// A random world: the grid, each zone's heights and paints, the wall face colours.
struct Case {
    w: usize,
    h: usize,
    cells: Vec<Cell>,
    /// Zone 0 is the default floor (0..1); 1.. are `a`.. .
    floor_paint: Vec<Rgb>,
    ceil_paint: Vec<Rgb>,
    /// `Wz` colour per zone, if given.
    face_paint: Vec<Option<Rgb>>,
    /// NO, SO, WE, EA colours (by the ray's heading).
    walls: [Rgb; 4],
    /// The door panels' colour.
    door: Rgb,
    /// Each door's open neighbour and the door cell (a place to look at it from).
    door_views: Vec<((usize, usize), (usize, usize))>,
}

impl Case {
    fn cell(&self, i: i64, j: i64) -> Cell {
        if i < 0 || j < 0 || i as usize >= self.w || j as usize >= self.h {
            Cell::Solid
        } else {
            self.cells[j as usize * self.w + i as usize]
        }
    }

    fn random(rng: &mut Rng) -> (Self, String, (usize, usize)) {
        let (w, h) = (5 + rng.below(10), 5 + rng.below(10));
        let zones = 1 + rng.below(5);
        let mut floor_paint = vec![rng.colour()];
        let mut ceil_paint = vec![rng.colour()];
        let mut face_paint = vec![None];
        let mut spans = vec![(0.0, 1.0)];
        let mut header = String::new();
        for z in 0..zones {
            let letter = (b'a' + z as u8) as char;
            let floor = (rng.range(-1.5, 1.5) * 8.0).round() / 8.0 + rng.range(0.0, 0.1);
            let ceil = floor + rng.range(0.3, 2.5);
            let (f, c) = (rng.colour(), rng.colour());
            header += &format!("H{letter} {floor} {ceil}\n");
            header += &format!(
                "F{letter} {},{},{}\nC{letter} {},{},{}\n",
                f.r, f.g, f.b, c.r, c.g, c.b
            );
            let face = (rng.below(2) == 0).then(|| rng.colour());
            if let Some(wc) = face {
                header += &format!("W{letter} {},{},{}\n", wc.r, wc.g, wc.b);
            }
            floor_paint.push(f);
            ceil_paint.push(c);
            face_paint.push(face);
            spans.push((floor, ceil));
        }
        let walls = [rng.colour(), rng.colour(), rng.colour(), rng.colour()];
        let start = (1 + rng.below(w - 2), 1 + rng.below(h - 2));
        let mut cells = Vec::new();
        let mut grid = String::new();
        for j in 0..h {
            for i in 0..w {
                let border = i == 0 || j == 0 || i == w - 1 || j == h - 1;
                let (ch, cell) = if (i, j) == start {
                    (
                        'N',
                        Cell::Open {
                            floor: 0.0,
                            ceil: 1.0,
                            zone: 0,
                        },
                    )
                } else if border || rng.below(6) == 0 {
                    ('1', Cell::Solid)
                } else {
                    let z = rng.below(zones + 1);
                    let (floor, ceil) = spans[z];
                    let ch = if z == 0 {
                        '0'
                    } else {
                        (b'a' + z as u8 - 1) as char
                    };
                    (
                        ch,
                        Cell::Open {
                            floor,
                            ceil,
                            zone: z,
                        },
                    )
                };
                grid.push(ch);
                cells.push(cell);
            }
            grid.push('\n');
        }
        // Doors: cells framed by two walls (west and east, or north and south).
        let mut chars: Vec<char> = grid.chars().filter(|&c| c != '\n').collect();
        let mut door_views = Vec::new();
        for _ in 0..4 {
            let (di, dj) = (1 + rng.below(w - 2), 1 + rng.below(h - 2));
            let near_start = di.abs_diff(start.0) + dj.abs_diff(start.1) <= 1;
            // Away from other doors, so no placement unframes another.
            let near_door = (di.saturating_sub(2)..(di + 3).min(w))
                .any(|i| (dj.saturating_sub(2)..(dj + 3).min(h)).any(|j| chars[j * w + i] == 'D'));
            if rng.below(4) != 0
                && !near_start
                && !near_door
                && (2..w - 2).contains(&di)
                && (2..h - 2).contains(&dj)
            {
                let panel_y = rng.below(2) == 0;
                let (frame, open) = if panel_y {
                    ([(di - 1, dj), (di + 1, dj)], (di, dj - 1))
                } else {
                    ([(di, dj - 1), (di, dj + 1)], (di - 1, dj))
                };
                for (i, j) in frame {
                    chars[j * w + i] = '1';
                    cells[j * w + i] = Cell::Solid;
                }
                // One open side, so the frame's direction is the door's.
                if (open.0, open.1) != start {
                    chars[open.1 * w + open.0] = '0';
                    cells[open.1 * w + open.0] = Cell::Open {
                        floor: 0.0,
                        ceil: 1.0,
                        zone: 0,
                    };
                }
                chars[dj * w + di] = 'D';
                door_views.push((open, (di, dj)));
                cells[dj * w + di] = Cell::Door { panel_y };
            }
        }
        let grid: String = chars
            .chunks(w)
            .map(|r| r.iter().collect::<String>() + "\n")
            .collect();
        let f = floor_paint[0];
        let c = ceil_paint[0];
        let text = format!(
            "NO no.png\nSO so.png\nWE we.png\nEA ea.png\nTD dr.png\nF {},{},{}\nC {},{},{}\n{header}{grid}",
            f.r, f.g, f.b, c.r, c.g, c.b
        );
        let case = Case {
            w,
            h,
            cells,
            floor_paint,
            ceil_paint,
            face_paint,
            walls,
            door: rng.colour(),
            door_views,
        };
        (case, text, start)
    }
}

/// Today's y-side shade: 184/256 of each channel.
fn y_shade(c: Rgb, side_y: bool) -> Rgb {
    if side_y {
        let s = |v: u8| ((u16::from(v) * 184) >> 8) as u8;
        Rgb::new(s(c.r), s(c.g), s(c.b))
    } else {
        c
    }
}

/// The colour pixel (x, y) should show: its ray, 2-D direction `ray` and height
/// z(t) = eye − slope·t, walked cell by cell.
fn reference_pixel(case: &Case, pos: Vec2, ray: Vec2, eye: f64, slope: f64) -> Rgb {
    let hit = reference_hit(case, pos, ray, eye, slope);
    y_shade(hit.paint, hit.side_y)
}

/// The surface a pixel's ray meets first.
struct Hit {
    /// Its paint, unshaded.
    paint: Rgb,
    /// A face met across a y grid line (shaded darker).
    side_y: bool,
    /// A vertical face (true) or a floor or ceiling.
    face: bool,
    /// Distance along the view direction.
    t: f64,
    /// The height met.
    z: f64,
}

/// [`reference_pixel`]'s walk, naming the surface met.
fn reference_hit(case: &Case, pos: Vec2, ray: Vec2, eye: f64, slope: f64) -> Hit {
    let (mut i, mut j) = (pos.x.floor() as i64, pos.y.floor() as i64);
    let step_i: i64 = if ray.x < 0.0 { -1 } else { 1 };
    let step_j: i64 = if ray.y < 0.0 { -1 } else { 1 };
    // Distance along the ray to the next vertical / horizontal grid line.
    let next_x = |i: i64| {
        if ray.x == 0.0 {
            f64::INFINITY
        } else {
            let line = if ray.x > 0.0 { i + 1 } else { i } as f64;
            (line - pos.x) / ray.x
        }
    };
    let next_y = |j: i64| {
        if ray.y == 0.0 {
            f64::INFINITY
        } else {
            let line = if ray.y > 0.0 { j + 1 } else { j } as f64;
            (line - pos.y) / ray.y
        }
    };
    let (mut floor, mut ceil, mut zone, mut door) = match case.cell(i, j) {
        Cell::Open { floor, ceil, zone } => (floor, ceil, zone, None),
        Cell::Door { panel_y } => (0.0, 1.0, 0, Some(panel_y)),
        Cell::Solid => panic!("camera inside a wall"),
    };
    let mut t_in = 0.0;
    for _ in 0..10_000 {
        let (tx, ty) = (next_x(i), next_y(j));
        let t = tx.min(ty);
        // A floor or ceiling at height `at` (met where the pixel's height reaches it).
        let flat = |paint: Rgb, at: f64| Hit {
            paint,
            side_y: false,
            face: false,
            t: if slope == 0.0 { t } else { (eye - at) / slope },
            z: at,
        };
        // A face at the crossing `t`.
        let face = |paint: Rgb, side_y: bool| Hit {
            paint,
            side_y,
            face: true,
            t,
            z: eye - slope * t,
        };
        if let Some(panel_y) = door {
            let tp = if panel_y {
                (j as f64 + 0.5 - pos.y) / ray.y
            } else {
                (i as f64 + 0.5 - pos.x) / ray.x
            };
            if tp >= t_in && tp < t {
                let z = eye - slope * tp;
                return if z <= 0.0 {
                    flat(case.floor_paint[0], 0.0)
                } else if z > 1.0 {
                    flat(case.ceil_paint[0], 1.0)
                } else {
                    Hit {
                        paint: case.door,
                        side_y: panel_y,
                        face: true,
                        t: tp,
                        z,
                    }
                };
            }
        }
        t_in = t;
        let z = eye - slope * t;
        if z <= floor {
            return flat(case.floor_paint[zone], floor);
        }
        if z > ceil {
            return flat(case.ceil_paint[zone], ceil);
        }
        let side_y = ty <= tx;
        if side_y {
            j += step_j;
        } else {
            i += step_i;
        }
        let heading = match (side_y, ray) {
            (true, r) if r.y < 0.0 => 0,
            (true, _) => 1,
            (false, r) if r.x < 0.0 => 2,
            (false, _) => 3,
        };
        match case.cell(i, j) {
            Cell::Solid => return face(case.walls[heading], side_y),
            Cell::Open {
                floor: f,
                ceil: c,
                zone: n,
            } => {
                if z <= f || z > c {
                    let paint = case.face_paint[n].unwrap_or(case.walls[heading]);
                    return face(paint, side_y);
                }
                (floor, ceil, zone, door) = (f, c, n, None);
            }
            Cell::Door { panel_y } => {
                // A door cell is open from 0 to 1; the faces beside it are plain walls'.
                if z <= 0.0 || z > 1.0 {
                    return face(case.walls[heading], side_y);
                }
                (floor, ceil, zone, door) = (0.0, 1.0, 0, Some(panel_y));
            }
        }
    }
    panic!("ray never stopped");
}

fn flat_png(dir: &std::path::Path, name: &str, c: Rgb) {
    let mut fb = Framebuffer::new(4, 4);
    for y in 0..4 {
        for x in 0..4 {
            fb.set(x, y, c);
        }
    }
    std::fs::write(dir.join(name), fb.to_png().unwrap()).unwrap();
}

#[test]
fn every_pixel_shows_the_first_surface_on_its_own_ray() {
    let mut worst = 0.0f64;
    let mut door_pixels = 0usize;
    let mut maps_with_doors = 0usize;
    for n in 0..60u64 {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ (n + 1).wrapping_mul(0x1000_0000_01b3));
        let (case, text, _) = Case::random(&mut rng);
        let dir = tempfile::tempdir().unwrap();
        for (name, c) in ["no.png", "so.png", "we.png", "ea.png"]
            .iter()
            .zip(case.walls)
        {
            flat_png(dir.path(), name, c);
        }
        flat_png(dir.path(), "dr.png", case.door);
        if text.lines().any(|l| l.starts_with('1') && l.contains('D')) {
            maps_with_doors += 1;
        }
        let path = dir.path().join("m.cub");
        std::fs::write(&path, &text).unwrap();
        let (world, warnings) = World::from_file(&path, true).unwrap();
        assert!(warnings.is_empty());
        assert!(world.map.has_heights());
        // A random open cell with room for an eye.
        let open: Vec<(usize, f64, f64)> = (0..case.cells.len())
            .filter_map(|k| match case.cells[k] {
                Cell::Open { floor, ceil, .. } if ceil - floor >= 0.4 => Some((k, floor, ceil)),
                _ => None,
            })
            .collect();
        let (k, mut floor, mut ceil) = open[rng.below(open.len())];
        let mut pos = Vec2::new(
            (k % case.w) as f64 + rng.range(0.05, 0.95),
            (k / case.w) as f64 + rng.range(0.05, 0.95),
        );
        let mut angle = rng.range(-180.0, 180.0);
        if n % 2 == 0 {
            // Half the maps with a door look at one from the cell beside it.
            if let Some(&((oi, oj), (di, dj))) = case.door_views.first() {
                (floor, ceil) = (0.0, 1.0);
                pos = Vec2::new(
                    oi as f64 + rng.range(0.1, 0.9),
                    oj as f64 + rng.range(0.1, 0.9),
                );
                let to = Vec2::new(di as f64 + 0.5, dj as f64 + 0.5) - pos;
                angle = (-to.y).atan2(to.x).to_degrees() + rng.range(-25.0, 25.0);
            }
        }
        let eye_z = rng.range(0.05, (ceil - floor - 0.05).min(0.95));
        let pitch = rng.range(-30.0, 30.0);
        let fov = rng.range(40.0, 110.0);
        let (width, height) = (16 + rng.below(160), 2 * (5 + rng.below(45)));
        let camera = Camera::from_angle(pos, angle, fov);
        let view = View::new(pitch, eye_z).on_ground(floor);
        let mut fb = Framebuffer::new(width, height);
        Scene::new(&world, camera)
            .with_view(view)
            .render_into(&mut fb, None);
        if n % 6 == 0 {
            // `render --format png` shows the same frame (its eye stands on the cell's floor).
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_halfcast"))
                .args([
                    "render",
                    path.to_str().unwrap(),
                    "--pos",
                    &format!("{},{}", pos.x, pos.y),
                    "--angle",
                    &angle.to_string(),
                    "--fov",
                    &fov.to_string(),
                    "--pitch",
                    &pitch.to_string(),
                    "--z",
                    &eye_z.to_string(),
                    "--size",
                    &format!("{width}x{}", height / 2),
                    "--strict",
                ])
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            let png = Framebuffer::from_image_bytes(&out.stdout).unwrap();
            assert!(
                png == fb,
                "case {n}: render --format png differs from Scene::render"
            );
        }

        // The reference's own camera maths, from the formulas.
        let a = angle.to_radians();
        let d = Vec2::new(a.cos(), -a.sin());
        let half = (fov.to_radians() / 2.0).tan();
        let plane = Vec2::new(-d.y * half, d.x * half);
        let focal = width as f64 / (2.0 * half);
        let hh = height as f64;
        let horizon = hh / 2.0 + (focal * pitch.to_radians().tan()).clamp(-hh, hh);
        let eye = floor + eye_z;
        let mut differ = 0;
        for x in 0..width {
            let ray = d + plane * (2.0 * x as f64 / width as f64 - 1.0);
            for y in 0..height {
                let slope = (y as f64 + 0.5 - horizon) / focal;
                let want = reference_pixel(&case, pos, ray, eye, slope);
                if want == case.door || want == y_shade(case.door, true) {
                    door_pixels += 1;
                }
                if fb.get(x, y) != want {
                    if differ < 5 && std::env::var_os("DEBUG_REF").is_some() {
                        eprintln!("({x},{y}) got {:?} want {want:?}", fb.get(x, y));
                    }
                    differ += 1;
                }
            }
        }
        let frac = differ as f64 / (width * height) as f64;
        worst = worst.max(frac);
        assert!(
            frac <= 0.005,
            "case {n}: {differ} of {} pixels differ ({:.3} %); pos {pos:?} angle {angle} fov {fov} pitch {pitch} eye {eye} size {width}x{height}\n{text}",
            width * height,
            frac * 100.0
        );
    }
    println!("worst frame: {:.4} % of pixels differ", worst * 100.0);
    println!("{door_pixels} pixels showed a door ({maps_with_doors} maps had one)");
    assert!(door_pixels > 0, "no case showed a door");
}

#[test]
fn a_flat_world_drawn_by_the_heights_renderer_looks_as_before() {
    // The default map (textures, sprites, doors, fog, lamps) plus one unused `Hz 0 1` zone takes
    // the heights path; every cell still spans 0..1, so the frame must be today's: walls with
    // the same texel rows, floors world-anchored the same, sprites hidden the same.
    use halfcast::map::parse_map;
    use halfcast::world::door::DoorState;
    use halfcast::world::{TextureSource, DEFAULT_MAP};
    let load = |extra: &str| {
        let text = format!("{extra}{DEFAULT_MAP}");
        let map = parse_map("default.cub", text.as_bytes()).unwrap();
        World::load(map, &TextureSource::Embedded, true).unwrap().0
    };
    let flat = load("");
    let heights = load("Hz 0 1\n");
    assert!(!flat.map.has_heights() && heights.map.has_heights());
    let mut doors = DoorState::new(&flat.map);
    for cell in doors.cells().to_vec() {
        doors.set_open(cell, 0.4);
    }
    let poses = [
        (Vec2::new(14.5, 9.5), 30.0, 0.0, 0.5, false),
        (Vec2::new(5.3, 5.7), 33.0, 12.0, 0.3, true),
        (Vec2::new(12.5, 5.5), 200.0, -20.0, 0.8, false),
        (Vec2::new(20.5, 4.5), -60.0, 5.0, 0.5, true),
    ];
    for (pos, angle, pitch, eye, night) in poses {
        let render = |w: &World| {
            let mut s = Scene::new(w, Camera::from_angle(pos, angle, 66.0))
                .with_view(View::new(pitch, eye))
                .with_doors(&doors)
                .at_time(0.7);
            s.light.night = night;
            s.render(120, 40)
        };
        let (a, b) = (render(&flat), render(&heights));
        let differ = a
            .pixels()
            .iter()
            .zip(b.pixels())
            .filter(|(p, q)| p != q)
            .count();
        println!(
            "{pos:?} {angle}: {differ} of {} pixels differ",
            a.pixels().len()
        );
        assert!(
            differ * 1000 <= a.pixels().len() * 5,
            "{pos:?} {angle}: {differ} pixels differ"
        );
    }
}

/// A lamp as the reference sees it: where, how far, how bright, and its segment of light (its
/// cell's floor up one wall height, clipped by the ceiling).
struct RefLamp {
    pos: Vec2,
    radius: f64,
    strength: f64,
    lo: f64,
    hi: f64,
}

/// A cell's open span for light: (floor, ceiling), `None` for a wall.
type Span = Option<(f64, f64)>;

/// The open span of a cell for light: doors count open (0..1), solid cells none.
fn light_span(case: &Case, i: i64, j: i64) -> Span {
    match case.cell(i, j) {
        Cell::Solid => None,
        Cell::Open { floor, ceil, .. } => Some((floor, ceil)),
        Cell::Door { .. } => Some((0.0, 1.0)),
    }
}

/// Issue 14's lamp rule at the map point `p` at height `z`, in [0, 1], walked in small steps
/// along the straight line from each lamp (no grid stepping shared with the engine): a wall on
/// the way hides it (a point inside a wall is seen when that wall is the first met: its lit
/// face); a floor the line from the lamp's top passes under, or a ceiling the line from its
/// bottom passes over, hides it; else it shines by the 3-D distance to its segment. `three_d`
/// false gives the flat 2-D rule (for showing the test can tell the two apart).
fn lamp_light_at(case: &Case, lamps: &[RefLamp], p: Vec2, z: f64, three_d: bool) -> f64 {
    let own = (p.x.floor() as i64, p.y.floor() as i64);
    let mut sum = 0.0;
    for l in lamps {
        let d = (p - l.pos).length();
        if d >= l.radius {
            continue;
        }
        let steps = (d / 0.004).ceil().max(1.0) as usize;
        let mut seen = true;
        // Most steps stay in the cell of the step before: its span is looked up once.
        let mut last: Option<((i64, i64), Span)> = None;
        for k in 0..=steps {
            let s = k as f64 / steps as f64;
            let q = l.pos + (p - l.pos) * s;
            let cell = (q.x.floor() as i64, q.y.floor() as i64);
            let span = match last {
                Some((c, span)) if c == cell => span,
                _ => light_span(case, cell.0, cell.1),
            };
            last = Some((cell, span));
            let Some((floor, ceil)) = span else {
                seen = cell == own;
                break;
            };
            if three_d
                && (l.hi + (z - l.hi) * s < floor - 1e-3 || l.lo + (z - l.lo) * s > ceil + 1e-3)
            {
                seen = false;
                break;
            }
        }
        if !seen {
            continue;
        }
        let dz = if three_d {
            (l.lo - z).max(z - l.hi).max(0.0)
        } else {
            0.0
        };
        let t = ((d * d + dz * dz).sqrt() / l.radius).min(1.0);
        sum += l.strength * (1.0 - t * t).powi(2);
    }
    sum.min(1.0)
}

/// Light samples already walked: (sample column, row, height's bits, 3-D rule) → level.
type SampleMemo = std::collections::HashMap<(i64, i64, u64, bool), f64>;

/// The lamp light the README documents for surface point `p` at height `z`, in 256ths: the rule
/// of [`lamp_light_at`] taken at the light map's samples (4 per cell each way, at their centres)
/// around `p`, blended bilinearly (samples past the map's edge clamped to it).
/// `memo` keeps each sample's value for one case and its lamps (many pixels share a sample and
/// a height: a floor's, a ceiling's), so the walk is done once per sample.
fn reference_lamp_level(
    case: &Case,
    lamps: &[RefLamp],
    memo: &mut SampleMemo,
    p: Vec2,
    z: f64,
    three_d: bool,
) -> u16 {
    let (sx, sy) = (p.x * 4.0 - 0.5, p.y * 4.0 - 0.5);
    let (x0, y0) = (sx.floor(), sy.floor());
    let (fx, fy) = (sx - x0, sy - y0);
    let (w, h) = ((case.w * 4 - 1) as f64, (case.h * 4 - 1) as f64);
    let mut sample = |x: f64, y: f64| {
        let (x, y) = (x.clamp(0.0, w), y.clamp(0.0, h));
        *memo
            .entry((x as i64, y as i64, z.to_bits(), three_d))
            .or_insert_with(|| {
                let at = Vec2::new((x + 0.5) / 4.0, (y + 0.5) / 4.0);
                (lamp_light_at(case, lamps, at, z, three_d) * 256.0).round()
            })
    };
    let top = sample(x0, y0) * (1.0 - fx) + sample(x0 + 1.0, y0) * fx;
    let bottom = sample(x0, y0 + 1.0) * (1.0 - fx) + sample(x0 + 1.0, y0 + 1.0) * fx;
    (top * (1.0 - fy) + bottom * fy).round() as u16
}

#[test]
fn lamps_light_every_surface_by_its_3d_distance_like_the_reference() {
    use halfcast::render::light::{Lighting, ShadeTable};
    // `SHADE 3`: dark beyond a step from the eye, so the lamps show (at night the eye's own
    // lantern outshines them near it).
    let night = Lighting {
        falloff: 3.0,
        ..Lighting::default()
    };
    let table = ShadeTable::new(&night);
    let (mut total, mut lit, mut off, mut off_2d) = (0usize, 0usize, 0usize, 0usize);
    for n in 0..30u64 {
        let mut rng = Rng(0x51a7_e5ed_0000_0001 ^ (n + 7).wrapping_mul(0x1000_0000_01b3));
        let (case, text, _) = Case::random(&mut rng);
        // One to three lamps over random open cells.
        let open: Vec<usize> = (0..case.cells.len())
            .filter(|&k| matches!(case.cells[k], Cell::Open { .. }))
            .collect();
        let mut lamps = Vec::new();
        let mut lines = String::new();
        for _ in 0..1 + rng.below(3) {
            let k = open[rng.below(open.len())];
            let pos = Vec2::new(
                (k % case.w) as f64 + rng.range(0.2, 0.8),
                (k / case.w) as f64 + rng.range(0.2, 0.8),
            );
            let (radius, strength) = (rng.range(2.0, 5.0), rng.range(0.6, 1.0));
            let Cell::Open { floor, ceil, .. } = case.cells[k] else {
                unreachable!()
            };
            lines += &format!("LIGHT {},{} {radius} {strength}\n", pos.x, pos.y);
            lamps.push(RefLamp {
                pos,
                radius,
                strength,
                lo: floor,
                hi: ceil.min(floor + 1.0),
            });
        }
        let text = text.replacen("TD dr.png\n", &format!("TD dr.png\n{lines}"), 1);
        let dir = tempfile::tempdir().unwrap();
        for (name, c) in ["no.png", "so.png", "we.png", "ea.png"]
            .iter()
            .zip(case.walls)
        {
            flat_png(dir.path(), name, c);
        }
        flat_png(dir.path(), "dr.png", case.door);
        let path = dir.path().join("m.cub");
        std::fs::write(&path, &text).unwrap();
        let (world, _) = World::from_file(&path, true).unwrap();
        assert_eq!(world.map.lights.len(), lamps.len());
        // Stand near the first lamp, looking across it.
        let l0 = lamps[0].pos;
        let (floor, ceil) = light_span(&case, l0.x.floor() as i64, l0.y.floor() as i64).unwrap();
        let eye_z = rng.range(0.05, (ceil - floor - 0.05).clamp(0.06, 0.95));
        let angle = rng.range(-180.0, 180.0);
        let a = angle.to_radians();
        let d = Vec2::new(a.cos(), -a.sin());
        let pos = l0 - d * 0.15;
        if !matches!(
            case.cell(pos.x.floor() as i64, pos.y.floor() as i64),
            Cell::Open { .. }
        ) || ceil - floor < 0.2
        {
            continue;
        }
        let (floor, _) = light_span(&case, pos.x.floor() as i64, pos.y.floor() as i64).unwrap();
        let pitch = rng.range(-30.0, 30.0);
        let fov = rng.range(50.0, 100.0);
        let (width, height) = (60 + rng.below(100), 2 * (20 + rng.below(30)));
        let camera = Camera::from_angle(pos, angle, fov);
        let view = View::new(pitch, eye_z).on_ground(floor);
        let mut fb = Framebuffer::new(width, height);
        Scene::new(&world, camera)
            .with_view(view)
            .with_light(night)
            .render_into(&mut fb, None);
        let half = (fov.to_radians() / 2.0).tan();
        let plane = Vec2::new(-d.y * half, d.x * half);
        let focal = width as f64 / (2.0 * half);
        let hh = height as f64;
        let horizon = hh / 2.0 + (focal * pitch.to_radians().tan()).clamp(-hh, hh);
        let eye = floor + eye_z;
        let mut memo = SampleMemo::new();
        for x in 0..width {
            let ray = d + plane * (2.0 * x as f64 / width as f64 - 1.0);
            for y in 0..height {
                let slope = (y as f64 + 0.5 - horizon) / focal;
                let hit = reference_hit(&case, pos, ray, eye, slope);
                // Faces are lit just in front of them, on the side the ray came from.
                let back = if hit.face { 0.01 / ray.length() } else { 0.0 };
                let p = pos + ray * (hit.t - back);
                let colour = |level: u16| {
                    let s = table.at(hit.t).lit(level);
                    let s = if hit.side_y { s.scaled(184) } else { s };
                    s.apply(hit.paint)
                };
                let level = reference_lamp_level(&case, &lamps, &mut memo, p, hit.z, true);
                let want = colour(level);
                let flat = colour(reference_lamp_level(
                    &case, &lamps, &mut memo, p, hit.z, false,
                ));
                let got = fb.get(x, y);
                let far = |a: Rgb, b: Rgb| {
                    a.r.abs_diff(b.r)
                        .max(a.g.abs_diff(b.g))
                        .max(a.b.abs_diff(b.b))
                        > 10
                };
                if far(got, want) && std::env::var_os("DEBUG_REF").is_some() && off < 40 {
                    eprintln!(
                        "case {n} ({x},{y}) got {got:?} want {want:?} flat {flat:?} level {level} z {:.2} face {} p {p:?} t {:.2}",
                        hit.z, hit.face, hit.t
                    );
                }
                total += 1;
                lit += usize::from(level > 0);
                off += usize::from(far(got, want));
                off_2d += usize::from(far(flat, want));
            }
        }
    }
    let share = |k: usize| k as f64 / total.max(1) as f64 * 100.0;
    println!(
        "{total} pixels, {:.1} % lamp-lit; {:.2} % off the 3-D reference by more than 10 (the 2-D rule: {:.2} %)",
        share(lit),
        share(off),
        share(off_2d)
    );
    assert!(share(lit) > 20.0, "too few lamp-lit pixels to judge");
    assert!(
        share(off) <= 1.0,
        "{:.2} % of pixels off the reference",
        share(off)
    );
    assert!(
        off_2d > 3 * off,
        "the flat 2-D rule would pass too ({off_2d} vs {off}): the test cannot tell"
    );
}
