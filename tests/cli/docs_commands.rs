//! Issue 48: every `halfcast` command the README and docs/ give that writes a file runs as
//! written (from a scratch folder, reading the repository's maps and fixtures) and writes what it
//! names. The figures quoted beside some of them are checked in `docs_dda` and `docs_bench`,
//! which use the parsing here.

use std::path::Path;
use std::process::{Command, Output};

use crate::common::root;

/// One `halfcast …` command from a doc's `sh` block: where it is and its words (the comment
/// after `#` dropped; `a && b` gives two commands).
#[derive(Debug, Clone)]
pub struct DocCommand {
    /// `README.md:68`, for failure messages.
    pub place: String,
    /// The words after `halfcast`.
    pub args: Vec<String>,
}

impl DocCommand {
    /// The value after `flag` (`--size` → `80x24`), if the command has it.
    pub fn value(&self, flag: &str) -> Option<&str> {
        let at = self.args.iter().position(|a| a == flag)?;
        self.args.get(at + 1).map(String::as_str)
    }

    /// The file or folder the command writes (`-o`, `--out`), if any.
    pub fn output(&self) -> Option<&str> {
        self.value("-o").or_else(|| self.value("--out"))
    }

    /// Runs the command with `dir` as the current folder; arguments naming a file or folder of
    /// the repository (maps/…, tests/fixtures/…) are given as absolute paths.
    pub fn run_in(&self, dir: &Path) -> Output {
        let args: Vec<String> = self
            .args
            .iter()
            .map(|a| {
                let p = root().join(a);
                let in_repo = !a.starts_with('-') && a.contains('/') && p.exists();
                if in_repo {
                    p.display().to_string()
                } else {
                    a.clone()
                }
            })
            .collect();
        Command::new(env!("CARGO_BIN_EXE_halfcast"))
            .args(&args)
            .current_dir(dir)
            .stdin(std::process::Stdio::null())
            .output()
            .expect("run halfcast")
    }
}

/// The text of `doc` (a path from the repository root, such as `docs/output.md`).
pub fn read_doc(doc: &str) -> String {
    std::fs::read_to_string(root().join(doc)).unwrap_or_else(|e| panic!("{doc}: {e}"))
}

/// Every `halfcast …` command in `doc`'s ```` ```sh ```` blocks, in order.
pub fn doc_commands(doc: &str) -> Vec<DocCommand> {
    let mut out = Vec::new();
    let mut in_sh = false;
    for (n, line) in read_doc(doc).lines().enumerate() {
        let t = line.trim();
        if t.starts_with("```") {
            in_sh = !in_sh && t == "```sh";
            continue;
        }
        if !in_sh {
            continue;
        }
        let code = t.split(" #").next().unwrap_or("");
        for part in code.split("&&") {
            let mut words = part.split_whitespace().map(str::to_owned);
            if words.next().as_deref() == Some("halfcast") {
                out.push(DocCommand {
                    place: format!("{doc}:{}", n + 1),
                    args: words.collect(),
                });
            }
        }
    }
    out
}

/// Whether a command is a template (`--frames DIR`, `[MAP]`, `png|ansi`) rather than one to
/// type as it stands.
fn is_template(c: &DocCommand) -> bool {
    c.args.iter().any(|a| {
        let upper = a
            .as_bytes()
            .windows(2)
            .any(|w| w[0].is_ascii_uppercase() && w[1].is_ascii_uppercase());
        upper || a.contains(['[', '|', '…'])
    })
}

/// The README's and docs' commands that write a file, runnable as written: not templates and
/// not `record` (it plays in a terminal first).
pub fn file_commands(doc: &str) -> Vec<DocCommand> {
    doc_commands(doc)
        .into_iter()
        .filter(|c| c.output().is_some() && !is_template(c))
        .filter(|c| c.args.first().is_some_and(|a| a != "record"))
        .collect()
}

/// The README and every doc in docs/.
pub fn all_docs() -> Vec<String> {
    let mut docs: Vec<String> = std::fs::read_dir(root().join("docs"))
        .expect("docs/")
        .filter_map(|e| {
            let name = e.ok()?.file_name().into_string().ok()?;
            name.ends_with(".md").then(|| format!("docs/{name}"))
        })
        .collect();
    docs.sort();
    docs.insert(0, "README.md".to_owned());
    docs
}

/// The exit codes a doc's command may end with: `diff` of two different frames exits 1, as its
/// comment in the docs says; everything else 0.
fn expected_codes(c: &DocCommand) -> &'static [i32] {
    if c.args.first().map(String::as_str) == Some("diff") {
        &[0, 1]
    } else {
        &[0]
    }
}

#[test]
fn every_doc_command_that_writes_a_file_runs_as_written() {
    let mut ran = 0;
    for doc in all_docs() {
        // One scratch folder per doc: a command may read what an earlier one wrote (diff).
        let dir = tempfile::tempdir().unwrap();
        for c in file_commands(&doc) {
            let out = c.run_in(dir.path());
            let code = out.status.code().unwrap_or(-1);
            assert!(
                expected_codes(&c).contains(&code),
                "{}: halfcast {} exited {code}: {}",
                c.place,
                c.args.join(" "),
                String::from_utf8_lossy(&out.stderr)
            );
            let written = dir.path().join(c.output().unwrap());
            assert!(
                written.exists(),
                "{}: wrote no {}",
                c.place,
                written.display()
            );
            ran += 1;
        }
    }
    // The README alone has six (trace, two renders, replay, two renders and a diff).
    assert!(ran >= 10, "only {ran} commands found");
}
