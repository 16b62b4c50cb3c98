//! The public cub3D maps in ../shared/corpus/cub3d: valid ones load and render, invalid ones are
//! refused (exit 2) with the rule `SOURCES.tsv` names, contested ones follow halfcast's documented rules.

use crate::common;

use std::path::Path;

use common::{halfcast, shared_dir};
use halfcast::camera::Camera;
use halfcast::world::World;
use halfcast::Scene;

/// One row of SOURCES.tsv: file, category, reason.
struct Entry {
    file: String,
    category: String,
    reason: String,
}

fn entries(corpus: &Path) -> Vec<Entry> {
    let tsv = std::fs::read_to_string(corpus.join("SOURCES.tsv")).expect("SOURCES.tsv");
    tsv.lines()
        .skip(1)
        .filter_map(|l| {
            let cols: Vec<&str> = l.split('\t').collect();
            (cols.len() >= 6).then(|| Entry {
                file: cols[0].into(),
                category: cols[4].into(),
                reason: cols[5].into(),
            })
        })
        .collect()
}

/// The halfcast message fragment a SOURCES.tsv reason must show up as; `None` = must load.
fn expected_fragment(reason: &str) -> Option<String> {
    let reason = reason.trim();
    let contested = reason.contains("halfcast rules say");
    if reason == "-" || reason.contains("halfcast rules say valid") {
        return None;
    }
    // Contested rows read "source says …; halfcast rules say invalid (REASON)".
    let reason = reason
        .rsplit_once("halfcast rules say invalid (")
        .map_or(reason, |(_, r)| r.strip_suffix(')').unwrap_or(r));
    let after = |p: &str| reason.strip_prefix(p).map(str::to_owned);
    Some(if let Some(id) = after("bad colour ") {
        format!("bad colour for {id}:")
    } else if let Some(id) = after("missing ") {
        format!("missing identifier '{id}'")
    } else if let Some(id) = after("no space after ") {
        format!("no space after identifier '{id}'")
    } else if let Some(id) = after("duplicate ") {
        format!("duplicate identifier '{id}'")
    } else if let Some(rest) = after("not closed at line ") {
        let (line, col) = rest.split_once(" col ").expect("line N col M");
        format!("map is not closed: floor cell at {line}:{col} touches void")
    } else if reason.ends_with("needs one path") {
        format!(
            "{} needs exactly one texture path",
            reason.split(' ').next().unwrap()
        )
    } else if reason.starts_with("blank line inside or after the map") {
        "content after the blank line at".to_owned()
    } else if reason == "no map" {
        "no map grid after the header".to_owned()
    } else if reason == "0 players" {
        "no player start".to_owned()
    } else if reason == "2 players" {
        "second player start".to_owned()
    } else if reason.starts_with("bad map character") && contested {
        // halfcast names the first bad character in reading order; the source's checker differs.
        "bad map character '".to_owned()
    } else if reason.starts_with("bad map character") || reason.starts_with("unknown identifier") {
        reason.to_owned()
    } else {
        panic!("no expectation for reason '{reason}'")
    })
}

#[test]
fn corpus_maps_follow_halfcasts_rules() {
    let Some(shared) = shared_dir("corpus test") else {
        return;
    };
    let corpus = shared.join("corpus/cub3d");
    let all = entries(&corpus);
    assert!(all.len() > 50, "SOURCES.tsv looks truncated");
    let (mut loaded, mut refused) = (0, 0);
    for e in &all {
        let path = corpus.join(&e.category).join(&e.file);
        let path_str = path.to_str().unwrap();
        match expected_fragment(&e.reason) {
            None => {
                let (world, _warnings) = World::from_file(&path, false)
                    .unwrap_or_else(|err| panic!("{} should load: {err}", e.file));
                let start = world.map.start;
                let cam = Camera::from_angle(start.pos(), start.angle_deg(), 66.0);
                let fb = Scene::new(&world, cam).render(32, 10);
                assert_eq!(fb.height(), 20);
                loaded += 1;
            }
            Some(fragment) => {
                let out = halfcast(&["render", path_str, "--format", "txt"]);
                let stderr = String::from_utf8_lossy(&out.stderr);
                assert_eq!(
                    out.status.code(),
                    Some(2),
                    "{} should be refused: {stderr}",
                    e.file
                );
                assert!(
                    stderr.starts_with(&format!("error: {path_str}")),
                    "{}: {stderr}",
                    e.file
                );
                assert!(
                    stderr.contains(&fragment),
                    "{}: expected '{fragment}' in {stderr}",
                    e.file
                );
                refused += 1;
            }
        }
    }
    println!("corpus: {loaded} loaded, {refused} refused");
    assert!(loaded >= 40 && refused >= 40);
}
