//! Issue 48: the DDA walkthrough in the README and docs/learning-dda.md quotes what the program
//! prints. Each `trace` command's figure is the SVG the doc shows, byte for byte; the ray pane
//! written out in the doc is the pane of that command's ray, line by line; every number in the
//! walkthrough's prose is one the pane or the figure prints; and the straight-north ray prints
//! the deltaDist the doc says.

use std::path::Path;

use halfcast::render::cast::cast;
use halfcast::widget::RevealedTrace;
use halfcast::{Camera, DebugPane, Vec2, World};

use crate::docs_commands::{doc_commands, read_doc, DocCommand};

const DDA: &str = "docs/learning-dda.md";

/// The `trace` commands of `doc` that write an SVG.
fn svg_traces(doc: &str) -> Vec<DocCommand> {
    doc_commands(doc)
        .into_iter()
        .filter(|c| c.args.first().is_some_and(|a| a == "trace"))
        .filter(|c| c.output().is_some_and(|o| o.ends_with(".svg")))
        .collect()
}

/// The SVG `c` writes.
fn svg_of(c: &DocCommand) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = c.run_in(dir.path());
    assert!(
        out.status.success(),
        "{}: {}",
        c.place,
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::read_to_string(dir.path().join(c.output().unwrap())).unwrap()
}

/// The text an SVG shows (its `<text>` elements), one line each.
fn svg_text(svg: &str) -> String {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| Some(t.split_once('>')?.1.split_once("</text>")?.0))
        .map(|t| {
            t.replace("&lt;", "<")
                .replace("&gt;", ">")
                .replace("&amp;", "&")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The images a doc shows (`![…](name.svg)`), in order, as paths from the repository root.
fn svg_images(doc: &str) -> Vec<String> {
    let dir = Path::new(doc).parent().unwrap();
    read_doc(doc)
        .split("](")
        .skip(1)
        .filter_map(|rest| rest.split_once(')').map(|(link, _)| link.to_owned()))
        .filter(|link| link.ends_with(".svg"))
        .map(|link| dir.join(link).display().to_string())
        .collect()
}

/// The ray pane of `c`'s column, every line, as the game writes it for that camera and view.
fn pane_lines(c: &DocCommand) -> Vec<String> {
    let world = match c.args.get(1).filter(|a| a.ends_with(".cub")) {
        Some(map) => {
            World::from_file(&crate::common::root().join(map), false)
                .unwrap()
                .0
        }
        None => World::default_world(),
    };
    let (x, y) = c.value("--pos").unwrap().split_once(',').unwrap();
    let pos = Vec2::new(x.parse().unwrap(), y.parse().unwrap());
    let angle: f64 = c.value("--angle").unwrap().parse().unwrap();
    let fov: f64 = c.value("--fov").map_or(66.0, |f| f.parse().unwrap());
    let cam = Camera::from_angle(pos, angle, fov);
    let (cols, rows) = c.value("--size").unwrap().split_once('x').unwrap();
    let size: (usize, usize) = (cols.parse().unwrap(), rows.parse().unwrap());
    let column: usize = c.value("--column").unwrap().parse().unwrap();
    let cast = cast(&world.map, &cam, size.0, Some(column));
    let trace = cast.trace.as_ref().unwrap();
    let pane = DebugPane::new(RevealedTrace::full(trace), &world, &cam, size);
    pane.lines(500).iter().map(ToString::to_string).collect()
}

/// Whitespace-insensitive form of a line (the doc may indent differently).
fn squash(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The lines of the first ```` ```text ```` block of `doc`.
fn first_text_block(doc: &str) -> Vec<String> {
    let text = read_doc(doc);
    let start = text.find("```text\n").expect("a text block") + "```text\n".len();
    let len = text[start..].find("```").unwrap();
    text[start..start + len]
        .lines()
        .map(str::to_owned)
        .collect()
}

/// `text` without its fenced code blocks (what is left is prose with inline code).
fn without_code_blocks(text: &str) -> String {
    let mut fenced = false;
    let mut out = String::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// The numbers in `s` (`2.24`, `1e30`, `16` of `(16,4)`), signs and units dropped.
fn numbers(s: &str) -> Vec<f64> {
    let keep = |c: char| c.is_ascii_digit() || c == '.' || c == 'e';
    s.split(|c: char| !keep(c))
        .flat_map(|w| w.split(".."))
        .map(|w| w.trim_matches(|c| c == '.' || c == 'e'))
        .filter(|w| w.starts_with(|c: char| c.is_ascii_digit()))
        .filter_map(|w| w.parse().ok())
        .collect()
}

#[test]
fn each_trace_figure_in_learning_dda_is_what_its_command_draws() {
    let commands: Vec<DocCommand> = svg_traces(DDA)
        .into_iter()
        .filter(|c| c.output() != Some("north.svg"))
        .collect();
    let images = svg_images(DDA);
    assert_eq!(
        commands.len(),
        images.len(),
        "{commands:?} against {images:?}"
    );
    for (c, image) in commands.iter().zip(&images) {
        let shown = read_doc(image);
        assert!(
            svg_of(c) == shown,
            "{}: the figure differs from {image}",
            c.place
        );
    }
    // The README's walkthrough is the same ray as the chapter's.
    let readme = svg_traces("README.md");
    assert_eq!(readme.len(), 1);
    assert!(
        svg_of(&readme[0]) == read_doc(&images[0]),
        "{}",
        readme[0].place
    );
}

#[test]
fn the_ray_pane_written_out_in_learning_dda_is_the_pane_of_its_command() {
    let walk = &svg_traces(DDA)[0];
    let pane: Vec<String> = pane_lines(walk).iter().map(|l| squash(l)).collect();
    // Every line the doc shows, in the pane's order (`…` stands for the steps left out).
    let mut from = 0;
    for line in first_text_block(DDA) {
        let want = squash(&line);
        if want == "…" {
            continue;
        }
        let at = pane[from..].iter().position(|l| *l == want);
        assert!(
            at.is_some(),
            "{want:?} is not in the pane (from line {from}):\n{}",
            pane.join("\n")
        );
        from += at.unwrap() + 1;
    }
    // The README quotes one of its steps.
    let readme = read_doc("README.md");
    let section = readme.split("## Learning the DDA").nth(1).unwrap();
    let section = section.split("\n## ").next().unwrap();
    let prose = without_code_blocks(section);
    let readme_pane = pane_lines(&svg_traces("README.md")[0]).join("\n");
    for quote in prose.split('`').skip(1).step_by(2) {
        // What it quotes from the pane, not the commands it gives the reader.
        if quote.contains(|c: char| c.is_ascii_digit()) && !quote.starts_with("halfcast") {
            assert!(
                readme_pane.contains(quote),
                "README quotes {quote:?}:\n{readme_pane}"
            );
        }
    }
}

#[test]
fn every_number_of_the_walkthrough_is_printed_by_the_pane_or_the_figure() {
    let traces = svg_traces(DDA);
    let walk = &traces[0];
    let north = traces
        .iter()
        .find(|c| c.output() == Some("north.svg"))
        .unwrap();
    let mut printed = pane_lines(walk).join("\n") + "\n" + &svg_text(&svg_of(walk));
    printed += &svg_text(&svg_of(north));
    let mut known = numbers(&printed);
    // What the reader types, the view it makes (80×24, its 50 + 30 columns, the pane's start
    // column 25, four presses) and the plane's half-length tan(FOV/2), which the text derives.
    for c in [walk, north] {
        known.extend(numbers(&c.args.join(" ")));
    }
    known.extend([80.0, 24.0, 30.0, 25.0, 4.0, (33f64).to_radians().tan()]);
    let text = read_doc(DDA);
    // The walkthrough: from "The ray we follow" to the heights section, headings left out.
    let start = text.find("## The ray we follow").unwrap();
    let end = text.find("## 6.").unwrap();
    let prose: Vec<&str> = text[start..end]
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("!["))
        .collect();
    let missing: Vec<f64> = numbers(&prose.join("\n"))
        .into_iter()
        .filter(|n| !known.iter().any(|k| (k - n).abs() < 0.005))
        .collect();
    assert!(
        missing.is_empty(),
        "quoted but not printed: {missing:?}\n{printed}"
    );
}

#[test]
fn the_straight_north_ray_prints_the_delta_dist_the_doc_says() {
    let north = svg_traces(DDA)
        .into_iter()
        .find(|c| c.output() == Some("north.svg"))
        .expect("learning-dda.md's north.svg command");
    let quote = "deltaDist = |1/rayDir| = (1e30, 1.00)";
    assert!(read_doc(DDA).contains(&format!("`{quote}`")));
    let svg = svg_text(&svg_of(&north));
    assert!(svg.contains(quote), "{}: {svg}", north.place);
}
