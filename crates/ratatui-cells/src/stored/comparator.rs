//! How insta compares a stored cells snapshot with a new one: the texts, then, when they
//! differ, the cells, so the failure can say which cells changed and what, and a stored
//! snapshot in one of ratatui's own forms (a `Buffer`'s `Debug`, a `TestBackend`'s `Display`)
//! can say whether it shows the same screen before it is migrated.

use std::cell::RefCell;

use insta::internals::SnapshotContents;
use insta::{Comparator, DefaultComparator, Snapshot};

use super::finding::{find, Finding};

thread_local! {
    /// The last finding on this thread, for the assertion to report after insta returns.
    static LAST: RefCell<Option<Finding>> = const { RefCell::new(None) };
}

/// Forgets the last finding (before an assertion).
pub(crate) fn clear() {
    LAST.with(|l| l.borrow_mut().take());
}

/// The last finding on this thread, if the last comparison failed.
pub(crate) fn take() -> Option<Finding> {
    LAST.with(|l| l.borrow_mut().take())
}

/// Compares cells snapshots for insta (set by the assertion for its own call only).
#[derive(Clone, Copy)]
pub(crate) struct CellsComparator;

/// A snapshot's text, as insta compares it (normalised), when it is text.
fn text_of(snapshot: &Snapshot) -> Option<String> {
    match snapshot.contents() {
        SnapshotContents::Text(text) => Some(text.to_string()),
        SnapshotContents::Binary(_) => None,
    }
}

impl Comparator for CellsComparator {
    fn matches(&self, reference: &Snapshot, test: &Snapshot) -> bool {
        let (Some(stored), Some(new)) = (text_of(reference), text_of(test)) else {
            return DefaultComparator.matches(reference, test);
        };
        if stored == new {
            return true;
        }
        let finding = find(&stored, &new);
        // Printed now, before insta prints its own summary and line diff: the cells first.
        println!("{}", finding.describe());
        LAST.with(|l| *l.borrow_mut() = Some(finding));
        false
    }

    fn matches_fully(&self, reference: &Snapshot, test: &Snapshot) -> bool {
        self.matches(reference, test) && DefaultComparator.matches_fully(reference, test)
    }

    fn dyn_clone(&self) -> Box<dyn Comparator> {
        Box::new(*self)
    }
}
