//! Issue 56: what the README's and docs' commands write, run from the repository's root as they
//! stand, is covered by `.gitignore`, so following the docs leaves `git status` clean.

use crate::common::root;
use crate::docs_commands::{all_docs, doc_commands};

/// Whether git ignores `path` (relative to the root) by the repository's ignore rules; `None`
/// when git cannot say (not installed).
fn ignored(path: &str) -> Option<bool> {
    let out = std::process::Command::new("git")
        .args(["check-ignore", "--no-index", "-q", path])
        .current_dir(root())
        .output()
        .ok()?;
    match out.status.code() {
        Some(0) => Some(true),
        Some(1) => Some(false),
        _ => None,
    }
}

#[test]
fn every_file_a_doc_command_writes_is_ignored_by_git() {
    if ignored("target/x").is_none() {
        println!("SKIPPED docs_outputs_ignored: git is not available here");
        return;
    }
    let mut checked = 0;
    let mut bad = Vec::new();
    for doc in all_docs() {
        for c in doc_commands(&doc) {
            let Some(out) = c.output() else { continue };
            // A template (`OUT`, `DIR`) or an absolute path names no file here.
            if out.starts_with('/') || out.chars().any(|ch| ch.is_ascii_uppercase()) {
                continue;
            }
            // A folder (`--out frames/`) is covered when a file in it is.
            let path = if out.ends_with('/') {
                format!("{out}frame-00000.png")
            } else {
                out.to_owned()
            };
            checked += 1;
            if ignored(&path) != Some(true) {
                bad.push(format!(
                    "{}: halfcast {} writes {out}",
                    c.place,
                    c.args.join(" ")
                ));
            }
        }
    }
    assert!(checked >= 10, "only {checked} outputs found");
    assert!(
        bad.is_empty(),
        "not covered by .gitignore:\n{}",
        bad.join("\n")
    );
}
