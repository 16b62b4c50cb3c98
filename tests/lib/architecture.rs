//! The layers in `docs/architecture.md` hold in the code: every `crate::ROOM` path in `src/`
//! (outside `#[cfg(test)]` modules and comments) names a room its row allows.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Room → the rooms it may use, from the table between the `layers` markers.
fn allowed(doc: &str) -> BTreeMap<String, BTreeSet<String>> {
    let begin = doc
        .find("<!-- layers:begin -->")
        .expect("layers:begin marker");
    let end = doc.find("<!-- layers:end -->").expect("layers:end marker");
    let mut table = BTreeMap::new();
    for line in doc[begin..end].lines().filter(|l| l.starts_with('|')) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        // | layer | room | what it holds | may use |
        let Some(room) = cells.get(2).and_then(|c| backticked(c).into_iter().next()) else {
            continue; // the header and its rule
        };
        let uses = cells.get(4).map(|c| backticked(c)).unwrap_or_default();
        table.insert(room, uses.into_iter().collect());
    }
    table
}

/// The `names` written in backticks in a table cell.
fn backticked(cell: &str) -> Vec<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_owned)
        .collect()
}

/// The source without comments, string contents or `#[cfg(test)]` modules.
pub(crate) fn code_only(src: &str) -> String {
    stripped(src, true)
}

/// The source without comments or string contents, and without `#[cfg(test)]` modules when
/// `drop_tests`; every line break is kept, so lines are where they were.
pub(crate) fn stripped(src: &str, drop_tests: bool) -> String {
    let mut out = String::with_capacity(src.len());
    let b = src.as_bytes();
    let mut i = 0;
    let breaks = |span: &str, out: &mut String| {
        out.extend(span.chars().filter(|&c| c == '\n'));
    };
    while i < b.len() {
        let from = i;
        if src[i..].starts_with("//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if src[i..].starts_with("/*") {
            i += src[i..].find("*/").map_or(b.len() - i, |e| e + 2);
        } else if let Some(len) = char_literal(&src[i..]) {
            i += len;
        } else if let Some(len) = raw_string(&src[i..]) {
            i += len;
            out.push_str("\"\"");
        } else if b[i] == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if drop_tests
            && src[i..].starts_with("#[cfg(test)]")
            && test_module_follows(&src[i + 12..])
        {
            i = skip_braced(src, i);
        } else {
            let c = src[i..].chars().next().unwrap();
            out.push(c);
            i += c.len_utf8();
            continue;
        }
        breaks(&src[from..i.min(b.len())], &mut out);
    }
    out
}

/// The length of a char literal at the start of `s` (`'x'`, `'\n'`, `'"'`), not a lifetime.
fn char_literal(s: &str) -> Option<usize> {
    let rest = s.strip_prefix('\'')?;
    let len = if rest.starts_with('\\') {
        2 + rest.get(2..)?.find('\'')?
    } else {
        rest.chars().next()?.len_utf8()
    };
    (rest[len..].starts_with('\'')).then_some(len + 2)
}

/// The length of a raw string at the start of `s` (`r"…"`, `r#"…"#`).
fn raw_string(s: &str) -> Option<usize> {
    let rest = s.strip_prefix('r')?;
    let hashes = rest.len() - rest.trim_start_matches('#').len();
    let body = rest[hashes..].strip_prefix('"')?;
    let close = format!("\"{}", "#".repeat(hashes));
    Some(1 + hashes + 1 + body.find(&close)? + close.len())
}

/// Whether what follows a `#[cfg(test)]` is a module (a unit-test block), not a single item.
fn test_module_follows(rest: &str) -> bool {
    let rest = rest.trim_start();
    rest.starts_with("mod ") || rest.starts_with("pub mod ") || rest.starts_with("pub(crate) mod ")
}

/// The index just past the brace block (or `;`) that starts after `from`.
pub(crate) fn skip_braced(src: &str, from: usize) -> usize {
    let b = src.as_bytes();
    let mut i = from;
    while i < b.len() && b[i] != b'{' && b[i] != b';' {
        i += 1;
    }
    if i < b.len() && b[i] == b';' {
        return i + 1;
    }
    let mut depth = 0usize;
    while i < b.len() {
        match b[i] {
            b'{' => depth += 1,
            b'}' => {
                depth -= 1;
                if depth == 0 {
                    return i + 1;
                }
            }
            _ => {}
        }
        i += 1;
    }
    b.len()
}

/// The rooms a piece of code names with `crate::room` or `crate::{room, …}`.
fn rooms_named(code: &str) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        let before = rest[..at].chars().next_back();
        rest = &rest[at + "crate::".len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$') {
            continue; // `$crate::` in a macro, or part of a longer name
        }
        if let Some(group) = rest.strip_prefix('{') {
            let end = skip_braced(rest, 0) - 1;
            let mut depth = 0;
            let mut item = String::new();
            for c in group[..end - 1].chars().chain([',']) {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        found.insert(ident(item.trim_start()));
                        item.clear();
                    }
                    _ => item.push(c),
                }
            }
        } else {
            found.insert(ident(rest));
        }
    }
    found.retain(|r| !r.is_empty() && r != "self");
    found
}

pub(crate) fn ident(s: &str) -> String {
    s.chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect()
}

/// The room of a source file: its first path component under `src/`.
fn room_of(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy();
    first.trim_end_matches(".rs").to_owned()
}

pub(crate) fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The crate root's re-exports (`pub use room::…::{Name, …};`): name → the room it comes from.
fn re_exports(lib: &str) -> BTreeMap<String, String> {
    let mut names = BTreeMap::new();
    for line in code_only(lib).lines() {
        let Some(path) = line.trim().strip_prefix("pub use ") else {
            continue;
        };
        let room = ident(path);
        for word in path.split(|c: char| !(c.is_alphanumeric() || c == '_')) {
            if word.starts_with(|c: char| c.is_ascii_uppercase()) {
                names.insert(word.to_owned(), room.clone());
            }
        }
    }
    names
}

/// The files compiled for tests only: declared as `#[cfg(test)] mod name;` (with or without a
/// `#[path]`), so their uses of other rooms are a test's, as in an inline test module.
pub(crate) fn test_only_files(files: &[PathBuf]) -> BTreeSet<PathBuf> {
    let mut found = BTreeSet::new();
    for file in files {
        let src = std::fs::read_to_string(file).unwrap();
        let dir = file.parent().unwrap();
        let front_door = file
            .file_name()
            .is_some_and(|n| n == "mod.rs" || n == "lib.rs" || n == "main.rs");
        let own = if front_door {
            dir.to_path_buf()
        } else {
            dir.join(file.file_stem().unwrap())
        };
        let mut rest = src.as_str();
        while let Some(at) = rest.find("#[cfg(test)]") {
            rest = rest[at + 12..].trim_start();
            let mut path = None;
            if let Some(attr) = rest.strip_prefix("#[path = \"") {
                let end = attr.find('"').unwrap_or(0);
                path = Some(dir.join(&attr[..end]));
                rest = attr[end..].trim_start_matches(['"', ']']).trim_start();
            }
            let Some(decl) = rest.strip_prefix("mod ") else {
                continue;
            };
            let name = ident(decl);
            if decl[name.len()..].trim_start().starts_with(';') {
                found.insert(path.unwrap_or_else(|| own.join(format!("{name}.rs"))));
            }
        }
    }
    found
}

/// Every `(room, used room, file)` in `src/` that the table does not allow.
fn violations(root: &Path, table: &BTreeMap<String, BTreeSet<String>>) -> Vec<String> {
    let src = root.join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let front_door = re_exports(&std::fs::read_to_string(src.join("lib.rs")).unwrap());
    let tests = test_only_files(&files);
    let mut bad = Vec::new();
    for file in files.into_iter().filter(|f| !tests.contains(f)) {
        let room = room_of(&src, &file);
        // The front door re-exports every room; the binary's crate (`main.rs`, `cli/`) has
        // `crate::` of its own and reaches the library as `halfcast::`.
        if matches!(room.as_str(), "lib" | "main" | "cli") {
            continue;
        }
        let Some(may) = table.get(&room) else {
            bad.push(format!(
                "{}: room `{room}` is not in the table",
                file.display()
            ));
            continue;
        };
        let code = code_only(&std::fs::read_to_string(&file).unwrap());
        for named in rooms_named(&code) {
            // `crate::Rgb` and the like go through the front door to the room that defines them.
            let used = front_door.get(&named).cloned().unwrap_or(named);
            if used != room && !may.contains(&used) {
                bad.push(format!("{}: `{room}` may not use `{used}`", file.display()));
            }
        }
    }
    bad
}

pub(crate) fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn table() -> BTreeMap<String, BTreeSet<String>> {
    allowed(&std::fs::read_to_string(root().join("docs/architecture.md")).unwrap())
}

#[test]
fn every_use_of_another_room_is_allowed_by_the_layer_table() {
    let table = table();
    assert!(table.len() >= 20, "the table was not read: {table:?}");
    let bad = violations(root(), &table);
    assert!(bad.is_empty(), "layering broken:\n{}", bad.join("\n"));
}

#[test]
fn the_layer_table_has_no_cycle() {
    let table = table();
    // Every room reaches only rooms below it: walk the uses and never come back.
    for start in table.keys() {
        let mut seen = BTreeSet::new();
        let mut todo: Vec<&String> = table[start].iter().collect();
        while let Some(r) = todo.pop() {
            assert_ne!(r, start, "`{start}` reaches itself through the table");
            assert!(table.contains_key(r), "`{r}` is used but has no row");
            if seen.insert(r.clone()) {
                todo.extend(table[r].iter());
            }
        }
    }
}

#[test]
fn a_forbidden_use_is_caught() {
    // A copy of src/ with one `use` that points up the layers: map may not use render.
    let dir = tempfile::tempdir().unwrap();
    copy_dir(&root().join("src"), &dir.path().join("src"));
    let parse = dir.path().join("src/map/parse.rs");
    let text = std::fs::read_to_string(&parse).unwrap();
    std::fs::write(
        &parse,
        format!("use crate::render::light::Lighting;\n{text}"),
    )
    .unwrap();
    let bad = violations(dir.path(), &table());
    assert_eq!(bad.len(), 1, "{bad:?}");
    assert!(bad[0].ends_with("`map` may not use `render`"), "{}", bad[0]);
}

#[test]
fn the_reader_sees_groups_and_skips_comments_strings_and_tests() {
    let code = code_only(
        "use crate::{map::Map, render::{cast, view::View}};\n\
         // crate::tui in a comment\n\
         let s = \"crate::serve\";\n\
         fn f() -> crate::color::Rgb { todo!() }\n\
         #[cfg(test)]\nmod tests { use crate::ui::layout; }\n",
    );
    let named: Vec<String> = rooms_named(&code).into_iter().collect();
    assert_eq!(named, ["color", "map", "render"]);
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        let dest = to.join(path.file_name().unwrap());
        if path.is_dir() {
            copy_dir(&path, &dest);
        } else {
            std::fs::copy(&path, &dest).unwrap();
        }
    }
}

/// Which of `serve`'s transports a file under `src/serve/` names (`crate::serve::ssh`, `…::web`).
fn transports_named(code: &str) -> BTreeSet<&'static str> {
    ["ssh", "web"]
        .into_iter()
        .filter(|t| {
            code.contains(&format!("crate::serve::{t}"))
                || code.contains(&format!("serve::{{{t}"))
                || code.contains(&format!("super::super::{t}"))
        })
        .collect()
}

#[test]
fn the_transports_go_through_the_one_way_in_and_never_use_each_other() {
    let serve = root().join("src/serve");
    let mut bad = Vec::new();
    for (dir, may) in [("ssh", "ssh"), ("web", "web"), ("edge", "")] {
        let mut files = Vec::new();
        rust_files(&serve.join(dir), &mut files);
        assert!(!files.is_empty(), "src/serve/{dir} has files");
        for file in files {
            let code = code_only(&std::fs::read_to_string(&file).unwrap());
            for t in transports_named(&code) {
                if t != may {
                    bad.push(format!(
                        "{}: `serve/{dir}` may not use `serve/{t}`",
                        file.display()
                    ));
                }
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
    assert_eq!(
        transports_named("use crate::serve::{web::x, edge};"),
        BTreeSet::from(["web"]),
        "the reader sees a group"
    );
}
