//! The ray debugger in the browser (issue 53), against `halfcast serve --web` as a process
//! serving three maps (one with heights, one with doors): `/trace.svg` and `/trace.png` are the
//! bytes `halfcast trace` writes for the same values, a bad address gets `trace`'s message, and
//! in Debian's headless Chromium (Playwright for Python, `browser/ray_check.py`) a fresh page
//! opened at a ray's address shows the hit cell, the perpendicular distance and `wall_x` that
//! `trace` prints, a figure whose crossings, hit cell and perp are `trace`'s, and steps forward
//! and back. The rays are fixed ones and a few drawn at random (the seed is printed; set
//! `HALFCAST_RAY_SEED` to repeat one). Prints a skip notice when Chromium or Playwright is absent.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::Command;

use halfcast::trace_query::TraceQuery;
use halfcast::{Vec2, World};
use serde_json::Value;

use crate::serve_process::{free_port, spawn_server};
use crate::serve_support::browser;

/// The maps served, in rotation order.
const MAPS: [&str; 3] = ["maps/default.cub", "maps/heights.cub", "maps/level1.cub"];
/// trace's top view: where cell `min`'s corner is drawn (output/figure/mod.rs: MARGIN + 36, 112).
const TRACE_ORIGIN: (f64, f64) = (52.0, 112.0);
/// The page's figure: the same (ray_figure.js ORIGIN).
const PAGE_ORIGIN: (f64, f64) = (40.0, 30.0);

fn repo(p: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(p)
}

/// One ray as `trace` takes it.
#[derive(Debug, Clone)]
struct Ray {
    map: &'static str,
    pos: (f64, f64),
    angle: f64,
    column: usize,
    size: (u16, u16),
    fov: Option<f64>,
}

impl Ray {
    fn map_name(&self) -> &str {
        self.map.rsplit('/').next().unwrap()
    }

    fn address(&self) -> String {
        let mut a = format!(
            "pos={},{}&angle={}&column={}&size={}x{}",
            self.pos.0, self.pos.1, self.angle, self.column, self.size.0, self.size.1
        );
        if let Some(f) = self.fov {
            a.push_str(&format!("&fov={f}"));
        }
        a.push_str(&format!("&map={}", self.map_name()));
        a
    }

    fn trace(&self, extra: &[&str]) -> Vec<u8> {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_halfcast"));
        cmd.arg("trace").arg(repo(self.map)).args([
            "--pos",
            &format!("{},{}", self.pos.0, self.pos.1),
            "--angle",
            &self.angle.to_string(),
            "--column",
            &self.column.to_string(),
            "--size",
            &format!("{}x{}", self.size.0, self.size.1),
        ]);
        if let Some(f) = self.fov {
            cmd.args(["--fov", &f.to_string()]);
        }
        let out = cmd.args(extra).output().expect("halfcast trace runs");
        assert!(
            out.status.success(),
            "{self:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        out.stdout
    }
}

/// A small deterministic generator (xorshift), so a printed seed repeats a run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// A pose on `map` drawn from `rng` that `trace` accepts (open cell, room for the eye).
fn random_ray(rng: &mut Rng, map: &'static str) -> Ray {
    let world = World::from_file(&repo(map), false)
        .expect("the map loads")
        .0;
    loop {
        let i = rng.below(world.map.width as u64) as i64;
        let j = rng.below(world.map.height as u64) as i64;
        let cols = 20 + rng.below(180) as u16;
        let ray = Ray {
            map,
            // Two decimals, as a person would type them.
            pos: (
                (i * 100 + 5 + rng.below(90) as i64) as f64 / 100.0,
                (j * 100 + 5 + rng.below(90) as i64) as f64 / 100.0,
            ),
            angle: rng.below(3600) as f64 / 10.0,
            column: rng.below(u64::from(cols)) as usize,
            size: (cols, 10 + rng.below(50) as u16),
            fov: (rng.below(3) == 0).then(|| 40.0 + rng.below(80) as f64),
        };
        let mut q = TraceQuery::column(ray.column);
        q.pos = Some(Vec2::new(ray.pos.0, ray.pos.1));
        q.angle = Some(ray.angle);
        q.size = ray.size;
        q.fov = ray.fov.unwrap_or(q.fov);
        // Long enough to step through.
        if q.trace(&world).is_ok_and(|t| t.cast.trace.steps.len() >= 4) {
            return ray;
        }
    }
}

fn rays(seed: u64) -> Vec<Ray> {
    let ray = |map, pos, angle, column, size, fov| Ray {
        map,
        pos,
        angle,
        column,
        size,
        fov,
    };
    let mut out = vec![
        // docs/learning-dda.md's ray: 10 steps, 7.86 − 1.40 = 6.46, wall_x 0.41.
        ray(MAPS[0], (15.3, 5.6), 62.0, 39, (50, 23), None),
        ray(MAPS[0], (15.5, 5.5), 90.0, 0, (80, 24), None),
        // The stairs of docs/learning-dda.md: faces narrow the window.
        ray(MAPS[1], (1.5, 9.5), 90.0, 40, (80, 24), None),
        ray(MAPS[2], (2.5, 2.5), 10.0, 70, (120, 40), Some(90.0)),
        // West from the start to the door at (11,5): perp to its panel.
        ray(MAPS[0], (15.5, 5.5), 180.0, 40, (80, 24), None),
    ];
    let mut rng = Rng(seed | 1);
    for map in MAPS {
        out.push(random_ray(&mut rng, map));
    }
    out
}

fn seed() -> u64 {
    std::env::var("HALFCAST_RAY_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| {
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .unwrap()
                .as_nanos() as u64
        })
}

/// GET `path` on the web port: status and body bytes.
fn get(port: u16, path: &str) -> (u16, Vec<u8>) {
    let mut s = std::net::TcpStream::connect(("127.0.0.1", port)).expect("the web port answers");
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut reply = Vec::new();
    s.read_to_end(&mut reply).expect("a response");
    let end = reply
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a head")
        + 4;
    let head = String::from_utf8_lossy(&reply[..end]).into_owned();
    let status = head
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    (status, reply[end..].to_vec())
}

/// `halfcast serve --web` with the three maps; its web port once it listens.
fn serve(dir: &Path) -> (crate::serve_process::Guard, u16) {
    let maps: Vec<String> = MAPS.iter().map(|m| repo(m).display().to_string()).collect();
    let (guard, web, _log) = serve_maps(dir, &maps);
    (guard, web)
}

/// `halfcast serve --web` with `maps` (none: the embedded map); its web port once it listens,
/// and its log, which must be kept while players play (the server writes a line for each).
fn serve_maps(
    dir: &Path,
    maps: &[String],
) -> (
    crate::serve_process::Guard,
    u16,
    std::sync::mpsc::Receiver<String>,
) {
    let web = free_port();
    let web_addr = format!("127.0.0.1:{web}");
    let mut args = vec!["--web", &web_addr];
    args.extend(maps.iter().map(String::as_str));
    let (guard, _port, log) = spawn_server(dir, &args);
    for _ in 0..200 {
        if std::net::TcpStream::connect(("127.0.0.1", web)).is_ok() {
            return (guard, web, log);
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    panic!("the web port never opened");
}

#[test]
fn the_web_s_trace_figures_are_trace_s_bytes_and_bad_addresses_get_its_message() {
    let dir = tempfile::tempdir().unwrap();
    let (_server, web) = serve(dir.path());
    let seed = seed();
    println!("ray seed {seed} (HALFCAST_RAY_SEED repeats it)");
    for ray in rays(seed) {
        let (status, svg) = get(web, &format!("/trace.svg?{}", ray.address()));
        assert_eq!(status, 200, "{ray:?}: {}", String::from_utf8_lossy(&svg));
        assert!(
            svg == ray.trace(&[]),
            "{ray:?}: /trace.svg is not trace's SVG"
        );
        let (status, png) = get(web, &format!("/trace.png?{}", ray.address()));
        assert_eq!(status, 200);
        assert!(
            png == ray.trace(&["--format", "png"]),
            "{ray:?}: /trace.png differs"
        );
        let (status, json) = get(web, &format!("/trace.json?{}", ray.address()));
        assert_eq!(status, 200);
        let data: Value = serde_json::from_slice(&json).unwrap();
        assert_eq!(data["map"], ray.map_name());
    }
    // A bad address: 400 and the line trace prints after "error: ".
    let base = Ray {
        map: MAPS[0],
        pos: (15.3, 5.6),
        angle: 62.0,
        column: 39,
        size: (50, 23),
        fov: None,
    };
    for (query, flags) in [
        ("pos=abc&column=1", vec!["--pos", "abc", "--column", "1"]),
        (
            "pos=0.5,0.5&column=1",
            vec!["--pos", "0.5,0.5", "--column", "1"],
        ),
        (
            "column=90&size=80x24",
            vec!["--column", "90", "--size", "80x24"],
        ),
        ("column=1&fov=200", vec!["--column", "1", "--fov", "200"]),
        ("column=1&size=80", vec!["--column", "1", "--size", "80"]),
    ] {
        let (status, body) = get(web, &format!("/trace.json?{query}"));
        assert_eq!(status, 400, "{query}");
        let message = String::from_utf8(body).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_halfcast"))
            .arg("trace")
            .arg(repo(base.map))
            .args(&flags)
            .output()
            .unwrap();
        let said = String::from_utf8_lossy(&out.stderr);
        assert!(
            said.lines().next() == Some(&format!("error: {}", message.trim_end())),
            "{query}: the page is told {message:?}, trace says {said:?}"
        );
    }
    let (status, body) = get(web, "/trace.svg?column=1&map=nowhere.cub");
    assert_eq!(status, 400);
    assert!(String::from_utf8_lossy(&body).contains("heights.cub"));
}

/// What trace's SVG says about its ray: the crossings (step, side, label, circle centre in map
/// units), the perp label, the hit cell (from its filled rect) and the notes' lines.
struct TraceFacts {
    crossings: Vec<(u64, String, String, f64, f64)>,
    perp: String,
    hit: (i64, i64),
    notes: Vec<String>,
}

fn attr(line: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let at = line.find(&key)? + key.len();
    Some(line[at..].split('"').next()?.to_owned())
}

fn text_of(line: &str) -> String {
    line.split('>')
        .nth(1)
        .unwrap_or("")
        .split('<')
        .next()
        .unwrap_or("")
        .to_owned()
}

fn facts(svg: &str, grid: &Value) -> TraceFacts {
    let cell = {
        let span = grid["width"]
            .as_f64()
            .unwrap()
            .max(grid["height"].as_f64().unwrap());
        (720.0 / span).clamp(36.0, 72.0).floor()
    };
    let (x0, y0) = (grid["x0"].as_f64().unwrap(), grid["y0"].as_f64().unwrap());
    let to_map = |x: f64, y: f64| {
        (
            (x - TRACE_ORIGIN.0) / cell + x0,
            (y - TRACE_ORIGIN.1) / cell + y0,
        )
    };
    let mut last_circle = (0.0, 0.0);
    let (mut crossings, mut perp, mut hit, mut notes) =
        (Vec::new(), String::new(), None, Vec::new());
    let num = |l: &str, a: &str| {
        attr(l, a)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    for line in svg.lines() {
        if line.starts_with("<circle") && line.contains("stroke=\"#fafaf6\"") {
            last_circle = (num(line, "cx"), num(line, "cy"));
        } else if line.contains("class=\"crossing ") {
            let side = attr(line, "class").unwrap().replace("crossing ", "");
            let (x, y) = to_map(last_circle.0, last_circle.1);
            let step = attr(line, "data-step").unwrap().parse().unwrap();
            crossings.push((step, side, text_of(line), x, y));
        } else if line.contains("class=\"perp\"") {
            perp = text_of(line);
        } else if line.starts_with("<rect")
            && line.contains("fill=\"#f6b0a8\"")
            && num(line, "width") == cell
        {
            let (x, y) = to_map(num(line, "x"), num(line, "y"));
            hit = Some((x.round() as i64, y.round() as i64));
        } else if line.starts_with("<text") {
            notes.push(text_of(line));
        }
    }
    TraceFacts {
        crossings,
        perp,
        hit: hit.expect("trace's hit cell"),
        notes,
    }
}

#[test]
fn chromium_shows_the_ray_trace_draws_and_steps_through_it() {
    if !browser::ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (_server, web) = serve(dir.path());
    let seed = seed();
    println!("ray seed {seed} (HALFCAST_RAY_SEED repeats it)");
    let rays = rays(seed);
    let cases: Vec<Value> = rays
        .iter()
        .enumerate()
        .map(|(k, r)| {
            serde_json::json!({
                "name": format!("ray{k}"),
                "address": r.address(),
                "preview": (r.column + 1) % usize::from(r.size.0),
            })
        })
        .collect();
    let cases_file = dir.path().join("cases.json");
    std::fs::write(&cases_file, serde_json::to_string(&cases).unwrap()).unwrap();
    let url = format!("http://127.0.0.1:{web}");
    let figures = browser::run(
        "ray_check.py",
        &[url.as_ref(), cases_file.as_os_str(), dir.path().as_os_str()],
    );
    let refused = figures["refused"].as_str().unwrap();
    assert_eq!(
        refused,
        "--pos 0.5,0.5 is inside a wall, cell (0,0) of default.cub \
         (29x22 cells, x 0 to 29 and y 0 to 22): start in an open cell",
        "the page shows trace's message for a ray in a wall"
    );
    // ray_text.js's num() prints as render::derivation::num does.
    let numbers: Vec<String> = [
        0.125, 0.375, 0.625, -0.125, 2.5, 1e30, 5e29, -0.001, 2.876, 1234567.0,
    ]
    .map(halfcast::trace_query::data::num)
    .into();
    assert_eq!(figures["numbers"], serde_json::json!(numbers));
    let pages = figures["rays"].as_array().unwrap();
    for (ray, page) in rays.iter().zip(pages) {
        let (_, json) = get(web, &format!("/trace.json?{}", ray.address()));
        let data: Value = serde_json::from_slice(&json).unwrap();
        let svg = String::from_utf8(ray.trace(&[])).unwrap();
        check_page(ray, page, &data, &facts(&svg, &data["grid"]));
    }
    println!("{} rays checked in Chromium", pages.len());
}

fn check_page(ray: &Ray, page: &Value, data: &Value, trace: &TraceFacts) {
    let ctx = format!("{ray:?}");
    assert_eq!(page["errors"], serde_json::json!([]), "{ctx}");
    let text = page["text"].as_str().unwrap();
    // The hit cell and perp as trace's notes print them, and wall_x.
    let hit = format!("hit ({},{})", trace.hit.0, trace.hit.1);
    let notes = trace
        .notes
        .iter()
        .find(|l| l.contains(&hit))
        .unwrap_or_else(|| panic!("{ctx}: {:?}", trace.notes));
    let perp_eq = notes
        .split(": ")
        .nth(1)
        .unwrap()
        .split("    ")
        .next()
        .unwrap();
    assert!(
        text.contains(&hit),
        "{ctx}: the page does not say {hit}:\n{text}"
    );
    // perp's last number, and on a grid-line hit trace's whole equation.
    let perp_value = perp_eq.rsplit(" = ").next().unwrap();
    let perp_line = text
        .lines()
        .find(|l| l.trim_start().starts_with("perp ="))
        .unwrap_or("");
    assert!(
        perp_line.ends_with(&format!(" = {perp_value}")),
        "{ctx}: {perp_line:?} is not perp {perp_value}"
    );
    if perp_eq.starts_with("perp = sideDist") {
        assert!(
            text.contains(perp_eq),
            "{ctx}: the page does not say {perp_eq}:\n{text}"
        );
    }
    let wall_x = notes.rsplit("wall_x ").next().unwrap();
    assert!(
        text.contains("wall_x") && text.contains(wall_x),
        "{ctx}: wall_x {wall_x}"
    );
    // On a heights map, each face's narrowing of the window, and where it closed.
    if let Some(h) = data["heights"].as_object() {
        for f in h["faces"].as_array().unwrap() {
            let w = |k: &str| format!("{}..{}", f[k][0], f[k][1]);
            let says = format!("window {} → {}", w("before"), w("after"));
            assert!(text.contains(&says), "{ctx}: no {says:?} in\n{text}");
        }
        let closed = format!("window closed ({},{})", h["closed"][0], h["closed"][1]);
        assert!(text.contains(&closed), "{ctx}: no {closed:?}");
    }
    // The figure: the same crossings at the same places, the same hit cell and perp label.
    let fig = &page["figure"];
    let crossings = fig["crossings"].as_array().unwrap();
    let steps = data["steps"].as_array().unwrap().len();
    assert_eq!(crossings.len(), steps, "{ctx}: one crossing per step");
    let shown: Vec<&Value> = crossings
        .iter()
        .filter(|c| {
            trace
                .crossings
                .iter()
                .any(|t| t.0 == c["step"].as_u64().unwrap())
        })
        .collect();
    assert_eq!(shown.len(), trace.crossings.len(), "{ctx}");
    let cell = {
        let g = &data["grid"];
        (720.0
            / g["width"]
                .as_f64()
                .unwrap()
                .max(g["height"].as_f64().unwrap()))
        .clamp(36.0, 72.0)
        .floor()
    };
    for (t, p) in trace.crossings.iter().zip(&shown) {
        assert_eq!(t.0, p["step"].as_u64().unwrap(), "{ctx}");
        assert_eq!(t.1, p["side"].as_str().unwrap(), "{ctx}: step {}", t.0);
        assert_eq!(t.2, p["label"].as_str().unwrap(), "{ctx}: step {}", t.0);
        let px = (p["cx"].as_f64().unwrap() - PAGE_ORIGIN.0) / cell
            + data["grid"]["x0"].as_f64().unwrap();
        let py = (p["cy"].as_f64().unwrap() - PAGE_ORIGIN.1) / cell
            + data["grid"]["y0"].as_f64().unwrap();
        assert!(
            (px - t.3).abs() < 0.2 / cell && (py - t.4).abs() < 0.2 / cell,
            "{ctx}: crossing {} at ({px}, {py}) on the page, ({}, {}) in trace's figure",
            t.0,
            t.3,
            t.4
        );
    }
    assert_eq!(fig["perp"].as_str(), Some(trace.perp.as_str()), "{ctx}");
    let r = fig["hit_rect"].as_array().unwrap();
    let page_hit = (
        ((r[0].as_f64().unwrap() - PAGE_ORIGIN.0) / cell).round() as i64
            + data["grid"]["x0"].as_i64().unwrap(),
        ((r[1].as_f64().unwrap() - PAGE_ORIGIN.1) / cell).round() as i64
            + data["grid"]["y0"].as_i64().unwrap(),
    );
    assert_eq!(page_hit, trace.hit, "{ctx}: the figure's hit cell");
    // The export links are trace's routes for the same ray.
    let address = data["address"].as_str().unwrap();
    assert_eq!(
        page["export"],
        serde_json::json!([
            format!("/trace.svg?{address}"),
            format!("/trace.png?{address}")
        ]),
        "{ctx}"
    );
    // The address the page ends on is the ray's own.
    let url = page["url"].as_str().unwrap();
    assert!(
        url.ends_with(&format!("/ray?{}", data["address"].as_str().unwrap())),
        "{ctx}: {url}"
    );
    check_walk(&ctx, page, steps);
    println!(
        "{} {}: {steps} steps, {hit}, {}, {} crossings placed as trace's",
        ray.map_name(),
        ray.address(),
        trace.perp,
        trace.crossings.len()
    );
}

/// Home, →, →, ←, next, prev, End: setup, 1, 2, 1, 2, 1, the hit (clamped to the steps there are).
fn check_walk(ctx: &str, page: &Value, steps: usize) {
    let part = |k: usize| match k.min(steps + 1) {
        0 => "setup".to_owned(),
        k if k > steps => format!("hit ({steps} steps)"),
        k => format!("step {k} of {steps}"),
    };
    let walk = page["walk"].as_array().unwrap();
    for (got, k) in walk.iter().zip([0, 1, 2, 1, 2, 1, steps + 1]) {
        assert_eq!(got["part"].as_str().unwrap(), part(k), "{ctx}: {walk:?}");
        if (1..=steps).contains(&k.min(steps + 1)) {
            let k = k.min(steps);
            let current = got["current"][0].as_str().unwrap();
            assert!(
                current.trim_start().starts_with(&format!("{k} sideDistX")),
                "{ctx}: {current}"
            );
            assert!(
                got["now"]
                    .as_str()
                    .unwrap()
                    .starts_with(&format!("Step {k}:")),
                "{ctx}"
            );
        }
    }
    let step1 = page["figure_step1"]["crossings"].as_array().unwrap();
    for c in step1 {
        let k = c["step"].as_u64().unwrap();
        assert_eq!(
            c["current"].as_bool(),
            Some(k == 1),
            "{ctx}: crossing {k} at step 1"
        );
        assert_eq!(
            c["later"].as_bool(),
            Some(k > 1),
            "{ctx}: crossing {k} at step 1"
        );
    }
    let hover = page["hover"].as_str().unwrap_or("");
    let last = format!("-crossing {steps}: sideDist");
    assert!(
        hover.contains(&last),
        "{ctx}: hovering crossing {steps} says {hover:?}"
    );
    let preview = page["preview_title"].as_str().unwrap();
    assert!(preview.contains("preview"), "{ctx}: {preview}");
    assert!(
        !page["after_preview_title"]
            .as_str()
            .unwrap()
            .contains("preview"),
        "{ctx}"
    );
}

/// `key=value` of an address, by key.
fn address_value<'a>(address: &'a str, key: &str) -> &'a str {
    address
        .split('&')
        .find_map(|kv| kv.strip_prefix(key)?.strip_prefix('='))
        .unwrap_or_else(|| panic!("{key} in {address}"))
}

/// A player clicks a column of the live view: the page's address then carries the ray as
/// `halfcast trace` takes it, trace with those values finds the hit cell and perpendicular
/// distance the page shows, stepping walks the derivation, and the address opened in a fresh
/// browser shows the same ray without playing.
#[test]
fn a_click_on_the_view_debugs_that_column_and_its_address_reproduces_it() {
    if !browser::ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (_server, web, _log) = serve_maps(dir.path(), &[]);
    let column = 1 + seed() % 30;
    let (url, column_arg) = (format!("http://127.0.0.1:{web}"), column.to_string());
    let got = browser::run(
        "click_check.py",
        &[url.as_ref(), column_arg.as_ref(), dir.path().as_os_str()],
    );
    println!("clicked column {column}: /?{}", got["address"]);
    let address = got["address"].as_str().unwrap();
    assert_eq!(address_value(address, "column"), column.to_string());
    let decoded = |v: &str| v.replace("%2C", ",");
    let svg = dir.path().join("clicked.svg");
    let trace = Command::new(env!("CARGO_BIN_EXE_halfcast"))
        .args(["trace", "--pos", &decoded(address_value(address, "pos"))])
        .args(["--angle", address_value(address, "angle")])
        .args(["--column", address_value(address, "column")])
        .args(["--size", address_value(address, "size")])
        // The address names the field of view only when it is not the default, as trace's does.
        .args(
            address
                .split('&')
                .find_map(|kv| kv.strip_prefix("fov="))
                .map(|f| ["--fov", f])
                .into_iter()
                .flatten(),
        )
        .arg("-o")
        .arg(&svg)
        .output()
        .expect("trace runs");
    assert!(trace.status.success(), "{trace:?}");
    let svg = std::fs::read_to_string(&svg).unwrap();
    let perp: f64 = attr(
        svg.lines().find(|l| l.contains("data-perp=")).unwrap(),
        "data-perp",
    )
    .unwrap()
    .parse()
    .unwrap();
    let hit = svg
        .split("hit (")
        .nth(1)
        .and_then(|s| s.split(')').next())
        .expect("trace names its hit cell");
    let text = got["text"].as_str().unwrap();
    for (what, shown) in [("hit", format!("({hit})")), ("perp", format!("{perp:.2}"))] {
        assert!(
            text.contains(&shown),
            "the page's {what} {shown} is not in:\n{text}"
        );
        assert!(
            got["fresh_text"].as_str().unwrap().contains(&shown),
            "the fresh page's {what} {shown}"
        );
    }
    assert_eq!(
        got["fresh_frames"], 0,
        "the shared ray shows without playing"
    );
    let parts: Vec<&str> = got["parts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p.as_str().unwrap())
        .collect();
    assert_eq!(parts[1], "setup", "{parts:?}");
    assert_eq!(parts[2], parts[4], "forward and back: {parts:?}");
    assert!(parts[3].starts_with("step 2 of"), "{parts:?}");
    assert!(parts[5].starts_with("hit ("), "{parts:?}");
    assert_eq!(got["errors"], serde_json::json!([]));
}
