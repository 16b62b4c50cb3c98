//! Issue 25: the ray pane's derivation and `halfcast trace`'s figure come from the same trace
//! the JSON prints. The pane's numbers are checked against `render --format json`'s document
//! for random rays (zero components and grid corners included), the SVG is parsed as XML and
//! its crossing labels checked against the trace, one PNG figure is pinned as a golden image,
//! and the pane is pinned at 80×24 and in mono.

use crate::common;

use std::sync::Arc;

use common::{halfcast, halfcast_ok, root};
use halfcast::camera::Camera;
use halfcast::encode::{ColorLevel, ColourChoice, ColourReason};
use halfcast::game::{Command, GameState, Input};
use halfcast::output::figure::ColumnCast;
use halfcast::output::json::RayReport;
use halfcast::render::cast::cast;
use halfcast::snapshot::{assert_png_golden, Tolerance};
use halfcast::ui::layout::{Panes, Toggles};
use halfcast::ui::screen::{draw, Screen};
use halfcast::widget::{DebugPane, RevealedTrace};
use halfcast::world::door::DoorState;
use halfcast::{Framebuffer, Vec2, World};
use proptest::prelude::*;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use serde_json::Value;

/// Whether `text` (a number as the pane prints it: `2.88`, `0.5012`, `5e29`) is `value`
/// rounded to the digits printed.
fn shows(text: &str, value: f64) -> bool {
    let Ok(p) = text.parse::<f64>() else {
        return false;
    };
    let step = match text.split_once('e') {
        Some((_, exp)) => 10f64.powi(exp.parse::<i32>().unwrap_or(0)),
        None => text
            .split_once('.')
            .map_or(1.0, |(_, d)| 10f64.powi(-(d.len() as i32))),
    };
    (p - value).abs() <= step / 2.0 + 1e-9 * value.abs().max(1.0)
}

/// The word after `key` in `line` (up to a space or a comma).
fn after<'a>(line: &'a str, key: &str) -> Option<&'a str> {
    let rest = &line[line.find(key)? + key.len()..];
    Some(rest.split([' ', ',']).find(|w| !w.is_empty()).unwrap_or(""))
}

/// The last number on a line (after its last `= `).
fn last_value(line: &str) -> &str {
    line.rsplit("= ")
        .next()
        .unwrap_or("")
        .split(' ')
        .next()
        .unwrap_or("")
}

/// Checks every number of the pane's derivation against the JSON document of the same frame.
fn pane_agrees_with_json(world: &World, cam: &Camera, cols: usize) -> Result<(), TestCaseError> {
    let rows = 20;
    let centre = cols / 2;
    let c = cast(&world.map, cam, cols, Some(centre));
    let json: Value = serde_json::from_str(&RayReport::new(cam, &c, rows).to_json()).unwrap();
    let steps = json["centre_trace"].as_array().unwrap();
    let column = &json["columns"][centre];
    let trace = c.trace.as_ref().unwrap();
    let pane = DebugPane::new(RevealedTrace::full(trace), world, cam, (cols, rows));
    let lines: Vec<String> = pane.lines(500).iter().map(ToString::to_string).collect();
    let all = lines.join("\n");
    // Every step: the comparison (the sideDists before it: the previous step's), the axis it
    // chose, the cell it entered and the new sideDist.
    let mut before: Option<(f64, f64)> = None;
    for (k, s) in steps.iter().enumerate() {
        let sd = (
            s["side_dist"][0].as_f64().unwrap(),
            s["side_dist"][1].as_f64().unwrap(),
        );
        let side = s["side"].as_str().unwrap();
        let head = format!("{:>3} sideDistX ", k + 1);
        let i = lines
            .iter()
            .position(|l| l.starts_with(&head))
            .ok_or_else(|| TestCaseError::fail(format!("no step {} in\n{all}", k + 1)))?;
        let cmp = &lines[i];
        let x = after(cmp, "sideDistX ").unwrap();
        let y = after(cmp, "sideDistY ").unwrap();
        if let Some(b) = before {
            prop_assert!(shows(x, b.0) && shows(y, b.1), "{cmp} vs {b:?}");
            let sign = if b.0 < b.1 {
                "<"
            } else if b.0 > b.1 {
                ">"
            } else {
                "="
            };
            prop_assert!(cmp.contains(&format!(" {sign} ")), "{cmp} vs {b:?}");
        }
        prop_assert!(
            cmp.ends_with(&format!("→ step {side}")),
            "{cmp}: json {side}"
        );
        let cell = &lines[i + 1];
        let want = format!(
            "    map({},{})",
            s["cell"][0].as_i64().unwrap(),
            s["cell"][1].as_i64().unwrap()
        );
        prop_assert!(cell.starts_with(&want), "{cell} vs {want}");
        let new = if side == "x" { sd.0 } else { sd.1 };
        let shown = cell.rsplit("→ ").next().unwrap();
        prop_assert!(shows(shown, new), "{cell} vs {new}");
        before = Some(sd);
    }
    // The hit: perp = sideDist − deltaDist with the last step's sideDist, and wall_x.
    let perp_line = lines.iter().find(|l| l.starts_with("perp = ")).unwrap();
    let perp = column["perp_dist"].as_f64().unwrap();
    prop_assert!(shows(last_value(perp_line), perp), "{perp_line} vs {perp}");
    let last = before.unwrap();
    let axis = column["side"].as_str().unwrap();
    let sd = if axis == "x" { last.0 } else { last.1 };
    if perp_line.starts_with("perp = sideDist") {
        let sub = perp_line.split(" = ").nth(2).unwrap();
        prop_assert!(
            shows(sub.split(" − ").next().unwrap(), sd),
            "{perp_line} vs {sd}"
        );
    } else {
        // A door's panel, on its cell's mid-line.
        prop_assert!(perp_line.starts_with("perp = (map"), "{perp_line}");
    }
    let wall = lines.iter().find(|l| l.starts_with("wall_x")).unwrap();
    let wall_x = column["wall_x"].as_f64().unwrap();
    let shown = wall.rsplit(['→', '=']).next().unwrap().trim();
    prop_assert!(shows(shown, wall_x), "{wall} vs {wall_x}");
    // A zero ray component: deltaDist is Lode's 1e30, and the pane says so.
    let dir = (
        json["dir"][0].as_f64().unwrap(),
        json["dir"][1].as_f64().unwrap(),
    );
    if cols.is_multiple_of(2) && (dir.0 == 0.0 || dir.1 == 0.0) {
        prop_assert!(all.contains("1e30"), "{all}");
    }
    Ok(())
}

fn open_cells(world: &World) -> Vec<(i64, i64)> {
    let m = &world.map;
    let mut out = Vec::new();
    for j in 0..40 {
        for i in 0..40 {
            if m.is_walkable(Vec2::new(i as f64 + 0.5, j as f64 + 0.5)) {
                out.push((i, j));
            }
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Random rays, axis-parallel rays (a zero component) and diagonals from cell centres
    /// (through grid corners, where the sideDists tie).
    #[test]
    fn the_panes_numbers_are_the_json_traces(
        pick in 0usize..10_000,
        frac in (0.02f64..0.98, 0.02f64..0.98),
        kind in 0u8..3,
        angle in -180.0f64..180.0,
        quarter in 0usize..4,
        fov in 30.0f64..120.0,
        half_cols in 4usize..80,
    ) {
        let world = World::default_world();
        let cells = open_cells(&world);
        let c = cells[pick % cells.len()];
        let cols = half_cols * 2;
        let cam = match kind {
            0 => Camera::from_angle(Vec2::new(c.0 as f64 + frac.0, c.1 as f64 + frac.1), angle, fov),
            1 => {
                let dirs = [(1.0, 0.0), (0.0, -1.0), (-1.0, 0.0), (0.0, 1.0)];
                let d = dirs[quarter];
                Camera::from_dir(Vec2::new(c.0 as f64 + frac.0, c.1 as f64 + frac.1), Vec2::new(d.0, d.1), fov)
            }
            _ => {
                let dirs = [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)];
                let d = dirs[quarter];
                Camera::from_dir(Vec2::new(c.0 as f64 + 0.5, c.1 as f64 + 0.5), Vec2::new(d.0, d.1), fov)
            }
        };
        pane_agrees_with_json(&world, &cam, cols)?;
    }
}

#[test]
fn a_ray_through_grid_corners_shows_the_tie_and_steps_y() {
    let world = World::default_world();
    // From a cell centre at 45°: every x- and y-line is crossed at once.
    let cam = Camera::from_dir(Vec2::new(15.5, 5.5), Vec2::new(1.0, -1.0), 66.0);
    let c = cast(&world.map, &cam, 40, Some(20));
    let t = c.trace.as_ref().unwrap();
    let pane = DebugPane::new(RevealedTrace::full(t), &world, &cam, (40, 12));
    let all: Vec<String> = pane.lines(200).iter().map(ToString::to_string).collect();
    let ties: Vec<&String> = all
        .iter()
        .filter(|l| l.contains(" = sideDistY") && !l.starts_with("perp"))
        .collect();
    assert!(!ties.is_empty(), "{all:#?}");
    assert!(ties.iter().all(|l| l.ends_with("→ step y")), "{ties:#?}");
    pane_agrees_with_json(&world, &cam, 40).unwrap();
}

/// `halfcast render --format json`'s document and `halfcast trace`'s SVG for the same pose.
fn json_and_svg(extra: &[&str]) -> (Value, String) {
    let mut args = vec!["render", "--format", "json"];
    args.extend_from_slice(extra);
    let json = serde_json::from_slice(&halfcast_ok(&args).stdout).unwrap();
    let mut args = vec!["trace", "--format", "svg", "--column", "40"];
    args.extend_from_slice(extra);
    let svg = String::from_utf8(halfcast_ok(&args).stdout).unwrap();
    (json, svg)
}

#[test]
fn the_svg_parses_and_its_crossing_labels_are_the_traces_side_dists() {
    let pose = ["--pos", "15.3,5.6", "--angle", "62", "--size", "80x24"];
    let (json, svg) = json_and_svg(&pose);
    assert!(svg.len() < 40_000, "{} bytes", svg.len());
    let doc = roxmltree::Document::parse(&svg).expect("the SVG is well-formed XML");
    let root_el = doc.root_element();
    assert_eq!(root_el.tag_name().name(), "svg");
    assert!(
        doc.descendants().all(|n| n.tag_name().name() != "image"),
        "no embedded raster"
    );
    let steps = json["centre_trace"].as_array().unwrap();
    let labels: Vec<roxmltree::Node> = doc
        .descendants()
        .filter(|n| {
            n.attribute("class")
                .is_some_and(|c| c.starts_with("crossing"))
        })
        .collect();
    assert_eq!(labels.len(), steps.len(), "{svg}");
    // The sideDist at crossing k is the chosen axis's sideDist before step k: step k−1's
    // (computed here from the position for the first step).
    let dir = (
        json["dir"][0].as_f64().unwrap(),
        json["dir"][1].as_f64().unwrap(),
    );
    let pos = (
        json["pos"][0].as_f64().unwrap(),
        json["pos"][1].as_f64().unwrap(),
    );
    let first = |p: f64, d: f64| {
        let gap = if d < 0.0 {
            p - p.floor()
        } else {
            p.floor() + 1.0 - p
        };
        gap * (1.0 / d).abs()
    };
    let mut before = (first(pos.0, dir.0), first(pos.1, dir.1));
    for (k, (label, s)) in labels.iter().zip(steps).enumerate() {
        let side = s["side"].as_str().unwrap();
        let want = if side == "x" { before.0 } else { before.1 };
        assert_eq!(
            label.attribute("class"),
            Some(format!("crossing {side}").as_str())
        );
        assert_eq!(
            label.attribute("data-step"),
            Some((k + 1).to_string().as_str())
        );
        let exact: f64 = label.attribute("data-side-dist").unwrap().parse().unwrap();
        assert!(
            (exact - want).abs() < 1e-9,
            "step {}: {exact} vs {want}",
            k + 1
        );
        let text = label.text().unwrap();
        let (n, v) = text.split_once(": ").unwrap();
        assert_eq!(n, (k + 1).to_string());
        assert!(shows(v, want), "label {text:?} vs {want}");
        before = (
            s["side_dist"][0].as_f64().unwrap(),
            s["side_dist"][1].as_f64().unwrap(),
        );
    }
    // The perpendicular distance drawn is the JSON's.
    let perp = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("perp"))
        .unwrap();
    let want = json["columns"][40]["perp_dist"].as_f64().unwrap();
    let got: f64 = perp.attribute("data-perp").unwrap().parse().unwrap();
    assert!((got - want).abs() < 1e-12);
}

#[test]
fn on_a_heights_map_the_figure_adds_the_side_view_of_the_closing_window() {
    let pose = [
        "maps/heights.cub",
        "--pos",
        "2.5,4.5",
        "--angle",
        "0",
        "--size",
        "80x24",
    ];
    let (json, svg) = json_and_svg(&pose);
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let faces: Vec<roxmltree::Node> = doc
        .descendants()
        .filter(|n| n.attribute("class").is_some_and(|c| c.starts_with("face ")))
        .collect();
    let spans = json["columns"][40]["spans"].as_array().unwrap();
    assert_eq!(faces.len(), spans.len(), "{svg}");
    for (f, s) in faces.iter().zip(spans) {
        let rows = format!("{}..{}", s["rows"][0], s["rows"][1]);
        assert_eq!(f.attribute("data-rows"), Some(rows.as_str()));
        assert_eq!(
            f.attribute("class").unwrap(),
            format!("face {}", s["kind"].as_str().unwrap())
        );
    }
}

fn golden_figure() -> Framebuffer {
    let world = World::default_world();
    let cam = Camera::from_angle(Vec2::new(15.3, 5.6), 62.0, 66.0);
    let col = ColumnCast::new(
        &world.map,
        &DoorState::new(&world.map),
        &cam,
        &halfcast::View::default(),
        (80, 24),
        62,
    );
    col.figure(&world.map, &cam, 80).to_framebuffer()
}

#[test]
fn a_png_figure_matches_its_golden_and_the_commands_png() {
    let fb = golden_figure();
    let golden = root().join("tests/images/figure/trace_default.png");
    assert_png_golden(&fb, &golden, Tolerance::default());
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fig.png");
    halfcast_ok(&[
        "trace",
        "--pos",
        "15.3,5.6",
        "--angle",
        "62",
        "--size",
        "80x24",
        "--column",
        "62",
        "-o",
        out.to_str().unwrap(),
    ]);
    let png = Framebuffer::from_image_bytes(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(png, fb, "-o NAME.png writes the PNG of the same drawing");
}

#[test]
fn bad_input_is_refused_with_exit_2_and_a_clear_message() {
    let cases: [(&[&str], &str); 3] = [
        (
            &["trace", "--column", "80", "--size", "80x24"],
            "error: column 80 is out of range: a 80-column view has columns 0 to 79\n",
        ),
        (
            &["trace", "--column", "3", "--pos", "0.5,0.5"],
            "error: --pos 0.5,0.5 is inside a wall, cell (0,0) of default.cub (29x22 cells, x 0 \
             to 29 and y 0 to 22): start in an open cell\n",
        ),
        (
            &["trace", "--column", "3", "--pos", "-4,2"],
            "error: --pos -4,2 is outside the map: default.cub is 29x22 cells, x 0 to 29 and y 0 \
             to 22\n",
        ),
    ];
    for (args, want) in cases {
        let out = halfcast(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert_eq!(String::from_utf8_lossy(&out.stderr), want, "{args:?}");
        assert!(out.stdout.is_empty());
    }
    let out = halfcast(&["trace", "--column", "3", "--format", "gif"]);
    assert_eq!(out.status.code(), Some(2));
}

/// The game screen at `size`, paused on the centre ray and stepped `steps` times, at `level`.
fn screen(size: (u16, u16), steps: usize, level: ColorLevel) -> (Buffer, Rect) {
    let world = Arc::new(World::default_world());
    let cam = Camera::from_angle(Vec2::new(15.3, 5.6), 62.0, 66.0);
    let area = Rect::new(0, 0, size.0, size.1);
    let panes = Panes::compute(area, Toggles::default());
    let Panes::Game { view, debug, .. } = panes else {
        panic!("too small")
    };
    let mut state = GameState::new(world, cam, usize::from(view.width));
    let mut commands = vec![Command::TogglePause];
    commands.extend(std::iter::repeat_n(Command::StepDda, steps + 1));
    halfcast::game::step(
        &mut state,
        &Input {
            commands,
            ..Input::default()
        },
        0.0,
    );
    let mut fb = Framebuffer::for_cells(view.width, view.height);
    let cast = halfcast::ui::render::render_view(&state, &mut fb);
    let mut stats = halfcast::tui::FrameStats::default();
    stats.level = Some(ColourChoice {
        level,
        reason: ColourReason::Flag,
    });
    let s = Screen {
        state: &state,
        view: &fb,
        cast: &cast,
        stats: &stats,
        toggles: Toggles::default(),
        input_mode: halfcast::ui::keys::InputMode::Emulated,
        results: None,
        ray_text: None,
    };
    let mut buf = Buffer::empty(area);
    draw(&s, &panes, area, &mut buf);
    (buf, debug.expect("the ray pane fits"))
}

fn pane_text(buf: &Buffer, r: Rect) -> String {
    (r.y..r.bottom())
        .map(|y| {
            (r.x..r.right())
                .map(|x| buf[(x, y)].symbol())
                .collect::<String>()
                .trim_end()
                .to_owned()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_pane_at_80x24_mid_step() {
    let (buf, r) = screen((80, 24), 3, ColorLevel::TrueColor);
    let text = pane_text(&buf, r);
    insta::assert_snapshot!(text);
    assert!(text.contains("  3 sideDist"), "{text}");
    assert!(text.contains("not yet (step 3"), "{text}");
}

#[test]
fn the_pane_in_mono_is_ascii_only() {
    let (buf, r) = screen((80, 24), 3, ColorLevel::Mono);
    let inner = Rect::new(r.x + 1, r.y + 1, r.width - 2, r.height - 2);
    let text = pane_text(&buf, inner);
    insta::assert_snapshot!(text);
    assert!(text.is_ascii(), "{text}");
    assert!(text.contains("->"), "{text}");
}

#[test]
fn the_pane_at_160x48_writes_the_derivation_out() {
    let (buf, r) = screen((160, 48), 3, ColorLevel::TrueColor);
    let text = pane_text(&buf, r);
    insta::assert_snapshot!(text);
    for want in [
        "cameraX = 2x/w",
        "rayDir = dir + plane",
        "deltaDist = |1/rayDir|",
    ] {
        assert!(text.contains(want), "{want}: {text}");
    }
}
