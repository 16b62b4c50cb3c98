//! Issue 56: what a packaged crate's README and docs point at is in that package, so they hold
//! where crates.io and docs.rs show them, and in the unpacked crate: every relative link and
//! image (to a listed file, and to a heading that exists when it names one), and every file of
//! the repository a shell command in them uses. Checked over `cargo package --list` of each
//! crate of the workspace.

use std::collections::BTreeSet;
use std::path::{Component, Path, PathBuf};

use crate::common::root;

/// A crate of the workspace: its name and its folder in the repository.
const PACKAGES: [(&str, &str); 2] = [("halfcast", ""), ("ratatui-cells", "crates/ratatui-cells")];

/// The files `cargo package --list` puts in `package`, as paths inside it.
fn package_files(package: &str) -> BTreeSet<String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    let out = std::process::Command::new(cargo)
        .args([
            "package",
            "--list",
            "--allow-dirty",
            "--offline",
            "-p",
            package,
        ])
        .current_dir(root())
        .output()
        .expect("cargo package runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(str::to_owned)
        .collect()
}

/// `path` with `.` and `..` folded away (`None` if it climbs out of the package).
fn normal(path: &Path) -> Option<String> {
    let mut parts: Vec<String> = Vec::new();
    for c in path.components() {
        match c {
            Component::Normal(p) => parts.push(p.to_string_lossy().into_owned()),
            Component::ParentDir => {
                parts.pop()?;
            }
            Component::CurDir => {}
            _ => return None,
        }
    }
    Some(parts.join("/"))
}

/// Whether `path` (inside the package) is a listed file or a folder holding some.
fn packaged(files: &BTreeSet<String>, path: &str) -> bool {
    let dir = format!("{}/", path.trim_end_matches('/'));
    files.contains(path) || files.iter().any(|f| f.starts_with(&dir))
}

/// GitHub's anchor for a heading: lower case, punctuation dropped, spaces as hyphens.
fn slug(heading: &str) -> String {
    let text = strip_links(heading);
    text.trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// `[text](url)` as `text`.
fn strip_links(s: &str) -> String {
    let mut out = String::new();
    let mut rest = s;
    while let Some(open) = rest.find('[') {
        out.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        match after
            .find("](")
            .and_then(|m| after[m..].find(')').map(|c| (m, m + c)))
        {
            Some((m, close)) => {
                out.push_str(&after[..m]);
                rest = &after[close + 1..];
            }
            None => {
                out.push('[');
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// A markdown file's prose lines (fenced blocks left out) and its code blocks' lines with their
/// language, each with its line number.
struct Markdown {
    prose: Vec<(usize, String)>,
    code: Vec<(usize, String, String)>,
}

fn read_markdown(text: &str) -> Markdown {
    let (mut prose, mut code) = (Vec::new(), Vec::new());
    let mut fence: Option<String> = None;
    for (n, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if let Some(rest) = t.strip_prefix("```") {
            fence = match fence {
                Some(_) => None,
                None => Some(rest.trim().to_owned()),
            };
            continue;
        }
        match &fence {
            Some(lang) => code.push((n + 1, lang.clone(), line.to_owned())),
            None => prose.push((n + 1, line.to_owned())),
        }
    }
    Markdown { prose, code }
}

/// The anchors of a markdown file's headings (`-1`, `-2` … for repeated ones).
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    for (_, line) in read_markdown(text).prose {
        let Some(heading) = line.strip_prefix('#') else {
            continue;
        };
        let base = slug(heading.trim_start_matches('#'));
        let mut name = base.clone();
        let mut k = 0;
        while seen.contains(&name) {
            k += 1;
            name = format!("{base}-{k}");
        }
        seen.insert(name);
    }
    // `<a id="…">` / `<a name="…">` anchors too.
    for part in text.split("<a ").skip(1) {
        for key in ["id=\"", "name=\""] {
            if let Some(v) = part.split(key).nth(1).and_then(|v| v.split('"').next()) {
                seen.insert(v.to_owned());
            }
        }
    }
    seen
}

/// The link targets of a prose line: inline links and images `[x](t)`, and reference
/// definitions `[x]: t`; inline code is not looked into.
fn targets(line: &str) -> Vec<String> {
    let plain: String = line.split('`').step_by(2).collect::<Vec<_>>().join("``");
    let mut out = Vec::new();
    let t = plain.trim_start();
    if t.starts_with('[') {
        if let Some((_, def)) = t.split_once("]: ") {
            if let Some(target) = def.split_whitespace().next() {
                out.push(target.to_owned());
            }
        }
    }
    for piece in plain.split("](").skip(1) {
        if let Some(end) = piece.find(')') {
            let target = piece[..end].split_whitespace().next().unwrap_or("");
            out.push(target.trim_matches(['<', '>']).to_owned());
        }
    }
    out
}

/// Words of a shell line that name something in the package's folder `base` of the repository
/// (relative, with a `/`; a glob expands to the files it matches): `(word, paths it names)`.
fn repository_paths(base: &Path, line: &str) -> Vec<(String, Vec<String>)> {
    let code = line.split(" #").next().unwrap_or("");
    code.split(|c: char| c.is_whitespace() || c == '=')
        .map(|w| w.trim_matches(['"', '\'', '(', ')', ';', ',']))
        .filter(|w| {
            w.contains('/') && !w.starts_with(['-', '/', '~', '$', '.']) && !w.contains("://")
        })
        // What cargo builds (`target/release/halfcast`) is never in a package.
        .filter(|w| !w.starts_with("target/"))
        .filter_map(|w| {
            let named = if w.contains('*') {
                glob(base, w)
            } else {
                vec![w.to_owned()]
            };
            let named: Vec<String> = named
                .into_iter()
                .filter(|p| base.join(p).exists())
                .collect();
            (!named.is_empty()).then(|| (w.to_owned(), named))
        })
        .collect()
}

/// The files a `dir/*.ext`-style pattern matches (one `*`, in the last part).
fn glob(base: &Path, pattern: &str) -> Vec<String> {
    let (dir, name) = pattern.rsplit_once('/').unwrap_or(("", pattern));
    let Some((head, tail)) = name.split_once('*') else {
        return vec![];
    };
    let Ok(entries) = std::fs::read_dir(base.join(dir)) else {
        return vec![];
    };
    let mut out: Vec<String> = entries
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.starts_with(head) && n.ends_with(tail) && n.len() >= head.len() + tail.len())
        .map(|n| format!("{dir}/{n}"))
        .collect();
    out.sort();
    out
}

/// Every broken link and unpackaged file in `package`'s markdown files, as `file:line: what`.
fn problems(package: &str, folder: &str) -> (Vec<String>, usize) {
    let files = package_files(package);
    let base = root().join(folder);
    let (mut bad, mut checked) = (Vec::new(), 0);
    for doc in files.iter().filter(|f| f.ends_with(".md")) {
        let text = std::fs::read_to_string(base.join(doc)).unwrap();
        let md = read_markdown(&text);
        let here = Path::new(doc).parent().unwrap_or(Path::new(""));
        for (n, line) in &md.prose {
            for target in targets(line) {
                if target.contains(':') && !target.starts_with('#') {
                    continue; // an address on the web (https:, mailto:), not a file
                }
                checked += 1;
                let (path, fragment) = target.split_once('#').unwrap_or((&target, ""));
                let inside = if path.is_empty() {
                    Some(doc.clone())
                } else {
                    normal(&here.join(path))
                };
                let Some(inside) = inside.filter(|p| packaged(&files, p)) else {
                    bad.push(format!(
                        "{package}: {doc}:{n}: {target} is not in the package"
                    ));
                    continue;
                };
                if !fragment.is_empty() && inside.ends_with(".md") {
                    let linked = std::fs::read_to_string(base.join(&inside)).unwrap();
                    if !anchors(&linked).contains(fragment) {
                        bad.push(format!("{package}: {doc}:{n}: {target}: no such heading"));
                    }
                }
            }
        }
        for (n, lang, line) in &md.code {
            if !["sh", "bash", "shell", "console"].contains(&lang.as_str()) {
                continue;
            }
            for (word, paths) in repository_paths(&base, line) {
                for p in paths {
                    checked += 1;
                    // Commands run in the package's own folder.
                    let inside = PathBuf::from(&p);
                    if !normal(&inside).is_some_and(|p| packaged(&files, &p)) {
                        bad.push(format!(
                            "{package}: {doc}:{n}: the command's {word} names {p}, which is not in the package"
                        ));
                    }
                }
            }
        }
    }
    (bad, checked)
}

#[test]
fn every_link_and_file_the_packaged_docs_name_is_in_the_package() {
    let mut total = 0;
    for (package, folder) in PACKAGES {
        let (bad, checked) = problems(package, folder);
        println!("{package}: {checked} links and files checked");
        assert!(bad.is_empty(), "{}", bad.join("\n"));
        total += checked;
    }
    // The README alone links a dozen files and pictures.
    assert!(total >= 50, "only {total} links and files checked");
}

#[test]
fn the_checks_see_what_they_must() {
    assert_eq!(
        slug(" Glyphs: four times the pixels in the same terminal"),
        "glyphs-four-times-the-pixels-in-the-same-terminal"
    );
    assert_eq!(
        slug(" `render --format json` and [rays](x.md)"),
        "render---format-json-and-rays"
    );
    assert_eq!(
        targets("see [a](../b.md#c), ![img](d.png \"t\") and `[not](e.md)`"),
        ["../b.md#c", "d.png"]
    );
    assert_eq!(targets("[ref]: docs/x.md"), ["docs/x.md"]);
    assert_eq!(
        normal(Path::new("docs/../crates/x/README.md")).unwrap(),
        "crates/x/README.md"
    );
    assert_eq!(normal(Path::new("../README.md")), None);
    let words = repository_paths(
        root(),
        "halfcast replay tests/fixtures/walk_turn_debug.hcr --out frames/ # tests/x",
    );
    assert_eq!(words.len(), 1);
    assert_eq!(words[0].1, ["tests/fixtures/walk_turn_debug.hcr"]);
    let files: BTreeSet<String> = ["docs/a.md".to_owned()].into();
    assert!(packaged(&files, "docs") && packaged(&files, "docs/a.md") && !packaged(&files, "doc"));
}
