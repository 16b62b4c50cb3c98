//! Issue 56: `bench --bytes-only` times nothing twice, so its table has no timing columns (and
//! the glyph bench, all timings, is refused with it).

use crate::common::{halfcast, halfcast_ok};

#[test]
fn the_bytes_only_table_has_no_timing_columns() {
    let out = halfcast_ok(&[
        "bench",
        "--bytes-only",
        "--frame-count",
        "2",
        "--colors",
        "256",
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    let header = text.lines().next().unwrap();
    let columns: Vec<&str> = header.split(['|', ' ']).filter(|w| !w.is_empty()).collect();
    assert!(!text.contains(" ms"), "{text}");
    assert!(!text.contains("S-CIELAB"), "{text}");
    for column in ["B/frame", "zlib", "vs", "rat", "frames"] {
        assert!(columns.contains(&column), "{header}");
    }
    // Every row has a figure under every column: nothing left blank where a time was.
    for row in text.lines().skip(1).filter(|l| l.contains('|')) {
        let cells = row.split(['|', ' ']).filter(|w| !w.is_empty()).count();
        assert_eq!(cells, 11, "{row}");
    }
    let out = halfcast(&["bench", "--bytes-only", "--glyphs"]);
    assert_eq!(out.status.code(), Some(2));
}
