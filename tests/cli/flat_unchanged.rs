//! A map without `Hz` lines renders byte-identical to before variable heights existed (issue 14):
//! `render` output (PNG, ANSI at two colour levels, JSON) of the default map and of public cub3D
//! maps is pinned by a hash of its bytes, recorded from the build before heights
//! (`tests/fixtures/flat_outputs.txt`, written by `HALFCAST_WRITE_FLAT_HASHES=1` on commit
//! c716e55, the last before heights were drawn). The `ansi256` lines were re-pinned twice since,
//! when surface-anchored dithering changed every rendered 256-colour frame on purpose (issue 12),
//! and again when its lattice went to quarter-octave levels and its matrix to dashes, a third
//! time for per-pixel mixes (issue 20), a fourth when those mixes began charging two hues side
//! by side (issue 20, shipped tables), and a fifth when the mixes of pixels no surface wrote a
//! pattern for (floors, ceilings) began charging each pixel's own colour error (issue 20: no
//! orange stripes on warm floors); the PNG, truecolor and JSON lines are still those of c716e55,
//! but for `default-fog-down`: its pose was inside a wall block (cell 20,4), which `render`
//! refuses since issue 56, so it moved to the open cell north of it and its four lines were
//! pinned from that build.

use crate::common;

use common::{halfcast_ok, root, shared_dir};

/// The renders pinned: a name and the `render` arguments (maps under `corpus/` come from
/// `../shared/corpus/cub3d/valid`).
const CASES: &[(&str, &[&str])] = &[
    ("default", &[]),
    (
        "default-pose",
        &[
            "--pos", "5.3,5.7", "--angle", "33", "--pitch", "12", "--z", "0.3", "--size", "61x17",
        ],
    ),
    (
        "default-night-doors",
        &[
            "--pos",
            "12.5,5.5",
            "--angle",
            "200",
            "--night",
            "--door-open",
            "0.4",
            "--time",
            "1.3",
            "--fov",
            "90",
        ],
    ),
    (
        "default-fog-down",
        &[
            "--pos",
            "20.5,3.5",
            "--angle",
            "-60",
            "--fog",
            "200,200,210,0.3",
            "--pitch",
            "-20",
            "--size",
            "97x23",
        ],
    ),
    (
        "corpus/LDuheron__Cub3D_map_perso_map_big.cub",
        &["--size", "80x24"],
    ),
    (
        "corpus/StephanHainthaler__cub3D_maps_valid_sus_map.cub",
        &["--size", "80x24"],
    ),
    (
        "corpus/t-ecker__42-Cub3d_maps_bonus_library.cub",
        &["--size", "80x24"],
    ),
];

const FORMATS: &[(&str, &[&str])] = &[
    ("png", &["--format", "png"]),
    ("ansi24", &["--format", "ansi", "--colors", "truecolor"]),
    ("ansi256", &["--format", "ansi", "--colors", "256"]),
    ("json", &["--format", "json"]),
];

/// FNV-1a, 64 bits: enough to tell outputs apart, and simple to recompute anywhere.
fn fnv64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

fn fixture() -> std::path::PathBuf {
    root().join("tests/fixtures/flat_outputs.txt")
}

/// Every case's output hash as `name format hash` lines (corpus cases only when ../shared is there).
fn hashes() -> Vec<String> {
    // HALFCAST_SHARED names ../shared where a worktree does not have it beside the project.
    let shared = std::env::var_os("HALFCAST_SHARED")
        .map(std::path::PathBuf::from)
        .or_else(|| shared_dir("flat_unchanged corpus cases"));
    let corpus = shared.map(|s| s.join("corpus/cub3d/valid"));
    let mut lines = Vec::new();
    for (name, args) in CASES {
        let mut all: Vec<String> = vec!["render".into()];
        if let Some(file) = name.strip_prefix("corpus/") {
            let Some(dir) = &corpus else { continue };
            all.push(dir.join(file).to_string_lossy().into_owned());
        }
        all.extend(args.iter().map(|s| (*s).to_owned()));
        for (fmt, fargs) in FORMATS {
            let mut a = all.clone();
            a.extend(fargs.iter().map(|s| (*s).to_owned()));
            let refs: Vec<&str> = a.iter().map(String::as_str).collect();
            let out = halfcast_ok(&refs);
            assert!(!out.stdout.is_empty(), "{name} {fmt}: no output");
            lines.push(format!("{name} {fmt} {:016x}", fnv64(&out.stdout)));
        }
    }
    lines
}

#[test]
fn flat_maps_render_byte_identical_to_before_heights() {
    let got = hashes();
    if std::env::var_os("HALFCAST_WRITE_FLAT_HASHES").is_some() {
        std::fs::write(fixture(), got.join("\n") + "\n").unwrap();
        return;
    }
    let want = std::fs::read_to_string(fixture()).unwrap();
    let want: Vec<&str> = want.lines().collect();
    for line in &got {
        let key: Vec<&str> = line.split(' ').take(2).collect();
        let expected = want
            .iter()
            .find(|w| w.split(' ').take(2).eq(key.iter().copied()))
            .unwrap_or_else(|| panic!("no pinned hash for {key:?}"));
        assert_eq!(line, expected, "output changed");
    }
    assert!(got.len() >= 16, "only {} outputs compared", got.len());
}
