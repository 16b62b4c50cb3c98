//! Two jobs. The git commit this is built from goes into the binary as `HALFCAST_COMMIT` (the
//! `commit` label of `halfcast_build_info`): the `HALFCAST_COMMIT` environment variable if the
//! builder sets one (a packager building from a tarball), else `git rev-parse HEAD` when the
//! crate's own directory is a git checkout, else "unknown" (a crates.io package has no `.git`;
//! a package unpacked inside some other repository must not take that repository's commit).
//! And Cargo.toml's `[build-dependencies]` (a feature of syn that keeps every feature
//! combination on one build of syn) is read because a build script exists. See Cargo.toml.

use std::path::Path;
use std::process::Command;

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-env-changed=HALFCAST_COMMIT");
    let commit = std::env::var("HALFCAST_COMMIT")
        .ok()
        .filter(|c| !c.is_empty())
        .or_else(git_commit)
        .unwrap_or_else(|| "unknown".into());
    println!("cargo::rustc-env=HALFCAST_COMMIT={commit}");
}

/// The checked-out commit, when this crate's directory is the top of a git work tree; the
/// files that change with it are watched, so a new commit rebuilds with its own hash.
fn git_commit() -> Option<String> {
    let dir = std::env::var("CARGO_MANIFEST_DIR").ok()?;
    if !Path::new(&dir).join(".git").exists() {
        return None;
    }
    let git = |args: &[&str]| -> Option<String> {
        let out = Command::new("git")
            .arg("-C")
            .arg(&dir)
            .args(args)
            .output()
            .ok()?;
        out.status
            .success()
            .then(|| String::from_utf8_lossy(&out.stdout).trim().to_owned())
    };
    let commit = git(&["rev-parse", "HEAD"])?;
    let mut watched = vec![git(&["rev-parse", "--git-path", "HEAD"])?];
    if let Some(branch) = git(&["symbolic-ref", "-q", "HEAD"]) {
        watched.extend(git(&["rev-parse", "--git-path", &branch]));
    }
    watched.extend(git(&["rev-parse", "--git-path", "packed-refs"]));
    for path in watched {
        let path = Path::new(&dir).join(path);
        if path.exists() {
            println!("cargo::rerun-if-changed={}", path.display());
        }
    }
    (commit.len() == 40 && commit.bytes().all(|b| b.is_ascii_hexdigit())).then_some(commit)
}
