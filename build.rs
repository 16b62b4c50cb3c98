//! Nothing to build: this script exists so Cargo.toml's `[build-dependencies]` (a feature of syn
//! that keeps every feature combination on one build of syn) is read. See Cargo.toml.

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
}
