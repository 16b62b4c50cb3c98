//! Semver discipline: the crate's public API, listed from its source, must equal the listing
//! committed in `public-api.txt`, and that listing can only be rewritten together with a new
//! version in Cargo.toml. A change to a public signature, field, re-export, trait impl or
//! macro therefore fails here until the version is bumped and the listing recorded with
//! `RATATUI_CELLS_RECORD_API=1`.

use std::path::Path;

/// The listing's file, beside Cargo.toml.
const LISTING: &str = "public-api.txt";

/// The crate's version now.
const VERSION: &str = env!("CARGO_PKG_VERSION");

/// A file's text without its `#[cfg(test)]` module (always the file's last item here).
fn without_tests(text: &str) -> &str {
    text.find("#[cfg(test)]\nmod ")
        .map_or(text, |at| &text[..at])
}

/// The declaration starting at line `i`, on one line: a field alone; a `use` to its `;`; any
/// other item up to its body's `{` or its `;` (outside brackets).
fn declaration(lines: &[&str], i: usize) -> String {
    let first = lines[i].trim();
    let is_field = first
        .strip_prefix("pub ")
        .and_then(|rest| rest.split_once(':'))
        .is_some_and(|(name, _)| name.chars().all(|c| c.is_alphanumeric() || c == '_'));
    if is_field {
        return first.trim_end_matches(',').to_string();
    }
    let is_use = first.starts_with("pub use ");
    let mut out = String::new();
    let mut depth = 0i32;
    'lines: for line in &lines[i..] {
        if !out.is_empty() {
            out.push(' ');
        }
        for c in line.trim().chars() {
            match c {
                '(' | '[' => depth += 1,
                ')' | ']' => depth -= 1,
                '{' if depth == 0 && !is_use => break 'lines,
                ';' if depth == 0 => break 'lines,
                _ => {}
            }
            out.push(c);
        }
    }
    out.replace("( ", "(")
        .replace(" )", ")")
        .replace("{ ", "{")
        .replace(" }", "}")
        .replace(", }", "}")
        .replace(",)", ")")
        .trim()
        .to_string()
}

/// Every public declaration in the crate's source: `pub` items and fields (not `pub(crate)`),
/// exported macros, and trait impls, one per line, sorted, with the file each is in.
fn listing(src: &Path) -> Vec<String> {
    let mut files = Vec::new();
    let mut dirs = vec![src.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(dir).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    let mut out = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        let lines: Vec<&str> = without_tests(&text).lines().collect();
        let name = file.strip_prefix(src).unwrap().display().to_string();
        for (i, line) in lines.iter().enumerate() {
            let t = line.trim_start();
            let public = t.starts_with("pub ") || t.starts_with("macro_rules!");
            let trait_impl = line.starts_with("impl") && line.contains(" for ");
            let exported =
                t.starts_with("macro_rules!") && i > 0 && lines[i - 1].trim() == "#[macro_export]";
            if (public && !t.starts_with("macro_rules!")) || trait_impl || exported {
                out.push(format!("{name}: {}", declaration(&lines, i)));
            }
            if exported {
                // The macro's forms: each arm's matcher.
                let arms = lines[i + 1..]
                    .iter()
                    .take_while(|l| !l.starts_with('}'))
                    .filter(|l| l.trim_start().starts_with('(') && l.contains("=>"));
                for arm in arms {
                    out.push(format!(
                        "{name}:   {}",
                        arm.trim().trim_end_matches(" => {")
                    ));
                }
            }
        }
    }
    out.sort();
    out
}

#[test]
fn the_public_api_changes_only_with_the_version() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let now = listing(&root.join("src"));
    let path = root.join(LISTING);
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    let (recorded_version, recorded) = committed.split_once('\n').unwrap_or(("", ""));
    let recorded_version = recorded_version.trim_start_matches("ratatui-cells ");
    let text = now.join("\n") + "\n";
    if text == recorded {
        return;
    }
    let record = std::env::var_os("RATATUI_CELLS_RECORD_API").is_some();
    if recorded_version != VERSION && record {
        std::fs::write(&path, format!("ratatui-cells {VERSION}\n{text}")).unwrap();
        return;
    }
    let old: Vec<&str> = recorded.lines().collect();
    let changes: Vec<String> = old
        .iter()
        .filter(|l| !now.iter().any(|n| n == *l))
        .map(|l| format!("- {l}"))
        .chain(
            now.iter()
                .filter(|n| !old.contains(&n.as_str()))
                .map(|n| format!("+ {n}")),
        )
        .collect();
    let what = if recorded_version == VERSION {
        format!(
            "the public API changed but the version is still {VERSION}: bump it in Cargo.toml \
             (a breaking change needs the next minor version while the crate is 0.x), then run \
             this test with RATATUI_CELLS_RECORD_API=1 to record the listing"
        )
    } else {
        format!(
            "the version is now {VERSION} (the listing was recorded at {recorded_version}): run \
             this test with RATATUI_CELLS_RECORD_API=1 to record the listing"
        )
    };
    panic!("{what}\n{}", changes.join("\n"));
}
