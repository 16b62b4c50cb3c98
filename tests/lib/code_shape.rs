//! The shape rules of the rooms that grew the most (`src/serve/`, `src/play/`, `src/tui/`): no
//! function over 120 lines, no file over 700 lines (tests included), and nowhere in `src/` two
//! files that use each other. `cargo test --test lib code_shape -- --nocapture` prints the
//! longest functions and largest files of all of `src/`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use super::architecture::{code_only, ident, root, rust_files, skip_braced, stripped};

/// The rooms the limits hold in.
const KEPT_SMALL: [&str; 3] = ["serve", "play", "tui"];
const MAX_FN_LINES: usize = 120;
const MAX_FILE_LINES: usize = 700;

/// Every `fn` in stripped source: its name and its lines, from the `fn` line to its closing
/// brace (declarations without a body are left out).
fn functions(code: &str) -> Vec<(String, usize)> {
    let b = code.as_bytes();
    let mut found = Vec::new();
    let mut at = 0;
    while let Some(off) = code[at..].find("fn ") {
        let i = at + off;
        at = i + 3;
        let before = code[..i].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let name = ident(&code[i + 3..]);
        if name.is_empty() {
            continue; // `fn(` types
        }
        let mut j = i;
        let mut parens = 0i32;
        while j < b.len() {
            match b[j] {
                b'(' | b'<' | b'[' => parens += 1,
                // `->` is an arrow, not a closing angle bracket.
                b'>' if j > 0 && b[j - 1] == b'-' => {}
                b')' | b'>' | b']' => parens -= 1,
                b'{' | b';' if parens <= 0 => break,
                _ => {}
            }
            j += 1;
        }
        if j >= b.len() || b[j] == b';' {
            continue;
        }
        let end = skip_braced(code, j);
        let lines = code[i..end].matches('\n').count() + 1;
        found.push((name, lines));
    }
    found
}

fn src_files() -> Vec<PathBuf> {
    let mut files = Vec::new();
    rust_files(&root().join("src"), &mut files);
    files.sort();
    files
}

fn rel(file: &Path) -> String {
    file.strip_prefix(root()).unwrap().display().to_string()
}

fn kept_small(file: &Path) -> bool {
    let r = rel(file);
    KEPT_SMALL
        .iter()
        .any(|room| r.starts_with(&format!("src/{room}/")))
}

#[test]
fn functions_and_files_in_the_kept_rooms_stay_short() {
    let mut fns = Vec::new();
    let mut files = Vec::new();
    for file in src_files() {
        let src = std::fs::read_to_string(&file).unwrap();
        files.push((src.lines().count(), rel(&file)));
        for (name, lines) in functions(&stripped(&src, false)) {
            fns.push((lines, format!("{} {name}", rel(&file))));
        }
    }
    fns.sort_by(|a, b| b.cmp(a));
    files.sort_by(|a, b| b.cmp(a));
    println!("longest functions in src/:");
    for (lines, what) in fns.iter().take(8) {
        println!("  {lines:>4}  {what}");
    }
    println!("largest files in src/:");
    for (lines, what) in files.iter().take(8) {
        println!("  {lines:>5}  {what}");
    }
    let in_rooms = |what: &str| {
        KEPT_SMALL
            .iter()
            .any(|room| what.starts_with(&format!("src/{room}/")))
    };
    if let (Some(f), Some(file)) = (
        fns.iter().find(|(_, w)| in_rooms(w)),
        files.iter().find(|(_, w)| in_rooms(w)),
    ) {
        println!(
            "in src/{{{}}}: longest function {} lines ({}), largest file {} lines ({})",
            KEPT_SMALL.join(","),
            f.0,
            f.1,
            file.0,
            file.1
        );
    }
    let long: Vec<_> = fns
        .iter()
        .filter(|(l, w)| *l > MAX_FN_LINES && in_rooms(w))
        .collect();
    assert!(
        long.is_empty(),
        "functions over {MAX_FN_LINES} lines: {long:?}"
    );
    let big: Vec<_> = files
        .iter()
        .filter(|(l, w)| *l > MAX_FILE_LINES && in_rooms(w))
        .collect();
    assert!(big.is_empty(), "files over {MAX_FILE_LINES} lines: {big:?}");
    assert!(
        src_files().iter().any(|f| kept_small(f)),
        "no kept room found"
    );
}

/// The module file for `segments` under `dir`, as far as files go: `a/b.rs` or `a/b/mod.rs`.
fn resolve(dir: &Path, segments: &[String]) -> Option<PathBuf> {
    let mut cur = dir.to_path_buf();
    let mut found = None;
    for seg in segments {
        let file = cur.join(format!("{seg}.rs"));
        let module = cur.join(seg).join("mod.rs");
        if file.is_file() {
            found = Some(file);
        } else if module.is_file() {
            found = Some(module);
        } else {
            break;
        }
        cur = cur.join(seg);
    }
    found
}

/// The paths a piece of code names from `start` (`crate::`, `super::`), groups expanded.
fn paths(code: &str, start: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find(start) {
        let before = rest[..at].chars().next_back();
        rest = &rest[at + start.len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$' || c == ':') {
            continue;
        }
        expand(rest, Vec::new(), &mut out);
    }
    out
}

/// Reads `a::b::{c, d::e}` at the start of `s` into every full path.
fn expand(s: &str, prefix: Vec<String>, out: &mut Vec<Vec<String>>) {
    let mut path = prefix;
    let mut s = s;
    loop {
        if let Some(group) = s.strip_prefix('{') {
            let end = skip_braced(s, 0) - 1;
            let mut depth = 0;
            let mut from = 0;
            for (k, c) in group[..end - 1].char_indices().chain([(end - 1, ',')]) {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        expand(group[from..k].trim_start(), path.clone(), out);
                        from = k + 1;
                    }
                    _ => {}
                }
            }
            return;
        }
        let word = ident(s);
        if word.is_empty() || word == "self" {
            break;
        }
        s = &s[word.len()..];
        path.push(word);
        match s.strip_prefix("::") {
            Some(more) => s = more,
            None => break,
        }
    }
    out.push(path);
}

/// The directory `super::` means in `file` (its parent module's folder).
fn super_dir(file: &Path) -> PathBuf {
    let dir = file.parent().unwrap();
    if file.file_name().is_some_and(|n| n == "mod.rs") {
        dir.parent().unwrap().to_path_buf()
    } else {
        dir.to_path_buf()
    }
}

/// File → the files it uses, front doors (`lib.rs`, `main.rs`, `mod.rs`) left out: they list
/// and re-export their children by design.
fn file_graph() -> BTreeMap<PathBuf, BTreeSet<PathBuf>> {
    let src = root().join("src");
    let front_door = |f: &Path| {
        f.file_name()
            .is_some_and(|n| n == "mod.rs" || n == "lib.rs" || n == "main.rs")
    };
    let mut graph = BTreeMap::new();
    for file in src_files().into_iter().filter(|f| !front_door(f)) {
        let code = code_only(&std::fs::read_to_string(&file).unwrap());
        let mut uses = BTreeSet::new();
        for (dir, start) in [(src.clone(), "crate::"), (super_dir(&file), "super::")] {
            for p in paths(&code, start) {
                if let Some(target) = resolve(&dir, &p) {
                    if target != file && !front_door(&target) {
                        uses.insert(target);
                    }
                }
            }
        }
        graph.insert(file, uses);
    }
    graph
}

#[test]
fn no_two_files_in_src_use_each_other() {
    let graph = file_graph();
    assert!(graph.len() > 100, "the files were not read");
    let mut circles = Vec::new();
    for (file, uses) in &graph {
        // Every file reached from `file`: a circle when `file` is among them.
        let mut seen = BTreeSet::new();
        let mut todo: Vec<&PathBuf> = uses.iter().collect();
        while let Some(f) = todo.pop() {
            if seen.insert(f) {
                todo.extend(graph.get(f).into_iter().flatten());
            }
        }
        if seen.contains(file) {
            circles.push(rel(file));
        }
    }
    assert!(circles.is_empty(), "files on a circle of uses: {circles:?}");
}

#[test]
fn the_reader_finds_functions_and_grouped_paths() {
    let code = "fn a() {\n    x();\n}\ntrait T { fn b(&self); }\nfn c<F: Fn() -> u8>(f: F) -> [u8; 2] { [f(), 0] }\n";
    assert_eq!(
        functions(code),
        vec![("a".to_owned(), 3), ("c".to_owned(), 1)]
    );
    let got = paths("use super::{a::{B, c}, d};", "super::");
    let want: Vec<Vec<String>> = [vec!["a", "B"], vec!["a", "c"], vec!["d"]]
        .iter()
        .map(|p| p.iter().map(|s| (*s).to_owned()).collect())
        .collect();
    assert_eq!(got, want);
}
