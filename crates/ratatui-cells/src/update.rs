//! The one switch that rewrites stored snapshots instead of comparing them.

/// Set this environment variable to `1` (any value but `0` or empty) to write stored snapshots
/// ([`crate::assert_cells_snapshot!`]) from the frames a test run makes instead of comparing
/// them. Tools built on this crate use it for their own stored files too (halfcast's PNG
/// goldens), so one switch updates every kind. Nothing else ever writes a snapshot file.
pub const UPDATE_ENV: &str = "RATATUI_CELLS_UPDATE";

/// Whether [`UPDATE_ENV`] asks for stored snapshots to be rewritten.
#[must_use]
pub fn update_requested() -> bool {
    std::env::var_os(UPDATE_ENV).is_some_and(|v| !v.is_empty() && v != "0")
}
