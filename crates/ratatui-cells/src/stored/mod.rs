//! Stored cells snapshots in insta's own workflow: [`crate::assert_cells_snapshot!`] hands
//! the cells text to `insta::assert_snapshot!`, which names, places, writes, reviews and
//! accepts the `.snap` file as it does any other, while this crate's comparator compares the
//! cells and the failure names the test's line with the cell diff first.

mod comparator;
mod finding;
mod quiet;

use crate::format::cells_text;
use crate::frame::TermFrame;

use comparator::CellsComparator;

/// How to accept a change, in insta's words.
const ACCEPT: &str =
    "if the new screen is right, accept it: `cargo insta review` (or `cargo insta accept`), or \
     run the tests with INSTA_UPDATE=always";

/// Asserts that a frame (a ratatui `Buffer` or `TestBackend`, owned or borrowed, or a
/// [`crate::TermFrame`]) equals its stored insta snapshot, cell by cell.
///
/// `assert_cells_snapshot!(&buffer)` names the snapshot after the test, as
/// `insta::assert_snapshot!(value)` does; `assert_cells_snapshot!("name", &buffer)` names it.
/// The value stored is the frame's [`crate::cells_text`], in a `.snap` file insta places,
/// names, writes and reviews as it does every snapshot: `INSTA_UPDATE`, `cargo insta review`,
/// `cargo insta accept`, `cargo insta test --unreferenced=reject` and insta's settings
/// (`insta::Settings`, `insta::with_settings!`) all apply.
///
/// A stored snapshot of ratatui's own forms, `insta::assert_debug_snapshot!(buffer)` (a
/// `Buffer`'s `Debug`) or `insta::assert_snapshot!(terminal.backend())` (a `TestBackend`'s
/// `Display`, glyphs only), is compared as the cells it shows and fails until accepted as
/// cells text: one run with `INSTA_UPDATE=always` migrates a suite.
///
/// # Panics
/// When the frame does not match: at the line of the test, after printing the cell diff
/// (the count, then each differing cell with what changed) ahead of insta's own summary;
/// insta decides, as always, whether a `.snap.new` is written or the snapshot updated.
///
/// ```no_run
/// use ratatui::backend::TestBackend;
/// use ratatui::Terminal;
/// use ratatui_cells::assert_cells_snapshot;
///
/// let mut terminal = Terminal::new(TestBackend::new(20, 3)).unwrap();
/// terminal.draw(|frame| frame.render_widget("ready", frame.area())).unwrap();
/// assert_cells_snapshot!("status_line", terminal.backend());
/// ```
#[macro_export]
macro_rules! assert_cells_snapshot {
    ($frame:expr $(,)?) => {
        $crate::__private::check_snapshot($frame, |text: &str| {
            $crate::__private::insta::assert_snapshot!(
                $crate::__private::insta::internals::AutoName,
                text,
                stringify!($frame)
            )
        })
    };
    ($name:expr, $frame:expr $(,)?) => {
        $crate::__private::check_snapshot($frame, |text: &str| {
            $crate::__private::insta::assert_snapshot!($name, text, stringify!($frame))
        })
    };
}

/// What [`crate::assert_cells_snapshot!`] calls: `assert` is insta's assertion of the cells
/// text, expanded at the caller's line; it runs with this crate's comparator, and a failure
/// is raised again here, at the caller's line.
#[track_caller]
pub fn check_snapshot(frame: impl Into<TermFrame>, assert: impl FnOnce(&str)) {
    let text = cells_text(frame.into());
    let mut settings = insta::Settings::clone_current();
    settings.set_comparator(Box::new(CellsComparator));
    comparator::clear();
    let outcome = quiet::catch_quietly(|| settings.bind(|| assert(&text)));
    let finding = comparator::take();
    if let Err(insta_says) = outcome {
        let why = match &finding {
            Some(finding) => finding.headline(),
            None => "no stored snapshot to compare (a new snapshot is stored once accepted)".into(),
        };
        panic!("{insta_says}: {why}\n{ACCEPT}");
    }
}
