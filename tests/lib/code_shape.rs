//! The shape rules of the whole tree (`src/` and every `crates/*/src`): no function over 120
//! lines, no file over 700 lines (its `#[cfg(test)]` modules aside), and within each crate no two
//! files that use each other, directly or round a longer circle. `cargo test --test lib
//! code_shape -- --nocapture` prints the longest functions, the largest files and the circles.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use super::architecture::{
    code_only, ident, root, rust_files, skip_braced, stripped, test_module_follows,
};

/// The rooms that grew the most: their files stay under the file limit with their tests too.
const KEPT_SMALL: [&str; 3] = ["src/serve/", "src/play/", "src/tui/"];
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

/// The source folders the rules hold in: `src/` and each crate's `src/`.
fn source_roots() -> Vec<PathBuf> {
    let mut roots = vec![root().join("src")];
    let mut crates: Vec<PathBuf> = std::fs::read_dir(root().join("crates"))
        .into_iter()
        .flatten()
        .map(|e| e.unwrap().path().join("src"))
        .filter(|p| p.is_dir())
        .collect();
    crates.sort();
    roots.extend(crates);
    roots
}

/// The Rust files under `dir`, sorted.
fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    rust_files(dir, &mut files);
    files.sort();
    files
}

fn rel(file: &Path) -> String {
    file.strip_prefix(root()).unwrap().display().to_string()
}

/// The lines of `src` outside its `#[cfg(test)]` modules.
fn lines_without_tests(src: &str) -> usize {
    let code = stripped(src, false);
    let mut test_lines = 0;
    let mut at = 0;
    while let Some(off) = code[at..].find("#[cfg(test)]") {
        let i = at + off;
        at = i + "#[cfg(test)]".len();
        if test_module_follows(&code[at..]) {
            let end = skip_braced(&code, at);
            test_lines += code[i..end].matches('\n').count() + 1;
            at = end;
        }
    }
    src.lines().count().saturating_sub(test_lines)
}

#[test]
fn every_function_and_file_in_the_tree_stays_short() {
    let mut fns = Vec::new();
    let mut files = Vec::new();
    let mut kept_with_tests = Vec::new();
    for dir in source_roots() {
        for file in files_under(&dir) {
            let src = std::fs::read_to_string(&file).unwrap();
            files.push((lines_without_tests(&src), rel(&file)));
            if KEPT_SMALL.iter().any(|room| rel(&file).starts_with(room)) {
                kept_with_tests.push((src.lines().count(), rel(&file)));
            }
            for (name, lines) in functions(&stripped(&src, false)) {
                fns.push((lines, format!("{} {name}", rel(&file))));
            }
        }
    }
    assert!(files.len() > 100, "the files were not read");
    fns.sort_by(|a, b| b.cmp(a));
    files.sort_by(|a, b| b.cmp(a));
    println!("longest functions in src/ and crates/*/src:");
    for (lines, what) in fns.iter().take(8) {
        println!("  {lines:>4}  {what}");
    }
    println!("largest files in src/ and crates/*/src (test modules aside):");
    for (lines, what) in files.iter().take(8) {
        println!("  {lines:>5}  {what}");
    }
    let long: Vec<_> = fns.iter().filter(|(l, _)| *l > MAX_FN_LINES).collect();
    let big: Vec<_> = files.iter().filter(|(l, _)| *l > MAX_FILE_LINES).collect();
    println!(
        "over the limits: {} functions over {MAX_FN_LINES} lines, {} files over {MAX_FILE_LINES}",
        long.len(),
        big.len()
    );
    assert!(
        long.is_empty(),
        "functions over {MAX_FN_LINES} lines: {long:?}"
    );
    assert!(big.is_empty(), "files over {MAX_FILE_LINES} lines: {big:?}");
    assert!(!kept_with_tests.is_empty(), "no kept room found");
    let big: Vec<_> = kept_with_tests
        .iter()
        .filter(|(l, _)| *l > MAX_FILE_LINES)
        .collect();
    assert!(
        big.is_empty(),
        "files over {MAX_FILE_LINES} lines with their tests: {big:?}"
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

/// File → the files it uses within the crate whose source folder is `src`, front doors
/// (`lib.rs`, `main.rs`, `mod.rs`) left out: they list and re-export their children by design.
fn file_graph(src: &Path) -> BTreeMap<PathBuf, BTreeSet<PathBuf>> {
    let front_door = |f: &Path| {
        f.file_name()
            .is_some_and(|n| n == "mod.rs" || n == "lib.rs" || n == "main.rs")
    };
    let mut graph = BTreeMap::new();
    for file in files_under(src).into_iter().filter(|f| !front_door(f)) {
        let code = code_only(&std::fs::read_to_string(&file).unwrap());
        let mut uses = BTreeSet::new();
        for (dir, start) in [
            (src.to_path_buf(), "crate::"),
            (super_dir(&file), "super::"),
        ] {
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

/// The files of `graph` that reach themselves through the files they use.
fn on_circles(graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>) -> Vec<String> {
    let mut circles = Vec::new();
    for (file, uses) in graph {
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
    circles
}

#[test]
fn no_two_files_in_a_crate_use_each_other() {
    let mut circles = Vec::new();
    let mut read = 0;
    for src in source_roots() {
        let graph = file_graph(&src);
        read += graph.len();
        circles.extend(on_circles(&graph));
    }
    assert!(read > 100, "the files were not read");
    println!("files on a circle of uses: {}", circles.len());
    for file in &circles {
        println!("  {file}");
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
