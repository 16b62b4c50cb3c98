//! Issue 48: the byte figures docs/output.md and docs/colour.md quote from `halfcast bench` are
//! what it prints. Bytes are deterministic (the same frames always encode to the same bytes);
//! times are not, so the encode times in the docs are quoted as measured and never checked.

use serde_json::Value;

use crate::common::halfcast_ok;
use crate::docs_commands::read_doc;

/// One row of output.md's bytes-per-frame table.
#[derive(Debug)]
struct Row {
    scene: String,
    colours: String,
    bytes: f64,
    vs_ratatui: f64,
    zlib: f64,
}

/// A table cell as a number: `335 905` → 335905, `74.1 %` → 74.1.
fn cell_number(cell: &str) -> f64 {
    let digits: String = cell
        .chars()
        .filter(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    digits
        .parse()
        .unwrap_or_else(|_| panic!("not a number: {cell:?}"))
}

/// The rows of the table under "## Bytes per frame" in output.md.
fn table_rows() -> Vec<Row> {
    let doc = read_doc("docs/output.md");
    let section = doc.split("## Bytes per frame").nth(1).expect("the section");
    let section = section.split("\n## ").next().unwrap();
    assert!(section.contains("Figures at 240×68 cells, 60 frames per path"));
    section
        .lines()
        .filter_map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let scene = *cells.get(1)?;
            ["turn", "walk", "flat"].contains(&scene).then(|| Row {
                scene: scene.to_owned(),
                colours: cells[2].to_owned(),
                bytes: cell_number(cells[3]),
                vs_ratatui: cell_number(cells[4]),
                zlib: cell_number(cells[5]),
            })
        })
        .collect()
}

/// Every run of `halfcast bench --bytes-only --json` (the default paths, sizes and levels).
fn bench_runs() -> Vec<Value> {
    let out = halfcast_ok(&["bench", "--bytes-only", "--json"]);
    let report: Value = serde_json::from_slice(&out.stdout).unwrap();
    report["runs"].as_array().unwrap().clone()
}

fn f(v: &Value, path: &[&str]) -> f64 {
    path.iter().fold(v, |v, k| &v[*k]).as_f64().unwrap()
}

/// `x` as the docs print a percentage or a ratio: one decimal.
fn one(x: f64) -> String {
    format!("{x:.1}")
}

/// The mean share of stock ratatui's truecolor bytes, in %, over the runs at `colours`.
fn mean_share(runs: &[Value], colours: &str) -> f64 {
    let shares: Vec<f64> = runs
        .iter()
        .filter(|r| r["colors"] == colours)
        .map(|r| 100.0 * f(r, &["ratio_vs_ratatui_truecolor"]))
        .collect();
    shares.iter().sum::<f64>() / shares.len() as f64
}

fn check_table(runs: &[Value]) {
    let rows = table_rows();
    assert!(rows.len() >= 8, "{rows:?}");
    for row in rows {
        let run = runs
            .iter()
            .find(|r| r["scene"] == row.scene.as_str() && r["colors"] == row.colours.as_str())
            .filter(|r| r["cols"] == 240 && r["rows"] == 68)
            .unwrap_or_else(|| panic!("no run for {row:?}"));
        let bytes = f(run, &["halfcast", "bytes_per_frame"]).round();
        let zlib = f(run, &["halfcast", "zlib_bytes_per_frame"]).round();
        let vs = one(100.0 * f(run, &["ratio_vs_ratatui_truecolor"]));
        assert_eq!(
            (row.bytes, one(row.vs_ratatui), row.zlib),
            (bytes, vs, zlib),
            "output.md's row {row:?} (bytes, vs ratatui, zlib) against bench"
        );
    }
}

fn check_summaries(runs: &[Value]) {
    let shares: Vec<String> = ["truecolor", "256", "16"]
        .iter()
        .map(|c| one(mean_share(runs, c)))
        .collect();
    let zlib: Vec<f64> = runs
        .iter()
        .map(|r| {
            f(r, &["halfcast", "bytes_per_frame"]) / f(r, &["halfcast", "zlib_bytes_per_frame"])
        })
        .collect();
    let (lo, hi) = zlib
        .iter()
        .fold((f64::MAX, 0f64), |(a, b), z| (a.min(*z), b.max(*z)));
    let output = read_doc("docs/output.md");
    let summary = format!(
        "halfcast sends {} % of stock ratatui's truecolor bytes at truecolor, {} % at 256 colours and \
         {} % at 16 colours, and zlib shrinks each stream another {}–{}×",
        shares[0],
        shares[1],
        shares[2],
        one(lo),
        one(hi)
    );
    let flat = output.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(flat.contains(&summary), "output.md should say: {summary}");
    // colour.md quotes the 256-colour share and its range over the six runs.
    let per_run: Vec<f64> = runs
        .iter()
        .filter(|r| r["colors"] == "256")
        .map(|r| 100.0 * f(r, &["ratio_vs_ratatui_truecolor"]))
        .collect();
    let (lo, hi) = per_run
        .iter()
        .fold((f64::MAX, 0f64), |(a, b), z| (a.min(*z), b.max(*z)));
    let quote = format!(
        "256 colours send {} % of stock ratatui's truecolor bytes over `halfcast bench`'s paths \
         (mean of its six runs; {}–{} % per run)",
        shares[1],
        one(lo),
        one(hi)
    );
    let colour = read_doc("docs/colour.md");
    let flat = colour.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(flat.contains(&quote), "colour.md should say: {quote}");
}

#[test]
fn the_byte_figures_the_docs_quote_are_what_bench_prints() {
    let runs = bench_runs();
    check_table(&runs);
    check_summaries(&runs);
}
