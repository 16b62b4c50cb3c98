//! Issue 56: the features tables of the API docs' front page (src/lib.rs) and docs/library.md
//! say, row by row, which crates each feature adds, as `Cargo.toml` has it: one row per feature
//! (and one for none), and in each the feature's own dependencies, no more and no fewer.

use std::collections::{BTreeMap, BTreeSet};

use serde_json::Value;

use crate::common::root;

/// What Cargo says of halfcast: its features and the names of its normal dependencies.
struct Manifest {
    features: BTreeMap<String, Vec<String>>,
    /// Every normal dependency: name → optional.
    deps: BTreeMap<String, bool>,
}

fn manifest() -> Manifest {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    let out = std::process::Command::new(cargo)
        .args([
            "metadata",
            "--format-version",
            "1",
            "--no-deps",
            "--offline",
        ])
        .current_dir(root())
        .output()
        .expect("cargo metadata runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let meta: Value = serde_json::from_slice(&out.stdout).unwrap();
    let package = meta["packages"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "halfcast")
        .unwrap();
    let features = package["features"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(k, v)| {
            let list = v
                .as_array()
                .unwrap()
                .iter()
                .map(|s| s.as_str().unwrap().to_owned());
            (k.clone(), list.collect())
        })
        .collect();
    let deps = package["dependencies"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|d| d["kind"].is_null())
        .map(|d| {
            (
                d["name"].as_str().unwrap().to_owned(),
                d["optional"] == true,
            )
        })
        .collect();
    Manifest { features, deps }
}

/// The crates a row should name: with no feature, every dependency that is not optional; for a
/// feature, the optional ones it turns on itself (`dep:NAME`).
fn expected(m: &Manifest, feature: Option<&str>) -> BTreeSet<String> {
    match feature {
        None => m
            .deps
            .iter()
            .filter(|(_, opt)| !**opt)
            .map(|(n, _)| n.clone())
            .collect(),
        Some(f) => m.features[f]
            .iter()
            .filter_map(|e| e.strip_prefix("dep:"))
            .map(str::to_owned)
            .collect(),
    }
}

/// A table's rows as (feature, crates named in its last cell): the feature is the first cell's
/// first `code` span (`None` for the no-feature row); crates are the plain words of the last
/// cell that are dependency names (`code` spans there name features, and are skipped).
fn table(text: &str, after: &str, m: &Manifest) -> Vec<(Option<String>, BTreeSet<String>)> {
    let from = text.find(after).unwrap_or_else(|| panic!("no {after:?}"));
    let mut rows = Vec::new();
    for line in text[from..].lines().skip_while(|l| !l.starts_with('|')) {
        if !line.starts_with('|') {
            break;
        }
        let cells: Vec<&str> = line.trim_matches('|').split('|').map(str::trim).collect();
        if cells[0] == "feature" || cells[0].starts_with("---") {
            continue;
        }
        let feature = cells[0].split('`').nth(1).map(str::to_owned);
        let last = cells[cells.len() - 1];
        let plain: String = last.split('`').step_by(2).collect::<Vec<_>>().join(" ");
        let crates = plain
            .split(|c: char| !(c.is_ascii_alphanumeric() || c == '-' || c == '_'))
            .filter(|w| m.deps.contains_key(*w))
            .map(str::to_owned)
            .collect();
        rows.push((feature, crates));
    }
    rows
}

fn check(doc: &str, text: &str, after: &str) {
    let m = manifest();
    let rows = table(text, after, &m);
    let mut want: Vec<Option<String>> = m
        .features
        .keys()
        .filter(|f| *f != "default")
        .cloned()
        .map(Some)
        .collect();
    want.push(None);
    want.sort();
    let mut have: Vec<Option<String>> = rows.iter().map(|(f, _)| f.clone()).collect();
    have.sort();
    assert_eq!(have, want, "{doc}: one row per feature, and one for none");
    for (feature, crates) in rows {
        assert_eq!(
            crates,
            expected(&m, feature.as_deref()),
            "{doc}: the crates the row of {feature:?} names"
        );
    }
}

#[test]
fn the_rustdoc_front_page_names_what_each_feature_pulls_in() {
    let lib = std::fs::read_to_string(root().join("src/lib.rs")).unwrap();
    let docs: String = lib
        .lines()
        .filter_map(|l| l.strip_prefix("//!"))
        .map(|l| format!("{}\n", l.strip_prefix(' ').unwrap_or(l)))
        .collect();
    check("src/lib.rs", &docs, "# Features");
}

#[test]
fn docs_library_names_what_each_feature_pulls_in() {
    let text = std::fs::read_to_string(root().join("docs/library.md")).unwrap();
    check("docs/library.md", &text, "## Adding it");
}
