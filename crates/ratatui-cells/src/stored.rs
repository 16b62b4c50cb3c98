//! Checking a frame against a snapshot file: the cells text stored on disk, compared cell by
//! cell, the cell diff printed on failure. Existing insta snapshots of a buffer's `Debug` form
//! read too, so moving to this assertion is one run with the update switch.

use std::path::Path;

use crate::diff::diff;
use crate::frame::TermFrame;
use crate::limits::MAX_FRAME_BYTES;
use crate::parse::{insta_body, parse_frame};
use crate::text::to_cells_text;
use crate::update::{update_requested, UPDATE_ENV};

/// Asserts that a frame (a ratatui `Buffer`, owned or borrowed, or a [`crate::TermFrame`])
/// equals the snapshot stored at a path relative to the calling crate's manifest directory,
/// strictly ([`crate::diff`]). The file is insta's `.snap` form (a header, then the cells
/// text), so an insta snapshot of the same screen, in cells text or as a buffer's `Debug`, is
/// read as it is.
///
/// With [`crate::UPDATE_ENV`] (`RATATUI_CELLS_UPDATE=1`) set, the file is written instead
/// whenever its contents are not the frame's cells text (a new snapshot, a change, or a
/// `Debug` snapshot to migrate); without it nothing is ever written.
///
/// In a test, `assert_cells_snapshot!("tests/snapshots/status_bar.snap", &buffer)`; here,
/// against a file this example writes first, as an earlier run with the switch would have:
///
/// ```
/// use ratatui::buffer::Buffer;
/// use ratatui::layout::Rect;
/// use ratatui_cells::{assert_cells_snapshot, cells_text};
///
/// let mut buffer = Buffer::empty(Rect::new(0, 0, 4, 1));
/// buffer.set_string(0, 0, "ok", ratatui::style::Style::new().bold());
/// let path = std::env::temp_dir().join(format!("ratatui-cells-doc-{}.snap", std::process::id()));
/// std::fs::write(&path, cells_text(&buffer)).unwrap();
/// assert_cells_snapshot!(&path, &buffer);
///
/// buffer.set_string(0, 0, "no", ratatui::style::Style::new().bold());
/// if !ratatui_cells::update_requested() {
///     let failed = std::panic::catch_unwind(|| assert_cells_snapshot!(&path, &buffer)).unwrap_err();
///     let message = failed.downcast_ref::<String>().unwrap();
///     assert!(message.contains(r#"cell (0,0) glyph: "o" bold -> "n" bold"#), "{message}");
/// }
/// std::fs::remove_file(&path).unwrap();
/// ```
#[macro_export]
macro_rules! assert_cells_snapshot {
    ($path:expr, $frame:expr $(,)?) => {
        $crate::check_stored_snapshot(
            ::std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join($path),
            $frame,
            stringify!($frame),
        )
    };
}

/// What [`assert_cells_snapshot!`] calls: `frame` against the snapshot at `path`
/// (`expression` names the frame in a file it writes).
///
/// # Panics
/// When the snapshot is missing (saying how to create it), unreadable, or differs (with the
/// cell diff), unless the update switch is set; then when the file cannot be written.
#[track_caller]
pub fn check_stored_snapshot(
    path: impl AsRef<Path>,
    frame: impl Into<TermFrame>,
    expression: &str,
) {
    check(path.as_ref(), &frame.into(), expression, update_requested());
}

/// [`check_stored_snapshot`] with the switch given.
#[track_caller]
fn check(path: &Path, frame: &TermFrame, expression: &str, update: bool) {
    let text = to_cells_text(frame);
    let stored = read_capped(path);
    if update {
        let current = stored.as_deref().ok().map(|s| insta_body(s).unwrap_or(s));
        if current != Some(text.as_str()) {
            write(path, &text, expression);
        }
        return;
    }
    let stored = stored.unwrap_or_else(|e| {
        panic!(
            "no readable snapshot at {} ({e}): run the test once with {UPDATE_ENV}=1 to write \
             it from this frame, review it, and commit it",
            path.display()
        )
    });
    let (want, _) = parse_frame(stored.as_bytes())
        .unwrap_or_else(|e| panic!("snapshot {} does not read: {e}", path.display()));
    let report = diff(&want, frame);
    if !report.is_equal() {
        panic!(
            "frame differs from the snapshot {} (stored -> actual):\n{}if the change is \
             intended, run with {UPDATE_ENV}=1 and review the file's diff",
            path.display(),
            report.summary()
        );
    }
}

/// The file's text, refusing what is too large to be a snapshot.
fn read_capped(path: &Path) -> Result<String, String> {
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if meta.len() > MAX_FRAME_BYTES {
        return Err(format!(
            "{} bytes, over the limit of {MAX_FRAME_BYTES}",
            meta.len()
        ));
    }
    std::fs::read_to_string(path).map_err(|e| e.to_string())
}

/// Writes the snapshot in insta's `.snap` form.
#[track_caller]
fn write(path: &Path, text: &str, expression: &str) {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)
            .unwrap_or_else(|e| panic!("cannot create {}: {e}", dir.display()));
    }
    let source = std::panic::Location::caller().file();
    let expression = expression.replace('\n', " ");
    let contents = format!("---\nsource: {source}\nexpression: {expression}\n---\n{text}");
    std::fs::write(path, contents)
        .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui_core::buffer::Buffer;
    use ratatui_core::layout::Rect;
    use ratatui_core::style::{Color, Style};

    /// A folder of this test's own under the system's temporary folder.
    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("ratatui-cells-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn buffer(text: &str) -> Buffer {
        let mut b = Buffer::empty(Rect::new(0, 0, 6, 1));
        b.set_string(0, 0, text, Style::new().fg(Color::Indexed(99)));
        b
    }

    fn panic_message(f: impl FnOnce() + std::panic::UnwindSafe) -> String {
        let payload = std::panic::catch_unwind(f).unwrap_err();
        payload
            .downcast_ref::<String>()
            .cloned()
            .unwrap_or_default()
    }

    #[test]
    fn without_the_switch_a_failure_writes_nothing() {
        let dir = scratch("nowrite");
        let path = dir.join("screen.snap");
        let frame = TermFrame::from(buffer("ok"));
        let missing = panic_message(|| check(&path, &frame, "buffer", false));
        assert!(missing.contains("RATATUI_CELLS_UPDATE=1"), "{missing}");
        assert!(!path.exists());
        std::fs::write(&path, to_cells_text(&TermFrame::from(buffer("no")))).unwrap();
        let differs = panic_message(|| check(&path, &frame, "buffer", false));
        assert!(
            differs.contains("2 differ")
                && differs.contains(r#"cell (0,0) glyph: "n" fg=idx99 -> "o" fg=idx99"#),
            "{differs}"
        );
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(names, ["screen.snap"]);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn the_switch_writes_new_and_changed_snapshots_and_migrates_debug_ones() {
        let dir = scratch("update");
        let path = dir.join("deep/screen.snap");
        let frame = TermFrame::from(buffer("ok"));
        check(&path, &frame, "buffer", true);
        let written = std::fs::read_to_string(&path).unwrap();
        assert!(written.starts_with("---\nsource: "), "{written}");
        assert!(
            written
                .ends_with("---\nhalfcast-cells v2 6x1\n\"ok    \"\nstyles:\ny0 x0-1 fg=idx99\n"),
            "{written}"
        );
        check(&path, &frame, "buffer", false);
        // An insta Debug snapshot of the same screen passes as it is, and the switch rewrites it.
        let debug = format!(
            "---\nsource: tests/ui.rs\nexpression: buffer\n---\n{:#?}\n",
            buffer("ok")
        );
        std::fs::write(&path, &debug).unwrap();
        check(&path, &frame, "buffer", false);
        assert_eq!(std::fs::read_to_string(&path).unwrap(), debug);
        check(&path, &frame, "buffer", true);
        assert_eq!(std::fs::read_to_string(&path).unwrap(), written);
        std::fs::remove_dir_all(dir).unwrap();
    }
}
